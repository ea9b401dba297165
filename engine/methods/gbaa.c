/* `gbaa`: geometry buffer anti-aliasing (Persson 2011, seed 000 section 3.3). The scene pass also writes,
 * through a geometry shader, each pixel's signed distance to the nearest triangle edge; a resolve pass
 * blends each edge pixel with its neighbour across the edge by one shifted bilinear fetch. */
#include <stdlib.h>

#include "render/renderer.h"
#include "types/method.h"

struct aa_method_state {
	struct aa_renderer *r;
	struct aa_scene_target target;
	struct aa_gpu_image output;
	struct aa_fullscreen_pass resolve;
};

static void gbaa_destroy(struct aa_method_state *s)
{
	aa_fullscreen_pass_destroy(s->r, &s->resolve);
	aa_gpu_image_destroy(s->r->gpu, &s->output);
	aa_scene_target_destroy(s->r, &s->target);
	free(s);
}

static int gbaa_create(struct aa_renderer *r, const struct aa_method_params *p, struct aa_method_result *info,
		       struct aa_method_state **out, struct aa_error *err)
{
	(void)p;
	if (!r->gpu->properties.limits.maxGeometryOutputVertices)
		return aa_error_set(err, AA_ERR_GPU, "", "gbaa needs geometry shaders, which %s lacks",
				    r->gpu->properties.deviceName);
	struct aa_method_state *s = calloc(1, sizeof *s);
	if (!s)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	s->r = r;
	snprintf(info->path_taken, sizeof info->path_taken, "geometry shader edge distances, 1 resolve fetch");
	struct aa_scene_target_desc d = {.samples = 1, .edge_distances = true};
	if (aa_scene_target_create_desc(r, &s->target, r->width, r->height, &d, "scene", info, err) ||
	    aa_renderer_image_create(r, &s->output, r->width, r->height, AA_SCENE_COLOR_FORMAT,
				     VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
				     VK_IMAGE_USAGE_TRANSFER_SRC_BIT, "resolved colour", info, err) ||
	    aa_fullscreen_pass_create(r, &s->resolve, &(struct aa_fullscreen_desc){
			.frag = "gbaa_resolve.frag", .source_count = 2,
			.sources = {s->target.output, &s->target.edges}, .linear = {true, false},
			.target = &s->output}, err)) {
		gbaa_destroy(s);
		return -1;
	}
	*out = s;
	return 0;
}

static int gbaa_render(struct aa_method_state *s, struct aa_frame_ctx *ctx, struct aa_error *err)
{
	int span = aa_gpu_timer_begin(ctx->cmd, ctx->timer, "scene-gbaa");
	aa_renderer_draw_scene(s->r, ctx->cmd, &s->target, 0.0f, 0.0f);
	aa_gpu_timer_end(ctx->cmd, ctx->timer, span);
	span = aa_gpu_timer_begin(ctx->cmd, ctx->timer, "gbaa-resolve");
	aa_fullscreen_pass_record(s->r, ctx->cmd, &s->resolve, NULL, 0);
	aa_gpu_timer_end(ctx->cmd, ctx->timer, span);
	ctx->output = &s->output;
	return 0;
}

static void gbaa_reset(struct aa_method_state *s) { (void)s; }

const struct aa_method aa_method_gbaa = {
	.name = "gbaa",
	.summary = "geometry buffer AA: analytic edge distances from a geometry shader, one blend fetch",
	.seed = "seed 000 (section 3.3, after Persson 2011)",
	.params = NULL,
	.param_count = 0,
	.needs = AA_NEED_GBUFFER,
	.create = gbaa_create,
	.render = gbaa_render,
	.reset = gbaa_reset,
	.destroy = gbaa_destroy,
};
