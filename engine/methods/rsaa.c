/* `rsaa`: resampling anti-aliasing (Reshetov, HPG 2012; seed 002). Shading once per pixel, geometry
 * (world position and triangle normal) at 4 or 8 standard subsample positions; each subsample is compared
 * with the pixel centre (SADP or depth), one k-means step splits them into similar and dissimilar, and the
 * resulting mask selects a trained offset for one bilinear fetch of the 1-spp image (rsaa_table.c).
 *
 * Subsamples come from "virtual samples": G-buffer outputs cannot be multisampled here (the renderer
 * refuses G-buffer outputs on multisampled targets, and lavapipe has 4x only and no integer MSAA
 * targets), so the G-buffer pass is rasterised once per standard position, geometry jittered so that the
 * position lands on the pixel centre, and a compute pre-pass turns each into that subsample's difference
 * from the centre. Only the differences are kept (two half floats per 32-bit channel, as the paper keeps
 * per-subsample SADP rather than positions). A hardware path (per-sample G-buffer attributes in one MSAA
 * pass, the paper's pull-model evaluation) would need the renderer to support multisampled G-buffer
 * targets; it is not written. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gpu/sample_positions.h"
#include "gpu/compute_pass.h"
#include "render/renderer.h"
#include "types/method.h"
#include "methods/rsaa_table.h"

static const int rsaa_sample_counts[] = {4, 8, 0};
static const char *const rsaa_similarities[] = {"sadp", "depth", NULL};

static const struct aa_param_def rsaa_params[] = {
	{.name = "samples", .type = AA_PARAM_INT, .def = 8, .min = 4, .max = 8, .allowed = rsaa_sample_counts,
	 .help = "geometric subsamples per pixel, at the Vulkan standard sample locations"},
	{.name = "similarity", .type = AA_PARAM_ENUM, .def = 0, .min = 0, .max = 1, .choices = rsaa_similarities,
	 .help = "sadp: sum of absolute dot products of normals and the joining direction; depth: view depth"},
	{.name = "auth", .type = AA_PARAM_INT, .def = 1, .min = 0, .max = 2,
	 .help = "authentication of offsets: 0 off, 1 post-process (halve), 2 pre-pass (reclassify)"},
	{.name = "alpha_to_coverage", .type = AA_PARAM_BOOL, .def = 0, .min = 0, .max = 1,
	 .help = "cut-out materials: each geometric subsample is kept iff alpha where it lies reaches the "
		 "cutoff, instead of one alpha test per pixel"},
};

/* push constants of rsaa_prepass.comp / rsaa_resolve.comp */
struct rsaa_push {
	float camera[4], forward[4];
	int32_t config[4];    /* prepass: subsample, similarity, auth; resolve: samples, similarity, auth */
	int32_t neighbour[4]; /* prepass only: the outside pixel nearest the subsample */
};

/* std430 `Table` of rsaa_resolve.comp */
struct rsaa_table_gpu {
	float subsample[8][4];
	float offset[256][2];
};

struct aa_method_state {
	struct aa_renderer *r;
	int samples, similarity, auth;
	int neighbour[8][2];
	struct aa_scene_target centre;   /* 1-spp colour, centre position + normal */
	struct aa_scene_target subsample; /* reused for every subsample's G-buffer */
	struct aa_gpu_image differences; /* RGBA32UI: per subsample, half-float difference from the centre */
	struct aa_gpu_image output;      /* RGBA16F */
	struct aa_gpu_buffer table;
	struct aa_compute_pass prepass, resolve;
};

static void rsaa_destroy(struct aa_method_state *s)
{
	struct aa_gpu *gpu = s->r->gpu;
	aa_compute_pass_destroy(gpu, &s->prepass);
	aa_compute_pass_destroy(gpu, &s->resolve);
	aa_gpu_buffer_destroy(gpu, &s->table);
	aa_gpu_image_destroy(gpu, &s->differences);
	aa_gpu_image_destroy(gpu, &s->output);
	aa_scene_target_destroy(s->r, &s->subsample);
	aa_scene_target_destroy(s->r, &s->centre);
	free(s);
}

/* The outside pixel whose centre is nearest to subsample position pos (pixel units, [0,1)^2). */
static void nearest_neighbour(const float pos[2], int out[2])
{
	double best = INFINITY;
	for (int dy = -1; dy <= 1; dy++)
		for (int dx = -1; dx <= 1; dx++) {
			if (!dx && !dy)
				continue;
			double x = pos[0] - 0.5 - dx, y = pos[1] - 0.5 - dy, d = x * x + y * y;
			if (d < best - 1e-12) {
				best = d;
				out[0] = dx;
				out[1] = dy;
			}
		}
}

static int upload_table(struct aa_method_state *s, const struct rsaa_table *t, struct aa_method_result *info,
			struct aa_error *err)
{
	const float (*pos)[2] = aa_standard_sample_positions(s->samples);
	struct rsaa_table_gpu g;
	memset(&g, 0, sizeof g);
	for (int i = 0; i < s->samples; i++) {
		nearest_neighbour(pos[i], s->neighbour[i]);
		double x = pos[i][0] - 0.5, y = pos[i][1] - 0.5;
		g.subsample[i][0] = (float)s->neighbour[i][0];
		g.subsample[i][1] = (float)s->neighbour[i][1];
		g.subsample[i][2] = (float)(x * x + y * y);
	}
	memcpy(g.offset, t->offset, (size_t)t->masks * sizeof g.offset[0]);
	if (aa_gpu_buffer_upload(s->r->gpu, &s->table, &g, sizeof g, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, err))
		return -1;
	aa_method_result_add_memory(info, "offset table", sizeof g);
	return 0;
}

static int rsaa_create(struct aa_renderer *r, const struct aa_method_params *p, struct aa_method_result *info,
		       struct aa_method_state **out, struct aa_error *err)
{
	struct aa_method_state *s = calloc(1, sizeof *s);
	if (!s)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	s->r = r;
	s->samples = (int)p->v[0];
	s->similarity = (int)p->v[1];
	s->auth = (int)p->v[2];
	const struct rsaa_table *t = rsaa_table_get(s->samples);
	if (!t) {
		free(s);
		return aa_error_set(err, AA_ERR_INTERNAL, "", "could not train the RSAA offset table (out of memory)");
	}
	/* the trained table's classes, as the paper reports them (40 and 151 for its 8x pattern) */
	snprintf(info->path_taken, sizeof info->path_taken,
		 "virtual samples: %d G-buffer passes + centre; table: %d one-line, %d two-line, %d fallback masks",
		 s->samples, t->class_count[RSAA_CLASS_ONE_LINE], t->class_count[RSAA_CLASS_TWO_LINE],
		 t->class_count[RSAA_CLASS_FALLBACK]);
	struct aa_scene_target_desc d = {.samples = 1, .outputs = AA_OUT_POSITION | AA_OUT_NORMAL};
	/* an MSAA G-buffer's subsamples: geometry at each subsample, the alpha test once per pixel and
	 * triangle at its shading point (as the centre pass tests it), or alpha to coverage */
	struct aa_scene_target_desc sub = {.samples = 1, .outputs = AA_OUT_POSITION | AA_OUT_NORMAL,
					   .virtual_samples = (uint32_t)s->samples, .geometry_at_sample = true,
					   .alpha_to_coverage = p->v[3] != 0};
	VkImageUsageFlags storage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
				    VK_IMAGE_USAGE_SAMPLED_BIT;
	if (aa_scene_target_create_desc(r, &s->centre, r->width, r->height, &d, "centre", info, err) ||
	    aa_scene_target_create_desc(r, &s->subsample, r->width, r->height, &sub, "subsample", info, err) ||
	    aa_renderer_image_create(r, &s->differences, r->width, r->height, VK_FORMAT_R32G32B32A32_UINT,
				     storage, "subsample differences (RGBA32UI)", info,
				     err) ||
	    aa_renderer_image_create(r, &s->output, r->width, r->height, AA_SCENE_COLOR_FORMAT, storage,
				     "resolved colour", info, err) ||
	    upload_table(s, t, info, err))
		goto fail;
	struct aa_compute_binding centre_pos = {AA_COMPUTE_SAMPLED, &s->centre.extra[2], NULL};
	struct aa_compute_binding centre_normal = {AA_COMPUTE_SAMPLED, &s->centre.extra[3], NULL};
	struct aa_compute_binding diffs = {AA_COMPUTE_STORAGE_IMAGE, &s->differences, NULL};
	if (aa_compute_pass_create(r->gpu, &s->prepass, &(struct aa_compute_desc){
			.comp = "rsaa_prepass.comp", .binding_count = 5,
			.bindings = {centre_pos, centre_normal,
				     {AA_COMPUTE_SAMPLED, &s->subsample.extra[2], NULL},
				     {AA_COMPUTE_SAMPLED, &s->subsample.extra[3], NULL}, diffs},
			.push_size = sizeof(struct rsaa_push)}, err) ||
	    aa_compute_pass_create(r->gpu, &s->resolve, &(struct aa_compute_desc){
			.comp = "rsaa_resolve.comp", .binding_count = 6,
			.bindings = {{AA_COMPUTE_SAMPLED_LINEAR, s->centre.output, NULL}, diffs, centre_pos,
				     centre_normal, {AA_COMPUTE_STORAGE_BUFFER, NULL, &s->table},
				     {AA_COMPUTE_STORAGE_IMAGE, &s->output, NULL}},
			.push_size = sizeof(struct rsaa_push)}, err))
		goto fail;
	*out = s;
	return 0;
fail:
	rsaa_destroy(s);
	return -1;
}

static int rsaa_render(struct aa_method_state *s, struct aa_frame_ctx *ctx, struct aa_error *err)
{
	(void)err;
	struct rsaa_push push;
	memset(&push, 0, sizeof push);
	vec3 cam = ctx->camera.position, fwd = v3_normalize(v3_sub(ctx->camera.target, ctx->camera.position));
	float camera[4] = {cam.x, cam.y, cam.z, 0}, forward[4] = {fwd.x, fwd.y, fwd.z, 0};
	memcpy(push.camera, camera, sizeof camera);
	memcpy(push.forward, forward, sizeof forward);
	uint32_t gx = aa_compute_groups(ctx->width, 8), gy = aa_compute_groups(ctx->height, 8);

	int span = aa_gpu_timer_begin(ctx->cmd, ctx->timer, "scene-centre");
	aa_renderer_draw_scene(s->r, ctx->cmd, &s->centre, 0.0f, 0.0f);
	aa_gpu_timer_end(ctx->cmd, ctx->timer, span);

	const float (*pos)[2] = aa_standard_sample_positions(s->samples);
	span = aa_gpu_timer_begin(ctx->cmd, ctx->timer, "rsaa-subsamples");
	for (int i = 0; i < s->samples; i++) {
		/* the previous pre-pass reads this target: finish it before the next rasterisation */
		aa_gpu_full_barrier(ctx->cmd);
		aa_renderer_draw_scene(s->r, ctx->cmd, &s->subsample, 0.5f - pos[i][0], 0.5f - pos[i][1]);
		push.config[0] = i;
		push.config[1] = s->similarity;
		push.config[2] = s->auth;
		push.neighbour[0] = s->neighbour[i][0];
		push.neighbour[1] = s->neighbour[i][1];
		aa_compute_pass_dispatch(ctx->cmd, &s->prepass, &push, sizeof push, gx, gy, 1);
	}
	aa_gpu_timer_end(ctx->cmd, ctx->timer, span);

	span = aa_gpu_timer_begin(ctx->cmd, ctx->timer, "rsaa-resolve");
	push.config[0] = s->samples;
	push.neighbour[0] = push.neighbour[1] = 0;
	aa_compute_pass_dispatch(ctx->cmd, &s->resolve, &push, sizeof push, gx, gy, 1);
	aa_gpu_timer_end(ctx->cmd, ctx->timer, span);
	ctx->output = &s->output;
	return 0;
}

static void rsaa_reset(struct aa_method_state *s) { (void)s; }

const struct aa_method aa_method_rsaa = {
	.name = "rsaa",
	.summary = "resampling AA: geometric subsamples -> similarity mask -> one bilinear fetch at a trained offset",
	.seed = "seed 002 (Reshetov, HPG 2012)",
	.params = rsaa_params,
	.param_count = 4,
	.main_param = "samples",
	.needs = AA_NEED_GBUFFER | AA_NEED_SUBSAMPLES,
	.alpha_rule = AA_ALPHA_PER_PIXEL,
	.create = rsaa_create,
	.render = rsaa_render,
	.reset = rsaa_reset,
	.destroy = rsaa_destroy,
};
