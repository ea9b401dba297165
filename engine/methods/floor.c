/* `floor`: the rasterizer's floor, not an AA method. The scene's geometry is drawn with the scene pass's
 * vertex shader, depth test and targets, but the fragment shader writes one constant colour, so the pass
 * costs what rasterising, depth testing and storing the target cost. bench/floor and bench/methods
 * divide the scene pass of `none` by this pass, measured in the same run. */
#include <stdio.h>
#include <stdlib.h>

#include "render/renderer.h"
#include "types/method.h"

struct aa_method_state {
	struct aa_renderer *r;
	struct aa_scene_target target;
};

static void floor_destroy(struct aa_method_state *s)
{
	aa_scene_target_destroy(s->r, &s->target);
	free(s);
}

static int floor_create(struct aa_renderer *r, const struct aa_method_params *p, struct aa_method_result *info,
			struct aa_method_state **out, struct aa_error *err)
{
	(void)p;
	struct aa_method_state *s = calloc(1, sizeof *s);
	if (!s)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	s->r = r;
	snprintf(info->path_taken, sizeof info->path_taken, "scene geometry, depth-tested, constant colour");
	struct aa_scene_target_desc desc = {.samples = 1, .constant_colour = true};
	if (aa_scene_target_create_desc(r, &s->target, r->width, r->height, &desc, "floor", info, err)) {
		floor_destroy(s);
		return -1;
	}
	*out = s;
	return 0;
}

static int floor_render(struct aa_method_state *s, struct aa_frame_ctx *ctx, struct aa_error *err)
{
	(void)err;
	int span = aa_gpu_timer_begin(ctx->cmd, ctx->timer, "floor");
	aa_renderer_draw_scene(s->r, ctx->cmd, &s->target, 0.0f, 0.0f);
	aa_gpu_timer_end(ctx->cmd, ctx->timer, span);
	ctx->output = s->target.output;
	return 0;
}

static void floor_reset(struct aa_method_state *s) { (void)s; }

const struct aa_method aa_method_floor = {
	.name = "floor",
	.summary = "benchmark floor, not AA: the scene's geometry depth-tested with a constant colour",
	.seed = "bench/floor (the rasterizer's floor)",
	.create = floor_create,
	.render = floor_render,
	.reset = floor_reset,
	.destroy = floor_destroy,
};
