/* `copy`: no anti-aliasing plus one full-screen copy pass, timed on its own. It is the bandwidth floor
 * that bench/methods divides every method's own pass time by; not an AA method. */
#include <stdlib.h>

#include "render/renderer.h"
#include "types/method.h"

struct aa_method_state {
	struct aa_renderer *r;
	struct aa_scene_target target;
	struct aa_gpu_image output;
	struct aa_fullscreen_pass copy;
};

static void copy_destroy(struct aa_method_state *s)
{
	aa_fullscreen_pass_destroy(s->r, &s->copy);
	aa_gpu_image_destroy(s->r->gpu, &s->output);
	aa_scene_target_destroy(s->r, &s->target);
	free(s);
}

static int copy_create(struct aa_renderer *r, const struct aa_method_params *p, struct aa_method_result *info,
		       struct aa_method_state **out, struct aa_error *err)
{
	(void)p;
	struct aa_method_state *s = calloc(1, sizeof *s);
	if (!s)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	s->r = r;
	snprintf(info->path_taken, sizeof info->path_taken, "1 sample + full-screen texelFetch copy");
	if (aa_scene_target_create(r, &s->target, r->width, r->height, "scene", info, err) ||
	    aa_renderer_image_create(r, &s->output, r->width, r->height, AA_SCENE_COLOR_FORMAT,
				     VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
				     VK_IMAGE_USAGE_TRANSFER_SRC_BIT, "copy", info, err) ||
	    aa_fullscreen_pass_create(r, &s->copy, &(struct aa_fullscreen_desc){
			.frag = "copy.frag", .source_count = 1, .sources = {s->target.output},
			.target = &s->output}, err)) {
		copy_destroy(s);
		return -1;
	}
	*out = s;
	return 0;
}

static int copy_render(struct aa_method_state *s, struct aa_frame_ctx *ctx, struct aa_error *err)
{
	int span = aa_gpu_timer_begin(ctx->cmd, ctx->timer, "scene");
	aa_renderer_draw_scene(s->r, ctx->cmd, &s->target, 0.0f, 0.0f);
	aa_gpu_timer_end(ctx->cmd, ctx->timer, span);
	span = aa_gpu_timer_begin(ctx->cmd, ctx->timer, "copy");
	aa_fullscreen_pass_record(s->r, ctx->cmd, &s->copy, NULL, 0);
	aa_gpu_timer_end(ctx->cmd, ctx->timer, span);
	ctx->output = &s->output;
	return 0;
}

static void copy_reset(struct aa_method_state *s) { (void)s; }

const struct aa_method aa_method_copy = {
	.name = "copy",
	.summary = "benchmark floor, not AA: one sample plus a full-screen copy pass",
	.seed = "bench/methods (bandwidth floor)",
	.create = copy_create,
	.render = copy_render,
	.reset = copy_reset,
	.destroy = copy_destroy,
};
