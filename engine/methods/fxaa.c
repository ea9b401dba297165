/* `fxaa`: FXAA 3.11 (quality path) as a pixel shader. A luma pass encodes the scene to sRGB with luma in
 * alpha; the FXAA pass finds edges by local contrast, searches along each edge for its ends with the
 * preset's steps and blends across it with one bilinear fetch (seed 003, seed 000 section 3.4). */
#include <stdio.h>
#include <stdlib.h>

#include "render/renderer.h"
#include "methods/fxaa.h"
#include "types/method.h"

/* FXAA 3.11's quality presets: FXAA_QUALITY__PS steps of FXAA_QUALITY__P0.. pixels. 10-15 "medium
 * dither", 20-29 "less dither", 39 "no dither"; 12 is FXAA 3.11's default. */
static const struct {
	int preset;
	int count;
	float steps[AA_FXAA_MAX_STEPS];
} presets[] = {
	{10, 3, {1.5f, 3.0f, 12.0f}},
	{11, 4, {1.0f, 1.5f, 3.0f, 12.0f}},
	{12, 5, {1.0f, 1.5f, 2.0f, 4.0f, 12.0f}},
	{13, 6, {1.0f, 1.5f, 2.0f, 2.0f, 4.0f, 12.0f}},
	{14, 7, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 4.0f, 12.0f}},
	{15, 8, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 12.0f}},
	{20, 3, {1.5f, 2.0f, 8.0f}},
	{21, 4, {1.0f, 1.5f, 2.0f, 8.0f}},
	{22, 5, {1.0f, 1.5f, 2.0f, 2.0f, 8.0f}},
	{23, 6, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 8.0f}},
	{24, 7, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 3.0f, 8.0f}},
	{25, 8, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}},
	{26, 9, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}},
	{27, 10, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}},
	{28, 11, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}},
	{29, 12, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}},
	{39, 12, {1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}},
};
#define PRESET_COUNT ((int)(sizeof presets / sizeof presets[0]))

static const int fxaa_preset_values[] = {10, 11, 12, 13, 14, 15, 20, 21, 22, 23, 24, 25, 26, 27, 28, 29, 39, 0};

const struct aa_param_def aa_fxaa_params[AA_FXAA_PARAM_COUNT] = {
	{.name = "preset", .type = AA_PARAM_INT, .def = 12, .min = 10, .max = 39, .allowed = fxaa_preset_values,
	 .help = "FXAA 3.11 quality preset: 10-15 and 20-29 (last digit: more search steps), 39 (finest steps)"},
	{.name = "subpix", .type = AA_PARAM_FLOAT, .def = 0.75, .min = 0.0, .max = 1.0,
	 .help = "amount of subpixel aliasing removal: 0 off, 0.75 default, 1 softest"},
	{.name = "edge_threshold", .type = AA_PARAM_FLOAT, .def = 0.166, .min = 0.0, .max = 1.0,
	 .help = "minimum local contrast, relative to the local maximum luma, to process a pixel"},
	{.name = "edge_threshold_min", .type = AA_PARAM_FLOAT, .def = 0.0833, .min = 0.0, .max = 1.0,
	 .help = "minimum local contrast in absolute luma: skips dark areas"},
};

enum { PARAM_PRESET, PARAM_SUBPIX, PARAM_EDGE_THRESHOLD, PARAM_EDGE_THRESHOLD_MIN };

static int preset_index(const struct aa_method_params *p)
{
	int want = (int)p->v[PARAM_PRESET];
	for (int i = 0; i < PRESET_COUNT; i++)
		if (presets[i].preset == want)
			return i;
	return 2; /* the parser only lets listed presets through; 12 otherwise */
}

void aa_fxaa_spec_init(struct aa_fxaa_spec *spec, const struct aa_method_params *p, bool horizontal)
{
	int k = preset_index(p);
	spec->data.step_count = presets[k].count;
	for (int i = 0; i < AA_FXAA_MAX_STEPS; i++)
		spec->data.steps[i] = presets[k].steps[i];
	spec->data.horizontal = horizontal ? VK_TRUE : VK_FALSE;
	spec->entries[0] = (VkSpecializationMapEntry){0, offsetof(struct aa_fxaa_spec_data, step_count),
						      sizeof(int32_t)};
	for (uint32_t i = 0; i < AA_FXAA_MAX_STEPS; i++)
		spec->entries[1 + i] = (VkSpecializationMapEntry){
			1 + i, (uint32_t)(offsetof(struct aa_fxaa_spec_data, steps) + i * sizeof(float)), sizeof(float)};
	spec->entries[AA_FXAA_MAX_STEPS + 1] = (VkSpecializationMapEntry){
		AA_FXAA_MAX_STEPS + 1, offsetof(struct aa_fxaa_spec_data, horizontal), sizeof(VkBool32)};
	spec->info = (VkSpecializationInfo){
		.mapEntryCount = AA_FXAA_MAX_STEPS + 2,
		.pMapEntries = spec->entries,
		.dataSize = sizeof spec->data,
		.pData = &spec->data,
	};
}

void aa_fxaa_push_init(struct aa_fxaa_push *push, const struct aa_method_params *p)
{
	push->subpix = (float)p->v[PARAM_SUBPIX];
	push->edge_threshold = (float)p->v[PARAM_EDGE_THRESHOLD];
	push->edge_threshold_min = (float)p->v[PARAM_EDGE_THRESHOLD_MIN];
	push->unused = 0.0f;
}

void aa_fxaa_describe(const struct aa_method_params *p, char *out, size_t size)
{
	int k = preset_index(p);
	snprintf(out, size, "preset %d, %d search steps", presets[k].preset, presets[k].count);
}

/* The edge mask's depth format: two values (0 edge, 1 not), the smallest depth format there is. The edge
 * pass clears it to 1 and draws the full-screen triangle's depth 0 (compare ALWAYS) on edge pixels only,
 * discarding the others: most pixels write nothing. */
#define EDGE_MASK_FORMAT VK_FORMAT_D16_UNORM

/* A pass of our own (not aa_fullscreen_pass): the edge mask needs a depth attachment. */
struct fxaa_pass {
	struct aa_gpu_pipeline pipeline;
	VkRenderPass render_pass;
	VkFramebuffer framebuffer;
	VkDescriptorSet set;
};

struct aa_method_state {
	struct aa_renderer *r;
	struct aa_scene_target target;   /* the scene; FXAA's output too: edge pixels are drawn into it */
	struct aa_gpu_image luma, edge_mask;
	struct aa_fullscreen_pass luma_pass;
	struct fxaa_pass edges, resolve;
	struct aa_fxaa_spec spec;
	struct aa_fxaa_push push;
};

static void fxaa_pass_destroy(struct aa_renderer *r, struct fxaa_pass *p)
{
	if (p->framebuffer)
		vkDestroyFramebuffer(r->gpu->device, p->framebuffer, NULL);
	if (p->render_pass)
		vkDestroyRenderPass(r->gpu->device, p->render_pass, NULL);
	aa_gpu_pipeline_destroy(r->gpu, &p->pipeline);
}

static void fxaa_destroy(struct aa_method_state *s)
{
	fxaa_pass_destroy(s->r, &s->resolve);
	fxaa_pass_destroy(s->r, &s->edges);
	aa_fullscreen_pass_destroy(s->r, &s->luma_pass);
	aa_gpu_image_destroy(s->r->gpu, &s->edge_mask);
	aa_gpu_image_destroy(s->r->gpu, &s->luma);
	aa_scene_target_destroy(s->r, &s->target);
	free(s);
}

/* A full-screen pass over the luma texture into `colour` (or none) and the edge mask. */
static int fxaa_pass_create(struct aa_method_state *s, struct fxaa_pass *p, const char *frag,
			    struct aa_gpu_image *colour, bool resolve, struct aa_error *err)
{
	struct aa_renderer *r = s->r;
	struct aa_gpu_pass_desc pd = {
		.color_count = colour ? 1 : 0, .color_formats = {colour ? colour->format : VK_FORMAT_UNDEFINED},
		.color_load = {true}, .depth_format = EDGE_MASK_FORMAT, .samples = 1,
		.depth_load = resolve, .depth_store = !resolve,
	};
	VkDescriptorType types[1] = {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER};
	struct aa_gpu_image *att[2];
	int n = 0;
	if (colour)
		att[n++] = colour;
	att[n++] = &s->edge_mask;
	if (aa_gpu_render_pass_create(r->gpu, &pd, &p->render_pass, err) ||
	    aa_gpu_layout_create(r->gpu, types, NULL, 1, sizeof s->push, &p->pipeline, err))
		return -1;
	struct aa_gpu_graphics_desc g = {
		.vert = "fullscreen.vert", .frag = frag, .vertex_layout = AA_VERTEX_NONE,
		.render_pass = p->render_pass, .color_count = pd.color_count, .samples = 1,
		.cull = VK_CULL_MODE_NONE, .depth_test = true, .depth_write = !resolve, .depth_always = !resolve,
		.layout = p->pipeline.layout, .frag_specialization = resolve ? &s->spec.info : NULL,
	};
	if (aa_gpu_graphics_pipeline_create(r->gpu, &g, &p->pipeline, err) ||
	    aa_gpu_descriptor_set_alloc(r->gpu, r->pass_pool, &p->pipeline, &p->set, err) ||
	    aa_gpu_framebuffer_create(r->gpu, p->render_pass, att, n, &p->framebuffer, err))
		return -1;
	aa_gpu_write_image(r->gpu, p->set, 0, 0, types[0], resolve ? r->gpu->sampler_linear_clamp
								    : r->gpu->sampler_nearest,
			   &s->luma, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
	return 0;
}

static int fxaa_create(struct aa_renderer *r, const struct aa_method_params *p, struct aa_method_result *info,
		       struct aa_method_state **out, struct aa_error *err)
{
	struct aa_method_state *s = calloc(1, sizeof *s);
	if (!s)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	s->r = r;
	aa_fxaa_spec_init(&s->spec, p, true);
	aa_fxaa_push_init(&s->push, p);
	char desc[40];
	aa_fxaa_describe(p, desc, sizeof desc);
	snprintf(info->path_taken, sizeof info->path_taken, "pixel shader on edge pixels (depth mask), %s", desc);
	const VkImageUsageFlags pass_target = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
	if (aa_scene_target_create(r, &s->target, r->width, r->height, "scene", info, err) ||
	    aa_renderer_image_create(r, &s->luma, r->width, r->height, VK_FORMAT_R8G8B8A8_UNORM, pass_target,
				     "sRGB colour + luma", info, err) ||
	    aa_renderer_image_create(r, &s->edge_mask, r->width, r->height, EDGE_MASK_FORMAT,
				     VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, "edge mask (depth)", info, err) ||
	    aa_fullscreen_pass_create(r, &s->luma_pass, &(struct aa_fullscreen_desc){
			.frag = "fxaa_luma.frag", .source_count = 1, .sources = {&s->target.color},
			.target = &s->luma}, err) ||
	    fxaa_pass_create(s, &s->edges, "fxaa_edges.frag", NULL, false, err) ||
	    fxaa_pass_create(s, &s->resolve, "fxaa.frag", &s->target.color, true, err)) {
		fxaa_destroy(s);
		return -1;
	}
	*out = s;
	return 0;
}

static void fxaa_pass_record(struct aa_method_state *s, VkCommandBuffer cmd, struct fxaa_pass *p)
{
	/* the edge mask is cleared to 1 ("leave alone"); the edge pass draws the triangle's depth 0 on edges */
	VkClearValue clear[2] = {{.color = {.float32 = {0, 0, 0, 0}}}, {.depthStencil = {1.0f, 0}}};
	aa_gpu_begin_pass(cmd, p->render_pass, p->framebuffer, s->r->width, s->r->height,
			  p == &s->edges ? &clear[1] : clear, p == &s->edges ? 1 : 2);
	aa_fullscreen_draw(cmd, &p->pipeline, p->set, &s->push, sizeof s->push);
}

static int fxaa_render(struct aa_method_state *s, struct aa_frame_ctx *ctx, struct aa_error *err)
{
	int span = aa_gpu_timer_begin(ctx->cmd, ctx->timer, "scene");
	aa_renderer_draw_scene(s->r, ctx->cmd, &s->target, 0.0f, 0.0f);
	aa_gpu_timer_end(ctx->cmd, ctx->timer, span);
	span = aa_gpu_timer_begin(ctx->cmd, ctx->timer, "fxaa-luma");
	aa_fullscreen_pass_record(s->r, ctx->cmd, &s->luma_pass, NULL, 0);
	aa_gpu_timer_end(ctx->cmd, ctx->timer, span);
	span = aa_gpu_timer_begin(ctx->cmd, ctx->timer, "fxaa-edges");
	fxaa_pass_record(s, ctx->cmd, &s->edges);
	s->edge_mask.layout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
	aa_gpu_timer_end(ctx->cmd, ctx->timer, span);
	span = aa_gpu_timer_begin(ctx->cmd, ctx->timer, "fxaa");
	aa_gpu_image_barrier(ctx->cmd, &s->target.color, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
	fxaa_pass_record(s, ctx->cmd, &s->resolve);
	aa_gpu_timer_end(ctx->cmd, ctx->timer, span);
	ctx->output = &s->target.color;
	return 0;
}

static void fxaa_reset(struct aa_method_state *s) { (void)s; }

const struct aa_method aa_method_fxaa = {
	.name = "fxaa",
	.summary = "FXAA 3.11 quality, pixel shader: luma pass, then edge search and one blended fetch",
	.seed = "seed 003; seed 000 section 3.4",
	.params = aa_fxaa_params,
	.param_count = AA_FXAA_PARAM_COUNT,
	.main_param = NULL,
	.needs = 0,
	.create = fxaa_create,
	.render = fxaa_render,
	.reset = fxaa_reset,
	.destroy = fxaa_destroy,
};
