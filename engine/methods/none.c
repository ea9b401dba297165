/* `none`: one sample per pixel at the pixel centre, no anti-aliasing: the baseline every method beats. */
#include <stdlib.h>

#include "render/renderer.h"
#include "types/method.h"

struct aa_method_state {
	struct aa_renderer *r;
	struct aa_scene_target target;
};

static int none_create(struct aa_renderer *r, const struct aa_method_params *p, struct aa_method_result *info,
		       struct aa_method_state **out, struct aa_error *err)
{
	struct aa_method_state *s = calloc(1, sizeof *s);
	if (!s)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	s->r = r;
	snprintf(info->path_taken, sizeof info->path_taken, "1 sample at the pixel centre");
	if (aa_scene_target_create(r, &s->target, r->width, r->height, "scene", info, err)) {
		aa_scene_target_destroy(r, &s->target);
		free(s);
		return -1;
	}
	*out = s;
	return 0;
}

static int none_render(struct aa_method_state *s, struct aa_frame_ctx *ctx, struct aa_error *err)
{
	int span = aa_gpu_timer_begin(ctx->cmd, ctx->timer, "scene");
	aa_renderer_draw_scene(s->r, ctx->cmd, &s->target, 0.0f, 0.0f);
	aa_gpu_timer_end(ctx->cmd, ctx->timer, span);
	ctx->output = s->target.output;
	return 0;
}

static void none_reset(struct aa_method_state *s) { (void)s; }

static void none_destroy(struct aa_method_state *s)
{
	aa_scene_target_destroy(s->r, &s->target);
	free(s);
}

const struct aa_method aa_method_none = {
	.name = "none",
	.summary = "no anti-aliasing: one sample at each pixel centre",
	.seed = "baseline of every seed",
	.params = NULL,
	.param_count = 0,
	.needs = 0,
	.create = none_create,
	.render = none_render,
	.reset = none_reset,
	.destroy = none_destroy,
};
