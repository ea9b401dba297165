/* `t2msaa`: temporal 2x MSAA (seed 000, section 4.4.2). Each frame renders two visibility samples per
 * pixel (the Vulkan standard 2x positions, as virtual samples shaded at the pixel centre) shifted by a
 * jitter that alternates between frames, and blends their mean with the previous frame reprojected by the
 * velocity buffer: 2 frames x 2 samples, about four samples per pixel. Sample counts are capped and
 * history is RGBA32F, so a static scene converges instead of stalling (the thesis's count is unbounded). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gpu/sample_positions.h"
#include "gpu/compute_pass.h"
#include "render/renderer.h"
#include "methods/jitter.h"
#include "types/method.h"

static const char *const t2msaa_offsets[] = {"0.25", "0.1875", "0.125", NULL};
static const char *const t2msaa_blur_velocities[] = {"fraction", "uv", NULL};
static const float t2msaa_offset_values[] = {0.25f, 0.1875f, 0.125f};

static const struct aa_param_def t2msaa_params[] = {
	/* default 0.125: with the thesis's 0.25 every sample lies on a pixel edge, shared with the neighbour,
	 * which blurs against a box-filtered reference (thin-wires: 20.7 dB vs 25.4 dB; docs/methods.md) */
	{.name = "offset", .type = AA_PARAM_ENUM, .def = 2, .min = 0, .max = 2, .choices = t2msaa_offsets,
	 .help = "temporal jitter in pixels along the anti-diagonal, +offset and -offset on alternate frames "
		 "(seed 000: 0.25; its later tests 0.1875 and 0.125: sharper geometry, more shading aliasing)"},
	{.name = "max_samples", .type = AA_PARAM_INT, .def = 16, .min = 1, .max = 255,
	 .help = "cap on the per-pixel sample count N; the blend weight of a new frame is at least "
		 "1/(max_samples+1)"},
	{.name = "blur_velocity", .type = AA_PARAM_ENUM, .def = 0, .min = 0, .max = 1,
	 .choices = t2msaa_blur_velocities,
	 .help = "velocity in the blur threshold: fraction (of a pixel, Eq. 3.31's meaning) or uv (|velocity| "
		 "in UV units, as the thesis's Listing 4.19)"},
};

struct aa_method_state {
	struct aa_renderer *r;
	float offset;
	float max_samples;
	bool blur_uv;
	bool history_valid;
	int current;                       /* history[current] is the latest frame */
	struct aa_scene_target sample0;    /* G-buffer: colour, velocity, linear depth */
	struct aa_scene_target sample1;    /* colour only */
	struct aa_gpu_image history[2];    /* RGBA32F frame, ping-pong; the method's output */
	struct aa_gpu_image state[2];      /* RGBA16F: linear depth, sample count N */
	struct aa_compute_pass resolve[2]; /* [i] reads history[i], writes history[1 - i] */
};

struct t2msaa_push {
	int32_t size[2];
	float max_samples;
	int32_t history_valid;
	int32_t blur_uv;
};

static void t2msaa_destroy(struct aa_method_state *s)
{
	struct aa_gpu *gpu = s->r->gpu;
	for (int i = 0; i < 2; i++) {
		aa_compute_pass_destroy(gpu, &s->resolve[i]);
		aa_gpu_image_destroy(gpu, &s->history[i]);
		aa_gpu_image_destroy(gpu, &s->state[i]);
	}
	aa_scene_target_destroy(s->r, &s->sample0);
	aa_scene_target_destroy(s->r, &s->sample1);
	free(s);
}

static int t2msaa_create(struct aa_renderer *r, const struct aa_method_params *p,
			 struct aa_method_result *info, struct aa_method_state **out, struct aa_error *err)
{
	struct aa_method_state *s = calloc(1, sizeof *s);
	if (!s)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	s->r = r;
	s->offset = t2msaa_offset_values[(int)p->v[0]];
	s->max_samples = (float)p->v[1];
	s->blur_uv = p->v[2] != 0;
	snprintf(info->path_taken, sizeof info->path_taken,
		 "2 virtual samples + 1 previous frame, jitter +-%g px, blur threshold from velocity %s",
		 (double)s->offset, s->blur_uv ? "in UV units" : "fractions");
	/* 2 virtual samples: shading and the alpha test once per pixel, as 2x MSAA does (shading_point.glsl) */
	struct aa_scene_target_desc d0 = {.samples = 1, .outputs = AA_OUT_VELOCITY | AA_OUT_SURFACE,
					  .virtual_samples = 2};
	struct aa_scene_target_desc d1 = {.samples = 1, .virtual_samples = 2};
	VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
	int rc = aa_scene_target_create_desc(r, &s->sample0, r->width, r->height, &d0, "sample 0", info, err) ||
		 aa_scene_target_create_desc(r, &s->sample1, r->width, r->height, &d1, "sample 1", info, err);
	for (int i = 0; i < 2 && !rc; i++) {
		char name[48];
		snprintf(name, sizeof name, "history %d (RGBA32F)", i);
		rc = aa_renderer_image_create(r, &s->history[i], r->width, r->height, VK_FORMAT_R32G32B32A32_SFLOAT,
					      usage | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, name, info, err);
		snprintf(name, sizeof name, "depth + count %d (RGBA16F)", i);
		rc = rc || aa_renderer_image_create(r, &s->state[i], r->width, r->height,
						    VK_FORMAT_R16G16B16A16_SFLOAT, usage, name, info, err);
	}
	for (int i = 0; i < 2 && !rc; i++) {
		struct aa_compute_desc d = {
			.comp = "t2msaa.comp", .binding_count = 8, .push_size = sizeof(struct t2msaa_push),
			.bindings = {
				{AA_COMPUTE_SAMPLED, s->sample0.output, NULL},
				{AA_COMPUTE_SAMPLED, s->sample1.output, NULL},
				{AA_COMPUTE_SAMPLED, &s->sample0.extra[0], NULL},
				{AA_COMPUTE_SAMPLED, &s->sample0.extra[4], NULL},
				{AA_COMPUTE_SAMPLED_LINEAR, &s->history[i], NULL},
				{AA_COMPUTE_SAMPLED_LINEAR, &s->state[i], NULL},
				{AA_COMPUTE_STORAGE_IMAGE, &s->history[1 - i], NULL},
				{AA_COMPUTE_STORAGE_IMAGE, &s->state[1 - i], NULL},
			},
		};
		rc = aa_compute_pass_create(r->gpu, &s->resolve[i], &d, err);
	}
	if (rc) {
		t2msaa_destroy(s);
		return -1;
	}
	*out = s;
	return 0;
}

static int t2msaa_render(struct aa_method_state *s, struct aa_frame_ctx *ctx, struct aa_error *err)
{
	(void)err;
	const float (*pos)[2] = aa_standard_sample_positions(2);
	/* aa_jitter_alternate moves along the main diagonal, where Vulkan's two standard positions already
	 * lie; mirrored in y it runs along the anti-diagonal as in the thesis (Fig. 4.15), so the four
	 * samples of two frames fall on three distinct rows and columns instead of repeating one. */
	float j[2];
	aa_jitter_alternate(ctx->frame, s->offset, j);
	float t[2] = {j[0], -j[1]};
	int span = aa_gpu_timer_begin(ctx->cmd, ctx->timer, "scene-virtual-samples");
	/* moving the geometry by centre - (position + t) puts that point of the pixel on its centre */
	aa_renderer_draw_scene(s->r, ctx->cmd, &s->sample0, 0.5f - pos[0][0] - t[0], 0.5f - pos[0][1] - t[1]);
	aa_renderer_draw_scene(s->r, ctx->cmd, &s->sample1, 0.5f - pos[1][0] - t[0], 0.5f - pos[1][1] - t[1]);
	aa_gpu_timer_end(ctx->cmd, ctx->timer, span);

	struct t2msaa_push push = {{ctx->width, ctx->height}, s->max_samples, s->history_valid, s->blur_uv};
	span = aa_gpu_timer_begin(ctx->cmd, ctx->timer, "t2msaa-resolve");
	aa_compute_pass_dispatch(ctx->cmd, &s->resolve[s->current], &push, sizeof push,
				 aa_compute_groups(ctx->width, 8), aa_compute_groups(ctx->height, 8), 1);
	aa_gpu_timer_end(ctx->cmd, ctx->timer, span);
	s->current = 1 - s->current;
	s->history_valid = true;
	/* compute writes must be visible to the readback that follows */
	aa_gpu_full_barrier(ctx->cmd);
	ctx->output = &s->history[s->current];
	return 0;
}

static void t2msaa_reset(struct aa_method_state *s)
{
	s->history_valid = false;
}

const struct aa_method aa_method_t2msaa = {
	.name = "t2msaa",
	.summary = "temporal 2x MSAA: two samples per frame plus the reprojected previous frame",
	.seed = "seed 000 (section 4.4.2, T2MSAA)",
	.params = t2msaa_params,
	.param_count = 3,
	.main_param = "offset",
	.needs = AA_NEED_VELOCITY | AA_NEED_HISTORY | AA_NEED_MSAA,
	.alpha_rule = AA_ALPHA_PER_PIXEL,
	.create = t2msaa_create,
	.render = t2msaa_render,
	.reset = t2msaa_reset,
	.destroy = t2msaa_destroy,
};
