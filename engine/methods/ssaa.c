/* `ssaa`: ordered-grid supersampling. The scene is rendered at k times the width and height (N = k*k
 * samples per pixel on a regular grid) and box-filtered down in linear colour (seed 000, Table 1). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "render/renderer.h"
#include "types/method.h"

static const int ssaa_sample_counts[] = {4, 9, 16, 25, 36, 49, 64, 0};

static const struct aa_param_def ssaa_params[] = {
	{.name = "samples", .type = AA_PARAM_INT, .def = 16, .min = 4, .max = 64, .allowed = ssaa_sample_counts,
	 .help = "samples per pixel, a square k*k: the image is rendered at k times the width and height"},
	{.name = "tonemapped_resolve", .type = AA_PARAM_BOOL, .def = 0, .min = 0, .max = 1,
	 .help = "resolve with Karis' weights 1/(1+luma) (a tone-mapped average) instead of the linear box: "
		 "no fireflies from sub-pixel HDR highlights, but farther from the linear-box reference"},
};

struct aa_method_state {
	struct aa_renderer *r;
	int factor;
	struct aa_scene_target big;
	struct aa_gpu_image output;
	struct aa_fullscreen_pass downsample;
};

static void ssaa_destroy(struct aa_method_state *s)
{
	aa_fullscreen_pass_destroy(s->r, &s->downsample);
	aa_gpu_image_destroy(s->r->gpu, &s->output);
	aa_scene_target_destroy(s->r, &s->big);
	free(s);
}

static int ssaa_create(struct aa_renderer *r, const struct aa_method_params *p, struct aa_method_result *info,
		       struct aa_method_state **out, struct aa_error *err)
{
	struct aa_method_state *s = calloc(1, sizeof *s);
	if (!s)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	s->r = r;
	s->factor = (int)lround(sqrt(p->v[0]));
	uint32_t max_dim = r->gpu->properties.limits.maxFramebufferWidth;
	if ((uint32_t)(r->width * s->factor) > max_dim || (uint32_t)(r->height * s->factor) > max_dim) {
		int factor = s->factor;
		free(s);
		return aa_error_set(err, AA_ERR_LIMIT, "size", "ssaa:%d needs a %dx%d target, larger than the "
				    "device's %u limit; use fewer samples or a smaller size", (int)p->v[0],
				    r->width * factor, r->height * factor, max_dim);
	}
	const bool tonemapped = p->v[1] != 0;
	snprintf(info->path_taken, sizeof info->path_taken, "%dx%d ordered grid, %s", s->factor, s->factor,
		 tonemapped ? "Karis-weighted (tone-mapped) box filter" : "box filter");
	if (aa_scene_target_create(r, &s->big, r->width * s->factor, r->height * s->factor, "supersampled", info,
				   err) ||
	    aa_renderer_image_create(r, &s->output, r->width, r->height, AA_SCENE_COLOR_FORMAT,
				     VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
				     VK_IMAGE_USAGE_TRANSFER_SRC_BIT, "resolved colour", info, err) ||
	    aa_fullscreen_pass_create(r, &s->downsample, &(struct aa_fullscreen_desc){
			.frag = tonemapped ? "resolve_karis.frag" : "resolve_box.frag", .source_count = 1, .sources = {s->big.output},
			.target = &s->output, .push_size = sizeof(int32_t)}, err)) {
		ssaa_destroy(s);
		return -1;
	}
	*out = s;
	return 0;
}

static int ssaa_render(struct aa_method_state *s, struct aa_frame_ctx *ctx, struct aa_error *err)
{
	int span = aa_gpu_timer_begin(ctx->cmd, ctx->timer, "scene");
	aa_renderer_draw_scene(s->r, ctx->cmd, &s->big, 0.0f, 0.0f);
	aa_gpu_timer_end(ctx->cmd, ctx->timer, span);
	span = aa_gpu_timer_begin(ctx->cmd, ctx->timer, "downsample");
	int32_t factor = s->factor;
	aa_fullscreen_pass_record(s->r, ctx->cmd, &s->downsample, &factor, sizeof factor);
	aa_gpu_timer_end(ctx->cmd, ctx->timer, span);
	ctx->output = &s->output;
	return 0;
}

static void ssaa_reset(struct aa_method_state *s) { (void)s; }

const struct aa_method aa_method_ssaa = {
	.name = "ssaa",
	.summary = "supersampling: render at k x k the resolution, box-filter down",
	.seed = "seed 000 (Table 1), seed 001",
	.params = ssaa_params,
	.param_count = 2,
	.main_param = "samples",
	.needs = AA_NEED_SUPERSAMPLED,
	.alpha_rule = AA_ALPHA_PER_SAMPLE,
	.create = ssaa_create,
	.render = ssaa_render,
	.reset = ssaa_reset,
	.destroy = ssaa_destroy,
};
