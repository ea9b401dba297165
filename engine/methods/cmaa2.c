/* `cmaa2`: conservative morphological anti-aliasing in the manner of Intel's CMAA2 (Strugar and Lake,
 * 2018), written from its published description: a post-process on the 1 spp scene colour that changes
 * only pixels on clear edges. Three compute passes: edge detection (colour contrast with a threshold per
 * quality preset and local contrast adaptation), shape handling (Z-shaped steps of edge lines, a
 * staircase, revectorised; pixels with edges on three or four sides blurred a little), and the deferred
 * blend (each pixel the mean of the blends the shapes wrote for it). Straight edges, corners and bumps
 * are left alone, which is what makes it conservative: text and fine detail keep their sharpness. */
#include <stdio.h>
#include <stdlib.h>

#include "gpu/compute_pass.h"
#include "render/renderer.h"
#include "types/method.h"

enum { PRESET_LOW, PRESET_MEDIUM, PRESET_HIGH, PRESET_ULTRA };
static const char *const cmaa2_presets[] = {"low", "medium", "high", "ultra", NULL};

static const struct aa_param_def cmaa2_params[] = {
	{.name = "preset", .type = AA_PARAM_ENUM, .def = PRESET_HIGH, .min = 0, .max = 3, .choices = cmaa2_presets,
	 .help = "quality preset: the edge threshold (0.15, 0.10, 0.07, 0.05 of the gamma-encoded range)"},
	{.name = "max_line", .type = AA_PARAM_INT, .def = 86, .min = 2, .max = 256,
	 .help = "longest edge line followed, in pixels; longer lines are revectorised in pieces"},
};

/* The published presets' edge thresholds (CMAA2's g_CMAA2_EdgeThreshold per quality level). */
static const float preset_threshold[] = {0.15f, 0.10f, 0.07f, 0.05f};
#define LCA_FACTOR 2.0f   /* an edge survives when no edge of its two pixels is over twice as strong */
#define SIMPLE_BLUR 0.10f /* simple shapes: share of each neighbour across an edge */

struct edges_push {
	float threshold, lca_factor;
};
struct shapes_push {
	int32_t max_line;
	float simple_blur;
};

struct aa_method_state {
	struct aa_renderer *r;
	struct aa_scene_target target;
	struct aa_gpu_image edges, output;
	struct aa_gpu_buffer accumulation;
	struct aa_compute_pass edge_pass, shape_pass, apply_pass;
	struct edges_push edges_push;
	struct shapes_push shapes_push;
};

static void cmaa2_destroy(struct aa_method_state *s)
{
	struct aa_gpu *gpu = s->r->gpu;
	aa_compute_pass_destroy(gpu, &s->apply_pass);
	aa_compute_pass_destroy(gpu, &s->shape_pass);
	aa_compute_pass_destroy(gpu, &s->edge_pass);
	aa_gpu_buffer_destroy(gpu, &s->accumulation);
	aa_gpu_image_destroy(gpu, &s->output);
	aa_gpu_image_destroy(gpu, &s->edges);
	aa_scene_target_destroy(s->r, &s->target);
	free(s);
}

static int cmaa2_create(struct aa_renderer *r, const struct aa_method_params *p, struct aa_method_result *info,
			struct aa_method_state **out, struct aa_error *err)
{
	struct aa_method_state *s = calloc(1, sizeof *s);
	if (!s)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	s->r = r;
	int preset = (int)p->v[0];
	s->edges_push = (struct edges_push){preset_threshold[preset], LCA_FACTOR};
	s->shapes_push = (struct shapes_push){(int32_t)p->v[1], SIMPLE_BLUR};
	snprintf(info->path_taken, sizeof info->path_taken,
		 "CMAA2 %s: colour edges (Rec. 601 weights), threshold %.2f, lines up to %d px, deferred blend", cmaa2_presets[preset],
		 (double)s->edges_push.threshold, s->shapes_push.max_line);
	int w = r->width, h = r->height;
	VkDeviceSize slots = (VkDeviceSize)w * h * 16; /* uvec4 per pixel */
	int rc = aa_scene_target_create(r, &s->target, w, h, "scene", info, err) ||
		 aa_renderer_image_create(r, &s->edges, w, h, VK_FORMAT_R8_UINT,
					  VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, "edges", info, err) ||
		 aa_renderer_image_create(r, &s->output, w, h, AA_SCENE_COLOR_FORMAT,
					  VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
					  VK_IMAGE_USAGE_TRANSFER_SRC_BIT, "blended colour", info, err) ||
		 aa_gpu_buffer_create(r->gpu, &s->accumulation, slots,
				      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, false, err);
	if (!rc)
		aa_method_result_add_memory(info, "deferred blends", slots);
	struct aa_compute_binding acc = {AA_COMPUTE_STORAGE_BUFFER, NULL, &s->accumulation};
	rc = rc ||
	     aa_compute_pass_create(r->gpu, &s->edge_pass, &(struct aa_compute_desc){
			.comp = "cmaa2_edges.comp", .binding_count = 2, .push_size = sizeof s->edges_push,
			.bindings = {{AA_COMPUTE_SAMPLED, s->target.output, NULL},
				     {AA_COMPUTE_STORAGE_IMAGE, &s->edges, NULL}}}, err) ||
	     aa_compute_pass_create(r->gpu, &s->shape_pass, &(struct aa_compute_desc){
			.comp = "cmaa2_shapes.comp", .binding_count = 3, .push_size = sizeof s->shapes_push,
			.bindings = {{AA_COMPUTE_SAMPLED, s->target.output, NULL},
				     {AA_COMPUTE_SAMPLED, &s->edges, NULL}, acc}}, err) ||
	     aa_compute_pass_create(r->gpu, &s->apply_pass, &(struct aa_compute_desc){
			.comp = "cmaa2_apply.comp", .binding_count = 3,
			.bindings = {{AA_COMPUTE_SAMPLED, s->target.output, NULL}, acc,
				     {AA_COMPUTE_STORAGE_IMAGE, &s->output, NULL}}}, err);
	if (rc) {
		cmaa2_destroy(s);
		return -1;
	}
	*out = s;
	return 0;
}

static int cmaa2_render(struct aa_method_state *s, struct aa_frame_ctx *ctx, struct aa_error *err)
{
	(void)err;
	uint32_t gx = aa_compute_groups(ctx->width, 8), gy = aa_compute_groups(ctx->height, 8);
	int span = aa_gpu_timer_begin(ctx->cmd, ctx->timer, "scene");
	aa_renderer_draw_scene(s->r, ctx->cmd, &s->target, 0.0f, 0.0f);
	aa_gpu_timer_end(ctx->cmd, ctx->timer, span);

	span = aa_gpu_timer_begin(ctx->cmd, ctx->timer, "cmaa2-edges");
	aa_compute_pass_dispatch(ctx->cmd, &s->edge_pass, &s->edges_push, sizeof s->edges_push, gx, gy, 1);
	aa_gpu_timer_end(ctx->cmd, ctx->timer, span);

	span = aa_gpu_timer_begin(ctx->cmd, ctx->timer, "cmaa2-shapes");
	vkCmdFillBuffer(ctx->cmd, s->accumulation.buffer, 0, VK_WHOLE_SIZE, 0);
	aa_compute_pass_dispatch(ctx->cmd, &s->shape_pass, &s->shapes_push, sizeof s->shapes_push, gx, gy, 1);
	aa_gpu_timer_end(ctx->cmd, ctx->timer, span);

	span = aa_gpu_timer_begin(ctx->cmd, ctx->timer, "cmaa2-apply");
	aa_compute_pass_dispatch(ctx->cmd, &s->apply_pass, NULL, 0, gx, gy, 1);
	aa_gpu_timer_end(ctx->cmd, ctx->timer, span);
	/* compute writes must be visible to the readback that follows */
	aa_gpu_full_barrier(ctx->cmd);
	ctx->output = &s->output;
	return 0;
}

static void cmaa2_reset(struct aa_method_state *s) { (void)s; }

const struct aa_method aa_method_cmaa2 = {
	.name = "cmaa2",
	.summary = "conservative morphological AA (CMAA2): colour edges, Z shapes revectorised, simple shapes "
		   "blurred, deferred blend; clear edges only",
	.seed = "Intel CMAA2 (2018), from its published description",
	.params = cmaa2_params,
	.param_count = 2,
	.main_param = NULL,
	.create = cmaa2_create,
	.render = cmaa2_render,
	.reset = cmaa2_reset,
	.destroy = cmaa2_destroy,
};
