/* TAA machinery: jittered G-buffer scene pass, the resolve into float history (production, accumulate or
 * seed 001's), sharpening for display, and taa-sobel's edge image with its stabiliser. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gpu/compute_pass.h"
#include "methods/jitter.h"
#include "methods/taa_impl.h"

struct aa_method_state {
	struct aa_renderer *r;
	struct aa_taa_config config;
	struct aa_scene_target scene;
	struct aa_gpu_image history[2];     /* ping-pong: frame k reads [k&1], writes [(k+1)&1] */
	struct aa_gpu_image run[2];         /* accumulate: still pixels' cycle under way and run length */
	struct aa_gpu_image positions;      /* accumulate: own-sample luma per jitter position (in place) */
	struct aa_gpu_image depth[2];       /* compute resolves, taa-sobel: linear depth of the previous frame */
	struct aa_gpu_image output;
	struct aa_gpu_image edges, sobel[2]; /* master: raw and stabilised Sobel images */
	struct aa_fullscreen_pass resolve[2], sharpen[2], edge_pass, stabilise[2];
	struct aa_compute_pass converge[2];
	int parity;
	bool history_valid;
	int history_frames;                 /* frames accumulated since the last reset */
};

/* seed 001's resolve and the Sobel stabiliser */
struct taa_push {
	float feedback_min, feedback_max;
	int32_t history_valid;
	float history_frames;
};

/* `Push` of shaders/taa_converge.glsl */
struct taa_converge_push {
	float jitter[2];
	int32_t size[2];
	float feedback_min, feedback_max, gamma, max_samples;
	int32_t cycle, jitter_index, history_valid, clip_variance, catmull_rom, clip_linear, tonemapped_resolve;
	float filter_weights[9];
	float current_weight;
};

/* production and accumulate: the compute resolve of shaders/taa_converge.glsl */
static bool converging(const struct aa_method_state *s)
{
	return s->config.preset != AA_TAA_PRESET_SEED001;
}

void aa_taa_destroy(struct aa_method_state *s)
{
	struct aa_renderer *r = s->r;
	for (int i = 0; i < 2; i++) {
		aa_fullscreen_pass_destroy(r, &s->resolve[i]);
		aa_compute_pass_destroy(r->gpu, &s->converge[i]);
		aa_fullscreen_pass_destroy(r, &s->sharpen[i]);
		aa_fullscreen_pass_destroy(r, &s->stabilise[i]);
		aa_gpu_image_destroy(r->gpu, &s->history[i]);
		aa_gpu_image_destroy(r->gpu, &s->run[i]);
		aa_gpu_image_destroy(r->gpu, &s->depth[i]);
		aa_gpu_image_destroy(r->gpu, &s->sobel[i]);
	}
	aa_fullscreen_pass_destroy(r, &s->edge_pass);
	aa_gpu_image_destroy(r->gpu, &s->edges);
	aa_gpu_image_destroy(r->gpu, &s->positions);
	aa_gpu_image_destroy(r->gpu, &s->output);
	aa_scene_target_destroy(r, &s->scene);
	free(s);
}

static const VkImageUsageFlags target_usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
					     VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
static const VkImageUsageFlags storage_usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
					      VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;

static int create_history(struct aa_method_state *s, struct aa_method_result *info, struct aa_error *err)
{
	struct aa_renderer *r = s->r;
	if (converging(s)) {
		/* float32: means over many frames must not stall on half-float steps. production keeps no
		 * cycle: its shader declares the cycle images but never reads or writes them, so they are 1x1 */
		bool production = s->config.preset == AA_TAA_PRESET_PRODUCTION;
		int cw = production ? 1 : r->width, ch = production ? 1 : r->height;
		static const char *const names[2][3] = {
			{"history A (RGBA32F: colour, sample count)", "cycle A (RGBA32F: own-sample mean, frames still)",
			 "depth A (R32F)"},
			{"history B (RGBA32F: colour, sample count)", "cycle B (RGBA32F: own-sample mean, frames still)",
			 "depth B (R32F)"}};
		for (int i = 0; i < 2; i++) {
			if (aa_renderer_image_create(r, &s->history[i], r->width, r->height,
						     VK_FORMAT_R32G32B32A32_SFLOAT, storage_usage, names[i][0], info, err) ||
			    aa_renderer_image_create(r, &s->run[i], cw, ch, VK_FORMAT_R32G32B32A32_SFLOAT,
						     storage_usage, names[i][1], info, err))
				return -1;
			if (s->config.master && aa_renderer_image_create(r, &s->depth[i], r->width, r->height,
									 VK_FORMAT_R32_SFLOAT, storage_usage,
									 names[i][2], info, err))
				return -1;
		}
		/* 16 lumas of 8 bits per pixel */
		return aa_renderer_image_create(r, &s->positions, cw, ch, VK_FORMAT_R32G32B32A32_UINT,
						storage_usage, "own-sample luma per jitter position (RGBA32UI)", info,
						err);
	}
	/* Master TAA keeps linear depth in the history's alpha, which needs float32 precision */
	VkFormat format = s->config.master ? VK_FORMAT_R32G32B32A32_SFLOAT : VK_FORMAT_R16G16B16A16_SFLOAT;
	for (int i = 0; i < 2; i++)
		if (aa_renderer_image_create(r, &s->history[i], r->width, r->height, format, target_usage,
					     i ? "history B" : "history A", info, err))
			return -1;
	return 0;
}

static int create_images(struct aa_method_state *s, struct aa_method_result *info, struct aa_error *err)
{
	struct aa_renderer *r = s->r;
	bool master = s->config.master;
	unsigned outputs = AA_OUT_VELOCITY | AA_OUT_SURFACE | (master ? AA_OUT_IDS : 0);
	struct aa_scene_target_desc d = {.samples = 1, .outputs = outputs};
	if (aa_scene_target_create_desc(r, &s->scene, r->width, r->height, &d, "scene", info, err) ||
	    create_history(s, info, err) ||
	    aa_renderer_image_create(r, &s->output, r->width, r->height, AA_SCENE_COLOR_FORMAT,
				     target_usage | (converging(s) ? VK_IMAGE_USAGE_STORAGE_BIT : 0), "displayed output",
				     info, err))
		return -1;
	if (master) {
		if (aa_renderer_image_create(r, &s->edges, r->width, r->height, VK_FORMAT_R16_SFLOAT, target_usage,
					     "sobel edges", info, err))
			return -1;
		for (int i = 0; i < 2; i++)
			if (aa_renderer_image_create(r, &s->sobel[i], r->width, r->height, VK_FORMAT_R16_SFLOAT,
						     target_usage, i ? "sobel history B" : "sobel history A", info,
						     err))
				return -1;
	}
	return 0;
}

/* The resolve of frame parity k: reads history[k], writes history[1 - k]. */
static int create_resolve(struct aa_method_state *s, int k, struct aa_error *err)
{
	struct aa_renderer *r = s->r;
	bool master = s->config.master;
	int read = k, write = 1 - k;
	struct aa_gpu_image *velocity = &s->scene.extra[0], *ids = &s->scene.extra[1], *surface = &s->scene.extra[4];
	if (converging(s)) {
		struct aa_compute_desc d = {
			.comp = s->config.preset == AA_TAA_PRESET_PRODUCTION ?
				(master ? "taa_master_production.comp" : "taa_production.comp") :
				(master ? "taa_master_converge.comp" : "taa_converge.comp"),
			.binding_count = master ? 13 : 9,
			.push_size = sizeof(struct taa_converge_push),
			.bindings = {
				{AA_COMPUTE_SAMPLED, s->scene.output, NULL},
				{AA_COMPUTE_SAMPLED_LINEAR, &s->history[read], NULL},
				{AA_COMPUTE_SAMPLED, &s->run[read], NULL},
				{AA_COMPUTE_SAMPLED, velocity, NULL},
				{AA_COMPUTE_SAMPLED, surface, NULL},
				{AA_COMPUTE_STORAGE_IMAGE, &s->history[write], NULL},
				{AA_COMPUTE_STORAGE_IMAGE, &s->run[write], NULL},
				{AA_COMPUTE_STORAGE_IMAGE, &s->positions, NULL},
				{AA_COMPUTE_SAMPLED, ids, NULL},
				{AA_COMPUTE_SAMPLED, &s->sobel[write], NULL},
				{AA_COMPUTE_SAMPLED, &s->depth[read], NULL},
				{AA_COMPUTE_STORAGE_IMAGE, &s->depth[write], NULL},
			},
		};
		/* the displayed output, written by the resolve itself (binding 8, or 12 after Master TAA's) */
		d.bindings[master ? 12 : 8] = (struct aa_compute_binding){AA_COMPUTE_STORAGE_IMAGE, &s->output, NULL};
		return aa_compute_pass_create(r->gpu, &s->converge[k], &d, err);
	}
	/* Master TAA also reads the model IDs and this frame's stabilised Sobel image. The resolve writes the
	 * displayed output too, unless the sharpen pass writes it from history. */
	struct aa_fullscreen_desc resolve = {
		.frag = master ? "taa_master_resolve.frag" : "taa_resolve.frag",
		.source_count = master ? 6 : 4,
		.sources = {s->scene.output, &s->history[read], velocity, surface, ids, &s->sobel[write]},
		.linear = {false, true, false, false, false, false},
		.target = &s->history[write], .push_size = sizeof(struct taa_push), .outputs = 2,
		.second_target = s->config.sharpen == AA_TAA_SHARPEN_OFF ? &s->output : NULL,
	};
	return aa_fullscreen_pass_create(r, &s->resolve[k], &resolve, err);
}

static int create_passes(struct aa_method_state *s, struct aa_error *err)
{
	struct aa_renderer *r = s->r;
	bool master = s->config.master;
	struct aa_gpu_image *velocity = &s->scene.extra[0], *surface = &s->scene.extra[4];
	if (master && aa_fullscreen_pass_create(r, &s->edge_pass, &(struct aa_fullscreen_desc){
			.frag = "taa_sobel_edges.frag", .source_count = 2, .sources = {s->scene.output, surface},
			.target = &s->edges, .push_size = sizeof(int32_t)}, err))
		return -1;
	for (int k = 0; k < 2; k++) {
		int read = k, write = 1 - k;
		if (create_resolve(s, k, err))
			return -1;
		/* with sharpen off the resolve writes the displayed output: no sharpen pass to make */
		if (s->config.sharpen != AA_TAA_SHARPEN_OFF &&
		    aa_fullscreen_pass_create(r, &s->sharpen[k], &(struct aa_fullscreen_desc){
				.frag = "taa_sharpen.frag", .source_count = 1, .sources = {&s->history[write]},
				.target = &s->output, .push_size = sizeof(int32_t)}, err))
			return -1;
		if (master && aa_fullscreen_pass_create(r, &s->stabilise[k], &(struct aa_fullscreen_desc){
				.frag = "taa_sobel_stabilise.frag", .source_count = 3,
				.sources = {&s->edges, &s->sobel[read], velocity}, .linear = {false, true, false},
				.target = &s->sobel[write], .push_size = sizeof(struct taa_push)}, err))
			return -1;
	}
	return 0;
}

/* History images start cleared and in the layout the resolve reads them in: the first frame binds them
 * (and ignores them) before anything was written. */
static int clear_history(struct aa_method_state *s, struct aa_error *err)
{
	VkCommandBuffer cmd;
	if (aa_gpu_begin(s->r->gpu, &cmd, err))
		return -1;
	struct aa_gpu_image *images[9] = {&s->history[0], &s->history[1], &s->run[0], &s->run[1],
					  &s->depth[0], &s->depth[1], &s->positions, &s->sobel[0], &s->sobel[1]};
	VkClearColorValue zero = {.float32 = {0, 0, 0, 0}};
	VkImageSubresourceRange range = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
	for (int i = 0; i < 9; i++) {
		if (!images[i]->image)
			continue;
		aa_gpu_image_barrier(cmd, images[i], VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
		vkCmdClearColorImage(cmd, images[i]->image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero, 1, &range);
		aa_gpu_image_barrier(cmd, images[i], VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
	}
	return aa_gpu_submit_wait(s->r->gpu, cmd, err);
}

static void describe(const struct aa_taa_config *c, struct aa_method_result *info)
{
	const char *box = c->master ? "Sobel/ID/depth" : "3x3+cross";
	if (c->preset == AA_TAA_PRESET_SEED001) {
		snprintf(info->path_taken, sizeof info->path_taken,
			 "preset seed001: Halton(2,3) x%d jitter, %s clip box, %s history", c->jitter_length, box,
			 c->master ? "RGBA32F" : "RGBA16F");
		return;
	}
	char clip[24] = "AABB";
	if (c->clip == AA_TAA_CLIP_VARIANCE) {
		snprintf(clip, sizeof clip, "variance %.3g", (double)c->gamma);
		box = c->master ? "Sobel/ID/depth" : "3x3";
	}
	char blend[64];
	if (c->preset == AA_TAA_PRESET_PRODUCTION)
		snprintf(blend, sizeof blend, "current weight %.3g, anti-flicker", (double)c->current_weight);
	else
		snprintf(blend, sizeof blend, "still pixels' exact mean <= %d samples", c->max_samples);
	char text[256]; /* longer than path_taken can be: cut to it */
	snprintf(text, sizeof text, "preset %s: Halton x%d, %s %s clip (%s), %s history, %s, %s",
		 c->preset == AA_TAA_PRESET_PRODUCTION ? "production" : "accumulate", c->jitter_length, box, clip,
		 c->clip_space == AA_TAA_CLIP_SPACE_LINEAR ? "linear" : "tonemapped",
		 c->history_filter == AA_TAA_HISTORY_CATMULL_ROM ? "Catmull-Rom" : "bilinear", blend,
		 c->tonemapped_resolve ? "Karis-weighted" : "linear blend");
	size_t n = strnlen(text, sizeof info->path_taken - 1);
	memcpy(info->path_taken, text, n);
	info->path_taken[n] = '\0';
}

int aa_taa_create(struct aa_renderer *r, const struct aa_taa_config *config, struct aa_method_result *info,
		  struct aa_method_state **out, struct aa_error *err)
{
	struct aa_method_state *s = calloc(1, sizeof *s);
	if (!s)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	s->r = r;
	s->config = *config;
	describe(config, info);
	if (create_images(s, info, err) || create_passes(s, err) || clear_history(s, err)) {
		aa_taa_destroy(s);
		return -1;
	}
	*out = s;
	return 0;
}

void aa_taa_reset(struct aa_method_state *s)
{
	s->history_valid = false;
	s->history_frames = 0;
}

/* The current frame's reconstruction at the pixel centre (Karis 2014; UE4's r.TemporalAAFilterSize):
 * each 3x3 sample weighted by exp(-2.29 (d / width)^2), d its distance from the centre (the sample of
 * pixel q shows the scene at q's centre minus the jitter). exp(-2.29 d^2) is UE4's Gaussian fit of
 * Blackman-Harris (sigma 0.47 px). Width 0.85 (sigma 0.40 px) measured against the box-filtered
 * reference (moving-sphere; first frame at 640x360 against none's 26.74 dB: 27.04 at 1.0, 27.50 at 0.85,
 * 26.47 at 0.7; 60 frames at 320x180: 23.58, 23.78, 23.91 dB mean). The weights depend on the jitter
 * only: computed here once a frame, as UE4 does, rather than per pixel. */
#define RECONSTRUCTION_WIDTH 0.85

static void reconstruction_weights(const float jitter[2], float out[9])
{
	for (int y = -1; y <= 1; y++)
		for (int x = -1; x <= 1; x++) {
			double dx = (x - jitter[0]) / RECONSTRUCTION_WIDTH, dy = (y - jitter[1]) / RECONSTRUCTION_WIDTH;
			out[(y + 1) * 3 + (x + 1)] = (float)exp(-2.29 * (dx * dx + dy * dy));
		}
}

static void record_resolve(struct aa_method_state *s, struct aa_frame_ctx *ctx, const float jitter[2])
{
	struct aa_renderer *r = s->r;
	int k = s->parity;
	if (!converging(s)) {
		struct taa_push push = {s->config.feedback_min, s->config.feedback_max, s->history_valid,
					(float)s->history_frames};
		aa_fullscreen_pass_record(r, ctx->cmd, &s->resolve[k], &push, sizeof push);
		return;
	}
	struct taa_converge_push push = {
		.jitter = {jitter[0], jitter[1]}, .size = {r->width, r->height},
		.feedback_min = s->config.feedback_min, .feedback_max = s->config.feedback_max,
		.gamma = s->config.gamma, .max_samples = (float)s->config.max_samples,
		.cycle = s->config.jitter_length, .jitter_index = ctx->frame % s->config.jitter_length,
		.history_valid = s->history_valid, .clip_variance = s->config.clip == AA_TAA_CLIP_VARIANCE,
		.catmull_rom = s->config.history_filter == AA_TAA_HISTORY_CATMULL_ROM,
		.clip_linear = s->config.clip_space == AA_TAA_CLIP_SPACE_LINEAR,
		.tonemapped_resolve = s->config.tonemapped_resolve, .current_weight = s->config.current_weight,
	};
	reconstruction_weights(jitter, push.filter_weights);
	aa_compute_pass_dispatch(ctx->cmd, &s->converge[k], &push, sizeof push, aa_compute_groups(r->width, 8),
				 aa_compute_groups(r->height, 8), 1);
	/* the sharpen pass, when on, samples what the compute pass wrote */
	aa_gpu_image_barrier(ctx->cmd, &s->history[1 - k], VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
}

int aa_taa_render(struct aa_method_state *s, struct aa_frame_ctx *ctx, struct aa_error *err)
{
	(void)err;
	struct aa_renderer *r = s->r;
	float jitter[2];
	aa_jitter_halton(ctx->frame, s->config.jitter_length, jitter);
	int span = aa_gpu_timer_begin(ctx->cmd, ctx->timer, "scene-gbuffer");
	aa_renderer_draw_scene(r, ctx->cmd, &s->scene, jitter[0], jitter[1]);
	aa_gpu_timer_end(ctx->cmd, ctx->timer, span);
	int k = s->parity;
	if (s->config.master) {
		span = aa_gpu_timer_begin(ctx->cmd, ctx->timer, "taa-sobel");
		int32_t tonemapped = converging(s);
		aa_fullscreen_pass_record(r, ctx->cmd, &s->edge_pass, &tonemapped, sizeof tonemapped);
		/* The Sobel image is stabilised by the colour's feedback law with a fixed, faster range:
		 * docs/methods.md (taa-sobel) says why 0.5/0.9 */
		struct taa_push sobel_push = {0.5f, 0.9f, s->history_valid, (float)s->history_frames};
		aa_fullscreen_pass_record(r, ctx->cmd, &s->stabilise[k], &sobel_push, sizeof sobel_push);
		aa_gpu_timer_end(ctx->cmd, ctx->timer, span);
	}
	span = aa_gpu_timer_begin(ctx->cmd, ctx->timer, "taa-resolve");
	record_resolve(s, ctx, jitter);
	aa_gpu_timer_end(ctx->cmd, ctx->timer, span);
	/* Every resolve writes the displayed output itself; with sharpen on, this pass writes it instead */
	if (s->config.sharpen != AA_TAA_SHARPEN_OFF) {
		span = aa_gpu_timer_begin(ctx->cmd, ctx->timer, "taa-sharpen");
		int32_t kind = (int32_t)s->config.sharpen;
		aa_fullscreen_pass_record(r, ctx->cmd, &s->sharpen[k], &kind, sizeof kind);
		aa_gpu_timer_end(ctx->cmd, ctx->timer, span);
	}
	s->parity = 1 - k;
	s->history_valid = true;
	if (s->history_frames < 1000000)
		s->history_frames++;
	ctx->output = &s->output;
	return 0;
}
