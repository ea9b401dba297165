/* `asaa`: amortised supersampling AA (seed 000, sections 3.8 and 4.4.1, after Yang et al.). Four
 * sub-pixel buffers each hold the samples of one pixel quadrant; every frame renders one quadrant (plus a
 * small Gaussian jitter), updates that quadrant's buffer by tent reconstruction from all four and
 * exponential smoothing, and reconstructs the frame from the four buffers with a wider tent. Unlike the
 * thesis, history is reprojected with the velocity buffer, so moving objects are followed too. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "reference/reference.h"
#include "render/renderer.h"
#include "methods/jitter.h"
#include "types/method.h"
#include "util/halton.h"

static const struct aa_param_def asaa_params[] = {
	{.name = "max_samples", .type = AA_PARAM_INT, .def = 16, .min = 1, .max = 255,
	 .help = "cap on the per-pixel sample count N on still pixels (the thesis leaves it unbounded)"},
	{.name = "sigma", .type = AA_PARAM_FLOAT, .def = 0.066, .min = 0.0, .max = 0.25,
	 .help = "standard deviation in pixels of the Gaussian jitter added to the quadrant offset "
		 "(the thesis's code: 0.2575^2); a table of 16 offsets per buffer"},
	{.name = "final_radius", .type = AA_PARAM_FLOAT, .def = 1.0, .min = 0.5, .max = 1.0,
	 .help = "tent radius of the frame reconstruction in pixels (thesis: twice the buffer update's 0.5; "
		 "0.5 gives the box of the four quadrant samples)"},
	{.name = "prime", .type = AA_PARAM_BOOL, .def = 1, .min = 0, .max = 1,
	 .help = "after a camera cut render all four quadrants at once, so the first frame is not aliased "
		 "(not in the thesis; costs four scene renders on that frame)"},
	{.name = "tonemapped_resolve", .type = AA_PARAM_BOOL, .def = 0, .min = 0, .max = 1,
	 .help = "weight every colour the buffer update and the frame reconstruction sum or blend by Karis' "
		 "1/(1+luma), so one HDR sample cannot dominate"},
};

enum { SRC_CURRENT, SRC_VELOCITY, SRC_SURFACE, SRC_BUFFERS, SRC_MOTION_A, SRC_MOTION_B, DST_UPDATED,
       DST_FRAME, DST_MOTION_A, DST_MOTION_B, BINDINGS };

struct aa_method_state {
	struct aa_renderer *r;
	float max_samples, sigma, final_radius;
	bool prime, reset_pending;
	bool tonemapped_resolve;          /* Karis-weighted sums and blends */
	int valid_ages;                   /* buffers written since the last reset, at most 4 */
	int parity;                       /* motion[parity] holds last frame's displacements */
	struct aa_scene_target scene;     /* G-buffer: colour, velocity, linear depth */
	struct aa_gpu_image buffers[4];   /* RGBA16F: rgb, linear depth of the sample */
	struct aa_gpu_image updated;      /* the buffer being updated, copied into buffers[index] */
	struct aa_gpu_image frame;        /* the output */
	struct aa_gpu_image motion_a[2], motion_b[2]; /* RGBA16F displacements + count, ping-pong */
	struct aa_gpu_pipeline pipeline;
	VkDescriptorPool pool;
	VkDescriptorSet sets[2];          /* [i] reads motion[i], writes motion[1 - i] */
};

struct asaa_push {
	float quadrant[4][4];
	int32_t size[2];
	int32_t index, valid_ages;
	float max_samples, motion_samples, final_radius;
	int32_t still, tonemapped_resolve;
};

static void asaa_destroy(struct aa_method_state *s)
{
	struct aa_gpu *gpu = s->r->gpu;
	if (s->pool)
		vkDestroyDescriptorPool(gpu->device, s->pool, NULL);
	aa_gpu_pipeline_destroy(gpu, &s->pipeline);
	for (int i = 0; i < 4; i++)
		aa_gpu_image_destroy(gpu, &s->buffers[i]);
	for (int i = 0; i < 2; i++) {
		aa_gpu_image_destroy(gpu, &s->motion_a[i]);
		aa_gpu_image_destroy(gpu, &s->motion_b[i]);
	}
	aa_gpu_image_destroy(gpu, &s->updated);
	aa_gpu_image_destroy(gpu, &s->frame);
	aa_scene_target_destroy(s->r, &s->scene);
	free(s);
}

static int create_images(struct aa_renderer *r, struct aa_method_state *s, struct aa_method_result *info,
			 struct aa_error *err)
{
	const VkFormat f16 = VK_FORMAT_R16G16B16A16_SFLOAT;
	const VkImageUsageFlags rw = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
	struct aa_scene_target_desc d = {.samples = 1, .outputs = AA_OUT_VELOCITY | AA_OUT_SURFACE};
	if (aa_scene_target_create_desc(r, &s->scene, r->width, r->height, &d, "scene", info, err))
		return -1;
	char name[48];
	for (int i = 0; i < 4; i++) {
		snprintf(name, sizeof name, "sub-pixel buffer %d (RGBA16F)", i);
		if (aa_renderer_image_create(r, &s->buffers[i], r->width, r->height, f16,
					     VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, name, info, err))
			return -1;
	}
	for (int i = 0; i < 2; i++) {
		snprintf(name, sizeof name, "displacement 1-2 %d (RGBA16F)", i);
		if (aa_renderer_image_create(r, &s->motion_a[i], r->width, r->height, f16, rw, name, info, err))
			return -1;
		snprintf(name, sizeof name, "displacement 3 + count %d", i);
		if (aa_renderer_image_create(r, &s->motion_b[i], r->width, r->height, f16, rw, name, info, err))
			return -1;
	}
	return aa_renderer_image_create(r, &s->updated, r->width, r->height, f16,
					rw | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, "updated buffer (RGBA16F)", info, err) ||
	       aa_renderer_image_create(r, &s->frame, r->width, r->height, f16,
					rw | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, "frame (RGBA16F)", info, err);
}

/* One compute pipeline whose set binds the four buffers as an array (more bindings than the shared
 * compute-pass helper takes), with two sets for the ping-ponged displacement images. */
static int create_pipeline(struct aa_renderer *r, struct aa_method_state *s, struct aa_error *err)
{
	struct aa_gpu *gpu = r->gpu;
	VkDescriptorType types[BINDINGS];
	uint32_t counts[BINDINGS];
	for (int i = 0; i < BINDINGS; i++) {
		types[i] = i < DST_UPDATED ? VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER
					   : VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
		counts[i] = i == SRC_BUFFERS ? 4 : 1;
	}
	if (aa_gpu_layout_create(gpu, types, counts, BINDINGS, sizeof(struct asaa_push), &s->pipeline, err) ||
	    aa_gpu_compute_pipeline_create(gpu, "asaa.comp", &s->pipeline, err) ||
	    aa_gpu_descriptor_pool_create(gpu, 2, &s->pool, err))
		return -1;
	const VkImageLayout ro = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
	const VkDescriptorType cis = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
	const VkDescriptorType st = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
	for (int i = 0; i < 2; i++) {
		VkDescriptorSet set;
		if (aa_gpu_descriptor_set_alloc(gpu, s->pool, &s->pipeline, &set, err))
			return -1;
		s->sets[i] = set;
		aa_gpu_write_image(gpu, set, SRC_CURRENT, 0, cis, gpu->sampler_nearest, s->scene.output, ro);
		aa_gpu_write_image(gpu, set, SRC_VELOCITY, 0, cis, gpu->sampler_nearest, &s->scene.extra[0], ro);
		aa_gpu_write_image(gpu, set, SRC_SURFACE, 0, cis, gpu->sampler_nearest, &s->scene.extra[4], ro);
		for (uint32_t k = 0; k < 4; k++)
			aa_gpu_write_image(gpu, set, SRC_BUFFERS, k, cis, gpu->sampler_linear_clamp, &s->buffers[k], ro);
		aa_gpu_write_image(gpu, set, SRC_MOTION_A, 0, cis, gpu->sampler_nearest, &s->motion_a[i], ro);
		aa_gpu_write_image(gpu, set, SRC_MOTION_B, 0, cis, gpu->sampler_nearest, &s->motion_b[i], ro);
		aa_gpu_write_image(gpu, set, DST_UPDATED, 0, st, VK_NULL_HANDLE, &s->updated, VK_IMAGE_LAYOUT_GENERAL);
		aa_gpu_write_image(gpu, set, DST_FRAME, 0, st, VK_NULL_HANDLE, &s->frame, VK_IMAGE_LAYOUT_GENERAL);
		aa_gpu_write_image(gpu, set, DST_MOTION_A, 0, st, VK_NULL_HANDLE, &s->motion_a[1 - i],
				   VK_IMAGE_LAYOUT_GENERAL);
		aa_gpu_write_image(gpu, set, DST_MOTION_B, 0, st, VK_NULL_HANDLE, &s->motion_b[1 - i],
				   VK_IMAGE_LAYOUT_GENERAL);
	}
	return 0;
}

static int asaa_create(struct aa_renderer *r, const struct aa_method_params *p, struct aa_method_result *info,
		       struct aa_method_state **out, struct aa_error *err)
{
	struct aa_method_state *s = calloc(1, sizeof *s);
	if (!s)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	s->r = r;
	s->max_samples = (float)p->v[0];
	s->sigma = (float)p->v[1];
	s->final_radius = (float)p->v[2];
	s->prime = p->v[3] != 0;
	s->tonemapped_resolve = p->v[4] != 0;
	s->reset_pending = true;
	snprintf(info->path_taken, sizeof info->path_taken, "4 sub-pixel buffers, velocity reprojection%s%s",
		 s->prime ? ", primed after cuts" : "", s->tonemapped_resolve ? ", Karis-weighted resolve" : "");
	if (create_images(r, s, info, err) || create_pipeline(r, s, err)) {
		asaa_destroy(s);
		return -1;
	}
	*out = s;
	return 0;
}

/* One ASAA step: render quadrant `index` of frame `frame`, update its buffer and the frame. */
static void asaa_step(struct aa_method_state *s, struct aa_frame_ctx *ctx, int frame, bool still,
		      const char *scene_span)
{
	int index = frame & 3;
	float phi[2], g[2];
	aa_jitter_quadrant(index, phi);
	aa_jitter_gaussian(frame, s->sigma, g);
	int span = aa_gpu_timer_begin(ctx->cmd, ctx->timer, scene_span);
	/* pixel centre c then sees the scene at c + phi + g: buffer texel x holds the sample at x+0.5+phi */
	aa_renderer_draw_scene(s->r, ctx->cmd, &s->scene, -(phi[0] + g[0]), -(phi[1] + g[1]));
	aa_gpu_timer_end(ctx->cmd, ctx->timer, span);

	span = aa_gpu_timer_begin(ctx->cmd, ctx->timer, "asaa-resolve");
	struct asaa_push push = {
		.size = {ctx->width, ctx->height}, .index = index, .valid_ages = s->valid_ages,
		.max_samples = s->max_samples, .motion_samples = 4.0f, .final_radius = s->final_radius, .still = still,
		.tonemapped_resolve = s->tonemapped_resolve,
	};
	for (int k = 0; k < 4; k++)
		aa_jitter_quadrant(k, push.quadrant[k]);
	struct aa_gpu_image *sampled[] = {s->scene.output, &s->scene.extra[0], &s->scene.extra[4], &s->buffers[0],
					  &s->buffers[1], &s->buffers[2], &s->buffers[3], &s->motion_a[s->parity],
					  &s->motion_b[s->parity]};
	struct aa_gpu_image *storage[] = {&s->updated, &s->frame, &s->motion_a[1 - s->parity],
					  &s->motion_b[1 - s->parity]};
	for (size_t i = 0; i < sizeof sampled / sizeof sampled[0]; i++)
		if (sampled[i]->layout != VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
			aa_gpu_image_barrier(ctx->cmd, sampled[i], VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
	for (size_t i = 0; i < sizeof storage / sizeof storage[0]; i++)
		if (storage[i]->layout != VK_IMAGE_LAYOUT_GENERAL)
			aa_gpu_image_barrier(ctx->cmd, storage[i], VK_IMAGE_LAYOUT_GENERAL);
	aa_gpu_full_barrier(ctx->cmd);
	vkCmdBindPipeline(ctx->cmd, VK_PIPELINE_BIND_POINT_COMPUTE, s->pipeline.pipeline);
	vkCmdBindDescriptorSets(ctx->cmd, VK_PIPELINE_BIND_POINT_COMPUTE, s->pipeline.layout, 0, 1,
				&s->sets[s->parity], 0, NULL);
	vkCmdPushConstants(ctx->cmd, s->pipeline.layout, VK_SHADER_STAGE_ALL, 0, sizeof push, &push);
	vkCmdDispatch(ctx->cmd, (uint32_t)(ctx->width + 7) / 8, (uint32_t)(ctx->height + 7) / 8, 1);

	/* the updated buffer replaces buffer `index` (the shader read its old contents) */
	struct aa_gpu_image *dst = &s->buffers[index];
	aa_gpu_image_barrier(ctx->cmd, &s->updated, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
	aa_gpu_image_barrier(ctx->cmd, dst, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
	VkImageCopy region = {
		.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
		.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
		.extent = {(uint32_t)ctx->width, (uint32_t)ctx->height, 1},
	};
	vkCmdCopyImage(ctx->cmd, s->updated.image, s->updated.layout, dst->image, dst->layout, 1, &region);
	aa_gpu_image_barrier(ctx->cmd, dst, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
	aa_gpu_image_barrier(ctx->cmd, &s->frame, VK_IMAGE_LAYOUT_GENERAL);
	aa_gpu_timer_end(ctx->cmd, ctx->timer, span);

	s->parity = 1 - s->parity;
	if (s->valid_ages < 4)
		s->valid_ages++;
}

static int asaa_render(struct aa_method_state *s, struct aa_frame_ctx *ctx, struct aa_error *err)
{
	(void)err;
	if (s->reset_pending) {
		s->reset_pending = false;
		s->valid_ages = 0;
		/* priming: the three quadrants before this frame's, rendered now as if the camera had held
		 * still, so the cut frame already has four samples. Velocity is ignored on this frame: every
		 * buffer shows this very frame (and a job starting mid-path gets velocity from before a cut). */
		for (int back = s->prime ? 3 : 0; back > 0; back--)
			asaa_step(s, ctx, ctx->frame - back, true, "asaa-prime");
		asaa_step(s, ctx, ctx->frame, true, "scene");
	} else {
		asaa_step(s, ctx, ctx->frame, false, "scene");
	}
	ctx->output = &s->frame;
	return 0;
}

static void asaa_reset(struct aa_method_state *s)
{
	s->reset_pending = true;
}

const struct aa_method aa_method_asaa = {
	.name = "asaa",
	.summary = "amortised supersampling: four sub-pixel buffers, one refreshed per frame, tent reconstruction",
	.seed = "seed 000 (sections 3.8 and 4.4.1, ASAA)",
	.params = asaa_params,
	.param_count = sizeof asaa_params / sizeof asaa_params[0],
	.main_param = NULL,
	.needs = AA_NEED_VELOCITY | AA_NEED_HISTORY | AA_NEED_SUBSAMPLES,
	.create = asaa_create,
	.render = asaa_render,
	.reset = asaa_reset,
	.destroy = asaa_destroy,
};
