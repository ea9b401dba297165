/* `user`: a user's own method from a method file (docs/user-methods.md). Each frame it draws the scene
 * (jittered when the file asks) into a target with the G-buffer outputs its passes read, then records the
 * passes in order, each a full-screen fragment pass or an 8x8 compute dispatch over the frame, timed as
 * its own span; a pass read as previous:NAME keeps two images and alternates between them. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gpu/compute_pass.h"
#include "render/renderer.h"
#include "methods/jitter.h"
#include "methods/user_method.h"

/* std430 layout of AaPush in the prelude (aa_user_pass_glsl): 44 bytes, then one 32-bit word a parameter */
struct user_push {
	float size[4];
	float jitter[2];
	float prev_jitter[2];
	int32_t frame;
	int32_t history_frames;
	float time;
	uint32_t params[AA_MAX_PARAMS];
};
_Static_assert(offsetof(struct user_push, params) == 44, "the prelude's AaPush puts params at 44");
_Static_assert(sizeof(struct user_push) <= 128, "push constants within Vulkan's guaranteed 128 bytes");
_Static_assert(AA_USER_MAX_READS <= AA_PASS_MAX_SOURCES, "a fragment pass binds every read");
_Static_assert(AA_USER_MAX_READS + 1 <= AA_COMPUTE_MAX_BINDINGS, "a compute pass binds every read and its output");

struct user_pass_gpu {
	struct aa_gpu_image image[2];       /* [1] only for a pass kept for the next frame */
	struct aa_fullscreen_pass fragment[2]; /* one per parity when the method keeps history */
	struct aa_compute_pass compute[2];
	struct aa_shader_code code;
};

struct aa_method_state {
	struct aa_renderer *r;
	const struct aa_user_method *um;
	struct aa_scene_target scene;
	struct user_pass_gpu passes[AA_USER_MAX_PASSES];
	int parities;                       /* 2 when some pass is kept, else 1 */
	int parity;                         /* this frame writes image[parity] of kept passes */
	int history_frames;
	struct user_push push;
};

static void user_destroy(struct aa_method_state *s)
{
	struct aa_renderer *r = s->r;
	for (int i = 0; i < AA_USER_MAX_PASSES; i++)
		for (int k = 0; k < 2; k++) {
			aa_fullscreen_pass_destroy(r, &s->passes[i].fragment[k]);
			aa_compute_pass_destroy(r->gpu, &s->passes[i].compute[k]);
			aa_gpu_image_destroy(r->gpu, &s->passes[i].image[k]);
		}
	aa_scene_target_destroy(r, &s->scene);
	aa_method_unref(&s->um->method);
	free(s);
}

/* The image pass i writes at parity k. */
static struct aa_gpu_image *pass_image(struct aa_method_state *s, int i, int k)
{
	return &s->passes[i].image[s->um->passes[i].kept ? k : 0];
}

static struct aa_gpu_image *read_image(struct aa_method_state *s, const struct aa_user_read *rd, int k)
{
	switch (rd->input) {
	case AA_USER_IN_COLOUR: return s->scene.output;
	case AA_USER_IN_DEPTH: return &s->scene.depth;
	case AA_USER_IN_VELOCITY: return &s->scene.extra[0];
	case AA_USER_IN_IDS: return &s->scene.extra[1];
	case AA_USER_IN_NORMALS: return &s->scene.extra[3];
	case AA_USER_IN_PASS: return pass_image(s, rd->pass, k);
	case AA_USER_IN_PREVIOUS: return pass_image(s, rd->pass, 1 - k);
	}
	return NULL;
}

static int create_images(struct aa_method_state *s, struct aa_method_result *info, struct aa_error *err)
{
	const struct aa_user_method *um = s->um;
	struct aa_renderer *r = s->r;
	unsigned needs = um->method.needs;
	bool depth = false;
	for (int i = 0; i < um->pass_count; i++)
		for (int k = 0; k < um->passes[i].read_count; k++)
			depth |= um->passes[i].reads[k].input == AA_USER_IN_DEPTH;
	/* only the outputs the passes read: a method that reads colour alone draws a plain scene target */
	struct aa_scene_target_desc d = {
		.samples = 1, .depth_readable = depth,
		.outputs = (needs & AA_NEED_VELOCITY ? AA_OUT_VELOCITY : 0u) | (needs & AA_NEED_IDS ? AA_OUT_IDS : 0u) |
			   (needs & AA_NEED_GBUFFER ? AA_OUT_NORMAL : 0u),
	};
	if (aa_scene_target_create_desc(r, &s->scene, r->width, r->height, &d, "scene", info, err))
		return -1;
	for (int i = 0; i < um->pass_count; i++) {
		const struct aa_user_pass *pass = &um->passes[i];
		VkImageUsageFlags usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
					  VK_IMAGE_USAGE_TRANSFER_DST_BIT |
					  (pass->compute ? VK_IMAGE_USAGE_STORAGE_BIT : VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT);
		for (int k = 0; k < (pass->kept ? 2 : 1); k++) {
			char name[48];
			snprintf(name, sizeof name, "%s%s", pass->name, pass->kept ? (k ? " B" : " A") : "");
			if (aa_renderer_image_create(r, &s->passes[i].image[k], r->width, r->height,
						     (VkFormat)aa_user_format_vk(pass->format), usage, name, info, err))
				return -1;
		}
	}
	return 0;
}

static int create_passes(struct aa_method_state *s, struct aa_error *err)
{
	const struct aa_user_method *um = s->um;
	struct aa_renderer *r = s->r;
	for (int i = 0; i < um->pass_count; i++) {
		const struct aa_user_pass *pass = &um->passes[i];
		struct user_pass_gpu *g = &s->passes[i];
		g->code = (struct aa_shader_code){.name = pass->shader, .words = pass->spirv, .size = pass->spirv_size};
		for (int k = 0; k < s->parities; k++) {
			int rc;
			if (pass->compute) {
				struct aa_compute_desc cd = {.comp = pass->shader, .comp_code = &g->code,
							     .binding_count = pass->read_count + 1,
							     .push_size = aa_user_push_size(um)};
				for (int j = 0; j < pass->read_count; j++)
					cd.bindings[j] = (struct aa_compute_binding){
						.kind = pass->reads[j].linear ? AA_COMPUTE_SAMPLED_LINEAR : AA_COMPUTE_SAMPLED,
						.image = read_image(s, &pass->reads[j], k)};
				cd.bindings[pass->read_count] = (struct aa_compute_binding){
					.kind = AA_COMPUTE_STORAGE_IMAGE, .image = pass_image(s, i, k)};
				rc = aa_compute_pass_create(r->gpu, &g->compute[k], &cd, err);
			} else {
				struct aa_fullscreen_desc fd = {.frag = pass->shader, .frag_code = &g->code,
								.source_count = pass->read_count,
								.target = pass_image(s, i, k),
								.push_size = aa_user_push_size(um)};
				for (int j = 0; j < pass->read_count; j++) {
					fd.sources[j] = read_image(s, &pass->reads[j], k);
					fd.linear[j] = pass->reads[j].linear;
				}
				rc = aa_fullscreen_pass_create(r, &g->fragment[k], &fd, err);
			}
			if (rc) {
				aa_error_prefix(err, "%s: pass %s", um->file, pass->name);
				return -1;
			}
		}
	}
	return 0;
}

/* Kept images start cleared and readable: the first frame binds them (history_frames 0 says they are
 * empty) before anything was written. */
static int clear_kept(struct aa_method_state *s, struct aa_error *err)
{
	VkCommandBuffer cmd;
	if (aa_gpu_begin(s->r->gpu, &cmd, err))
		return -1;
	VkClearColorValue zero = {.float32 = {0, 0, 0, 0}};
	VkImageSubresourceRange range = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
	for (int i = 0; i < s->um->pass_count; i++)
		for (int k = 0; s->um->passes[i].kept && k < 2; k++) {
			struct aa_gpu_image *img = &s->passes[i].image[k];
			aa_gpu_image_barrier(cmd, img, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
			vkCmdClearColorImage(cmd, img->image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero, 1, &range);
			aa_gpu_image_barrier(cmd, img, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
		}
	return aa_gpu_submit_wait(s->r->gpu, cmd, err);
}

/* The parameters as the shader's AaParams holds them: float bits, int, bool as 0/1, enum as its index. */
static void fill_params(struct aa_method_state *s, const struct aa_method_params *p)
{
	const struct aa_method *m = &s->um->method;
	for (int i = 0; i < m->param_count; i++) {
		if (m->params[i].type == AA_PARAM_FLOAT) {
			float f = (float)p->v[i];
			memcpy(&s->push.params[i], &f, sizeof f);
		} else {
			int32_t v = (int32_t)p->v[i];
			memcpy(&s->push.params[i], &v, sizeof v);
		}
	}
}

int aa_user_method_create(const struct aa_method *m, struct aa_renderer *r, const struct aa_method_params *p,
			  struct aa_method_result *info, struct aa_method_state **out, struct aa_error *err)
{
	struct aa_user_method *um = (struct aa_user_method *)(void *)m;
	if (aa_user_method_compile(um, err))
		return -1;
	struct aa_method_state *s = calloc(1, sizeof *s);
	if (!s)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	s->r = r;
	s->um = um;
	aa_method_ref(m); /* the state may outlive the job spec that named the method */
	s->parities = 1;
	int fragment = 0, compute = 0;
	for (int i = 0; i < um->pass_count; i++) {
		s->parities = um->passes[i].kept ? 2 : s->parities;
		compute += um->passes[i].compute;
		fragment += !um->passes[i].compute;
	}
	fill_params(s, p);
	char jitter[32] = "no jitter";
	if (um->jitter_length)
		snprintf(jitter, sizeof jitter, "Halton(2,3) x%d jitter", um->jitter_length);
	snprintf(info->path_taken, sizeof info->path_taken, "user method %.40s: %d fragment + %d compute pass%s, %s, "
		 "SPIR-V %s", um->file, fragment, compute, fragment + compute > 1 ? "es" : "", jitter,
		 um->compiled_from_cache ? "from the cache" : "compiled");
	if (create_images(s, info, err) || create_passes(s, err) || (s->parities == 2 && clear_kept(s, err))) {
		user_destroy(s);
		return -1;
	}
	*out = s;
	return 0;
}

/* Sampled images must be readable before a pass binds them: a compute pass leaves its output GENERAL,
 * a render pass leaves it SHADER_READ_ONLY_OPTIMAL. */
static void make_readable(VkCommandBuffer cmd, struct aa_method_state *s, const struct aa_user_pass *pass, int k)
{
	for (int j = 0; j < pass->read_count; j++) {
		struct aa_gpu_image *img = read_image(s, &pass->reads[j], k);
		if (img->layout != VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
			aa_gpu_image_barrier(cmd, img, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
	}
}

static int user_render(struct aa_method_state *s, struct aa_frame_ctx *ctx, struct aa_error *err)
{
	(void)err;
	const struct aa_user_method *um = s->um;
	struct aa_renderer *r = s->r;
	float jitter[2] = {0, 0}, prev[2] = {0, 0};
	if (um->jitter_length) {
		aa_jitter_halton(ctx->frame, um->jitter_length, jitter);
		if (ctx->frame > 0)
			aa_jitter_halton(ctx->frame - 1, um->jitter_length, prev);
	}
	int span = aa_gpu_timer_begin(ctx->cmd, ctx->timer, "scene");
	aa_renderer_draw_scene(r, ctx->cmd, &s->scene, jitter[0], jitter[1]);
	aa_gpu_timer_end(ctx->cmd, ctx->timer, span);
	struct user_push *push = &s->push;
	push->size[0] = (float)r->width;
	push->size[1] = (float)r->height;
	push->size[2] = 1.0f / (float)r->width;
	push->size[3] = 1.0f / (float)r->height;
	memcpy(push->jitter, jitter, sizeof jitter);
	memcpy(push->prev_jitter, prev, sizeof prev);
	push->frame = ctx->frame;
	push->history_frames = s->history_frames;
	push->time = (float)ctx->time;
	const uint32_t push_size = aa_user_push_size(um);
	const int k = s->parity;
	for (int i = 0; i < um->pass_count; i++) {
		const struct aa_user_pass *pass = &um->passes[i];
		struct user_pass_gpu *g = &s->passes[i];
		const int variant = s->parities == 2 ? k : 0;
		span = aa_gpu_timer_begin(ctx->cmd, ctx->timer, pass->name);
		if (pass->compute) {
			aa_compute_pass_dispatch(ctx->cmd, &g->compute[variant], push, push_size,
						 aa_compute_groups(r->width, 8), aa_compute_groups(r->height, 8), 1);
		} else {
			make_readable(ctx->cmd, s, pass, variant);
			aa_fullscreen_pass_record(r, ctx->cmd, &g->fragment[variant], push, push_size);
		}
		aa_gpu_timer_end(ctx->cmd, ctx->timer, span);
	}
	if (s->parities == 2)
		s->parity = 1 - k;
	if (s->history_frames < 1000000)
		s->history_frames++;
	ctx->output = pass_image(s, um->pass_count - 1, k);
	return 0;
}

static void user_reset(struct aa_method_state *s)
{
	s->history_frames = 0;
}

/* What every user method shares; user_method_file.c fills in the name, parameters and needs. */
const struct aa_method aa_user_method_functions = {
	.name = "user",
	.render = user_render,
	.reset = user_reset,
	.destroy = user_destroy,
	.create_self = aa_user_method_create,
};

/* `user` as `aalab methods` and aalabd's `methods` describe it: a job names a method file
 * (user:file=...), which job_spec.c reads into a method of its own. */
const struct aa_method aa_method_user = {
	.name = "user",
	.summary = "your own GLSL passes from a method file: user:file=FILE.json[,PARAM=VALUE...]",
	.seed = "docs/user-methods.md",
};
