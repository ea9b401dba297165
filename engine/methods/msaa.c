/* `msaa`: multisampling. Visibility is sampled at N standard positions per pixel, shading and the alpha
 * test once per pixel and triangle at its shading point (the centre, or the first covered sample when the
 * triangle covers only part of the pixel: shaders/shading_point.glsl), resolved with a box filter.
 * Hardware MSAA where the device renders N samples (lavapipe: 4 only); otherwise "virtual samples": the
 * scene is rasterised once per standard position (geometry jittered to it) with the same shading point,
 * and the N images are averaged (seed 000). Both paths give the same image up to rounding. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gpu/sample_positions.h"
#include "reference/sample_accumulator.h"
#include "render/renderer.h"
#include "types/method.h"

static const int msaa_sample_counts[] = {2, 4, 8, 0};
static const char *const msaa_paths[] = {"auto", "hardware", "virtual", NULL};
enum { PATH_AUTO, PATH_HARDWARE, PATH_VIRTUAL };

static const struct aa_param_def msaa_params[] = {
	{.name = "samples", .type = AA_PARAM_INT, .def = 4, .min = 2, .max = 8, .allowed = msaa_sample_counts,
	 .help = "samples per pixel, at the Vulkan standard sample locations"},
	{.name = "path", .type = AA_PARAM_ENUM, .def = PATH_AUTO, .min = 0, .max = 2, .choices = msaa_paths,
	 .help = "auto: hardware when the device supports the count, else virtual samples"},
	{.name = "alpha_to_coverage", .type = AA_PARAM_BOOL, .def = 0, .min = 0, .max = 1,
	 .help = "cut-out materials: each of the N samples is kept iff alpha at that sample reaches the cutoff "
		 "(colour still shaded once), instead of one alpha test per pixel"},
	{.name = "tonemapped_resolve", .type = AA_PARAM_BOOL, .def = 0, .min = 0, .max = 1,
	 .help = "resolve the samples with Karis' weights 1/(1+luma) (a tone-mapped average) in a pass of its own "
		 "instead of the render pass's box resolve (hardware path only)"},
};

struct aa_method_state {
	struct aa_renderer *r;
	int samples;
	bool hardware;
	struct aa_scene_target target;      /* hardware path */
	struct aa_sample_accumulator average; /* virtual path: RGBA32F average of the sample images */
	bool tonemapped;                    /* tonemapped_resolve: the Karis pass below replaces the box resolve */
	struct aa_gpu_image karis_output;
	struct aa_fullscreen_pass karis;
};

static void msaa_destroy(struct aa_method_state *s)
{
	aa_fullscreen_pass_destroy(s->r, &s->karis);
	aa_gpu_image_destroy(s->r->gpu, &s->karis_output);
	aa_sample_accumulator_destroy(&s->average);
	aa_scene_target_destroy(s->r, &s->target);
	free(s);
}

static int msaa_create(struct aa_renderer *r, const struct aa_method_params *p, struct aa_method_result *info,
		       struct aa_method_state **out, struct aa_error *err)
{
	struct aa_method_state *s = calloc(1, sizeof *s);
	if (!s)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	s->r = r;
	s->samples = (int)p->v[0];
	int path = (int)p->v[1];
	bool alpha_to_coverage = p->v[2] != 0;
	bool supported = (r->gpu->color_sample_counts & (VkSampleCountFlags)s->samples) != 0;
	if (path == PATH_HARDWARE && !supported) {
		free(s);
		return aa_error_set(err, AA_ERR_INVALID, "params.path", "this device (%s) cannot render %d samples "
				    "per pixel in hardware; use path=virtual or auto",
				    r->gpu->properties.deviceName, (int)p->v[0]);
	}
	s->hardware = path == PATH_HARDWARE || (path == PATH_AUTO && supported);
	s->tonemapped = p->v[3] != 0;
	if (s->tonemapped && !s->hardware) {
		free(s);
		/* the virtual path sums its sample images with fixed weights in the shared accumulator */
		return aa_error_set(err, AA_ERR_INVALID, "params.tonemapped_resolve", "msaa:%d takes the virtual "
				    "path on this device (%s), whose resolve is a linear sum; tonemapped_resolve needs "
				    "the hardware path (lavapipe: 4 samples)", (int)p->v[0],
				    r->gpu->properties.deviceName);
	}
	int rc;
	if (s->hardware) {
		snprintf(info->path_taken, sizeof info->path_taken, "hardware %dx, %s", s->samples,
			 s->tonemapped ? "Karis-weighted (tone-mapped) resolve pass" : "box resolve");
		struct aa_scene_target_desc d = {.samples = (uint32_t)s->samples,
						 .alpha_to_coverage = alpha_to_coverage};
		rc = aa_scene_target_create_desc(r, &s->target, r->width, r->height, &d, "msaa", info, err);
		if (!rc && s->tonemapped)
			rc = aa_renderer_image_create(r, &s->karis_output, r->width, r->height, AA_SCENE_COLOR_FORMAT,
						      VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
						      VK_IMAGE_USAGE_TRANSFER_SRC_BIT, "tone-mapped resolve", info,
						      err) ||
			     aa_fullscreen_pass_create(r, &s->karis, &(struct aa_fullscreen_desc){
					.frag = "resolve_karis_ms.frag", .source_count = 1,
					.sources = {&s->target.color}, .target = &s->karis_output,
					.push_size = sizeof(int32_t)}, err);
	} else {
		snprintf(info->path_taken, sizeof info->path_taken,
			 "virtual samples: %d rasterisations, shading once per pixel", s->samples);
		struct aa_scene_target_desc d = {.samples = 1, .virtual_samples = (uint32_t)s->samples,
						 .alpha_to_coverage = alpha_to_coverage};
		/* the sample images go in batches into one summing pass each (sample_accumulator.h) */
		rc = aa_sample_accumulator_create(r, &d, s->samples, 1.0f / (float)s->samples, "sample", info,
						  &s->average, err);
	}
	if (rc) {
		msaa_destroy(s);
		return -1;
	}
	*out = s;
	return 0;
}

static int msaa_render(struct aa_method_state *s, struct aa_frame_ctx *ctx, struct aa_error *err)
{
	if (s->hardware) {
		int span = aa_gpu_timer_begin(ctx->cmd, ctx->timer, "scene-msaa");
		aa_renderer_draw_scene(s->r, ctx->cmd, &s->target, 0.0f, 0.0f);
		aa_gpu_timer_end(ctx->cmd, ctx->timer, span);
		ctx->output = s->target.output;
		if (s->tonemapped) {
			span = aa_gpu_timer_begin(ctx->cmd, ctx->timer, "resolve-tonemapped");
			int32_t samples = s->samples;
			aa_fullscreen_pass_record(s->r, ctx->cmd, &s->karis, &samples, sizeof samples);
			aa_gpu_timer_end(ctx->cmd, ctx->timer, span);
			ctx->output = &s->karis_output;
		}
		return 0;
	}
	const float (*pos)[2] = aa_standard_sample_positions(s->samples);
	int span = aa_gpu_timer_begin(ctx->cmd, ctx->timer, "scene-virtual-samples");
	aa_sample_accumulator_clear(&s->average, ctx->cmd);
	for (int i = 0; i < s->samples; i++)
		/* moving the geometry by -(position - centre) puts sample i's point on the pixel centre */
		aa_sample_accumulator_render(&s->average, ctx->cmd, 0.5f - pos[i][0], 0.5f - pos[i][1]);
	ctx->output = aa_sample_accumulator_sum(&s->average, ctx->cmd);
	aa_gpu_timer_end(ctx->cmd, ctx->timer, span);
	return 0;
}

static void msaa_reset(struct aa_method_state *s) { (void)s; }

const struct aa_method aa_method_msaa = {
	.name = "msaa",
	.summary = "multisampling: N visibility samples per pixel, one shade per pixel and triangle",
	.seed = "seed 000 (2x/4x/8x MSAA)",
	.params = msaa_params,
	.param_count = 4,
	.main_param = "samples",
	.needs = AA_NEED_MSAA,
	.alpha_rule = AA_ALPHA_PER_PIXEL,
	.create = msaa_create,
	.render = msaa_render,
	.reset = msaa_reset,
	.destroy = msaa_destroy,
};
