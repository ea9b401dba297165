/* `fxaa-cs`: FXAA 3.11 in compute shaders with work queues, after the DX11 compute FXAA of seed 000
 * (section 3.4.1): a luma pass; a classification pass that copies the pixels FXAA leaves alone and appends
 * edge pixels to a horizontal or a vertical queue with atomic counters, writing the indirect dispatch
 * sizes as it goes; then one indirect dispatch per queue runs the edge search on its pixels only. The
 * FXAA arithmetic is shaders/fxaa_common.glsl, the same as `fxaa`, so both give the same image. */
#include <stdio.h>
#include <stdlib.h>

#include "gpu/compute_pass.h"
#include "render/renderer.h"
#include "methods/fxaa.h"
#include "types/method.h"

#define TILE 8        /* local size of the per-pixel passes (fxaa_cs_luma.comp, fxaa_cs_classify.comp) */

/* The header of the queue buffer (FxaaQueues in shaders/fxaa_cs_queue.glsl), reset every frame; the
 * item array (one uint per pixel) follows it. */
struct queue_header {
	uint32_t args_horizontal[3]; /* VkDispatchIndirectCommand */
	uint32_t count_horizontal;
	uint32_t args_vertical[3];
	uint32_t count_vertical;
};

struct aa_method_state {
	struct aa_renderer *r;
	struct aa_scene_target target;
	struct aa_gpu_image luma, output;
	struct aa_gpu_buffer queues;
	struct aa_compute_pass luma_pass, classify_pass, edges_pass[2]; /* edges: [0] horizontal, [1] vertical */
	struct aa_fxaa_spec spec[2];
	struct aa_fxaa_push push;
};

static void fxaa_cs_destroy(struct aa_method_state *s)
{
	struct aa_gpu *gpu = s->r->gpu;
	for (int i = 0; i < 2; i++)
		aa_compute_pass_destroy(gpu, &s->edges_pass[i]);
	aa_compute_pass_destroy(gpu, &s->classify_pass);
	aa_compute_pass_destroy(gpu, &s->luma_pass);
	aa_gpu_buffer_destroy(gpu, &s->queues);
	aa_gpu_image_destroy(gpu, &s->output);
	aa_gpu_image_destroy(gpu, &s->luma);
	aa_scene_target_destroy(s->r, &s->target);
	free(s);
}

static int create_passes(struct aa_method_state *s, struct aa_error *err)
{
	struct aa_gpu *gpu = s->r->gpu;
	struct aa_compute_binding scene = {AA_COMPUTE_SAMPLED, &s->target.color, NULL};
	struct aa_compute_binding luma_sampled = {AA_COMPUTE_SAMPLED_LINEAR, &s->luma, NULL};
	struct aa_compute_binding result = {AA_COMPUTE_STORAGE_IMAGE, &s->output, NULL};
	struct aa_compute_binding queues = {AA_COMPUTE_STORAGE_BUFFER, NULL, &s->queues};
	if (aa_compute_pass_create(gpu, &s->luma_pass, &(struct aa_compute_desc){
			.comp = "fxaa_cs_luma.comp", .binding_count = 2,
			.bindings = {scene, {AA_COMPUTE_STORAGE_IMAGE, &s->luma, NULL}}}, err) ||
	    aa_compute_pass_create(gpu, &s->classify_pass, &(struct aa_compute_desc){
			.comp = "fxaa_cs_classify.comp", .binding_count = 4,
			.bindings = {luma_sampled, scene, result, queues}, .push_size = sizeof s->push,
			.specialization = &s->spec[0].info}, err))
		return -1;
	for (int i = 0; i < 2; i++)
		if (aa_compute_pass_create(gpu, &s->edges_pass[i], &(struct aa_compute_desc){
				.comp = "fxaa_cs_edges.comp", .binding_count = 4,
				.bindings = {luma_sampled, scene, result, queues}, .push_size = sizeof s->push,
				.specialization = &s->spec[i].info}, err))
			return -1;
	return 0;
}

static int fxaa_cs_create(struct aa_renderer *r, const struct aa_method_params *p,
			  struct aa_method_result *info, struct aa_method_state **out, struct aa_error *err)
{
	struct aa_method_state *s = calloc(1, sizeof *s);
	if (!s)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	s->r = r;
	aa_fxaa_spec_init(&s->spec[0], p, true);
	aa_fxaa_spec_init(&s->spec[1], p, false);
	aa_fxaa_push_init(&s->push, p);
	char desc[40];
	aa_fxaa_describe(p, desc, sizeof desc);
	snprintf(info->path_taken, sizeof info->path_taken, "compute, edge queues, %s", desc);
	/* a pixel is in at most one queue: one item per pixel covers both (shaders/fxaa_cs_queue.glsl) */
	VkDeviceSize queue_bytes = sizeof(struct queue_header) + (VkDeviceSize)r->width * r->height * 4;
	if (aa_scene_target_create(r, &s->target, r->width, r->height, "scene", info, err) ||
	    aa_renderer_image_create(r, &s->luma, r->width, r->height, VK_FORMAT_R8G8B8A8_UNORM,
				     VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, "sRGB colour + luma",
				     info, err) ||
	    aa_renderer_image_create(r, &s->output, r->width, r->height, AA_SCENE_COLOR_FORMAT,
				     VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
				     VK_IMAGE_USAGE_TRANSFER_SRC_BIT, "fxaa output", info, err) ||
	    aa_gpu_buffer_create(r->gpu, &s->queues, queue_bytes,
				 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT |
				 VK_BUFFER_USAGE_TRANSFER_DST_BIT, false, err)) {
		fxaa_cs_destroy(s);
		return -1;
	}
	aa_method_result_add_memory(info, "edge queues", queue_bytes);
	if (create_passes(s, err)) {
		fxaa_cs_destroy(s);
		return -1;
	}
	*out = s;
	return 0;
}

static int fxaa_cs_render(struct aa_method_state *s, struct aa_frame_ctx *ctx, struct aa_error *err)
{
	VkCommandBuffer cmd = ctx->cmd;
	int w = s->r->width, h = s->r->height;
	int span = aa_gpu_timer_begin(cmd, ctx->timer, "scene");
	aa_renderer_draw_scene(s->r, cmd, &s->target, 0.0f, 0.0f);
	aa_gpu_timer_end(cmd, ctx->timer, span);

	span = aa_gpu_timer_begin(cmd, ctx->timer, "fxaa-cs-luma");
	aa_compute_pass_dispatch(cmd, &s->luma_pass, NULL, 0, aa_compute_groups(w, TILE),
				 aa_compute_groups(h, TILE), 1);
	aa_gpu_timer_end(cmd, ctx->timer, span);

	span = aa_gpu_timer_begin(cmd, ctx->timer, "fxaa-cs-classify");
	/* empty queues: zero counts and zero groups (y = z = 1) */
	const struct queue_header empty = {{0, 1, 1}, 0, {0, 1, 1}, 0};
	vkCmdUpdateBuffer(cmd, s->queues.buffer, 0, sizeof empty, &empty);
	aa_compute_pass_dispatch(cmd, &s->classify_pass, &s->push, sizeof s->push, aa_compute_groups(w, TILE),
				 aa_compute_groups(h, TILE), 1);
	aa_gpu_timer_end(cmd, ctx->timer, span);

	span = aa_gpu_timer_begin(cmd, ctx->timer, "fxaa-cs-horizontal");
	aa_compute_pass_dispatch_indirect(cmd, &s->edges_pass[0], &s->push, sizeof s->push, &s->queues,
					  offsetof(struct queue_header, args_horizontal));
	aa_gpu_timer_end(cmd, ctx->timer, span);
	span = aa_gpu_timer_begin(cmd, ctx->timer, "fxaa-cs-vertical");
	aa_compute_pass_dispatch_indirect(cmd, &s->edges_pass[1], &s->push, sizeof s->push, &s->queues,
					  offsetof(struct queue_header, args_vertical));
	aa_gpu_timer_end(cmd, ctx->timer, span);
	ctx->output = &s->output;
	return 0;
}

static void fxaa_cs_reset(struct aa_method_state *s) { (void)s; }

const struct aa_method aa_method_fxaa_cs = {
	.name = "fxaa-cs",
	.summary = "FXAA 3.11 in compute: luma, edge-pixel queues, indirect dispatches per edge direction",
	.seed = "seed 000 section 3.4.1; seed 003",
	.params = aa_fxaa_params,
	.param_count = AA_FXAA_PARAM_COUNT,
	.main_param = NULL,
	.needs = 0,
	.create = fxaa_cs_create,
	.render = fxaa_cs_render,
	.reset = fxaa_cs_reset,
	.destroy = fxaa_cs_destroy,
};
