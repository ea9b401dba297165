/* `fxaa`: FXAA 3.11 (quality path) as a pixel shader. A luma pass encodes the scene to sRGB with luma in
 * alpha; the FXAA pass finds edges by local contrast, searches along each edge for its ends with the
 * preset's steps and blends across it with one bilinear fetch (seed 003, seed 000 section 3.4). */
#include <stdio.h>
#include <stdlib.h>

#include "../renderer.h"
#include "fxaa.h"
#include "method.h"

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

struct aa_method_state {
	struct aa_renderer *r;
	struct aa_scene_target target;
	struct aa_gpu_image luma, output;
	struct aa_fullscreen_pass luma_pass, fxaa_pass;
	struct aa_fxaa_spec spec;
	struct aa_fxaa_push push;
};

static void fxaa_destroy(struct aa_method_state *s)
{
	aa_fullscreen_pass_destroy(s->r, &s->fxaa_pass);
	aa_fullscreen_pass_destroy(s->r, &s->luma_pass);
	aa_gpu_image_destroy(s->r->gpu, &s->output);
	aa_gpu_image_destroy(s->r->gpu, &s->luma);
	aa_scene_target_destroy(s->r, &s->target);
	free(s);
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
	snprintf(info->path_taken, sizeof info->path_taken, "pixel shader, %s", desc);
	const VkImageUsageFlags pass_target = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
	if (aa_scene_target_create(r, &s->target, r->width, r->height, "scene", info, err) ||
	    aa_renderer_image_create(r, &s->luma, r->width, r->height, VK_FORMAT_R8G8B8A8_UNORM, pass_target,
				     "sRGB colour + luma", info, err) ||
	    aa_renderer_image_create(r, &s->output, r->width, r->height, AA_SCENE_COLOR_FORMAT,
				     pass_target | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, "fxaa output", info, err) ||
	    aa_fullscreen_pass_create(r, &s->luma_pass, &(struct aa_fullscreen_desc){
			.frag = "fxaa_luma.frag", .source_count = 1, .sources = {&s->target.color},
			.target = &s->luma}, err) ||
	    aa_fullscreen_pass_create(r, &s->fxaa_pass, &(struct aa_fullscreen_desc){
			.frag = "fxaa.frag", .source_count = 2, .sources = {&s->luma, &s->target.color},
			.linear = {true, false}, .target = &s->output, .push_size = sizeof s->push,
			.specialization = &s->spec.info}, err)) {
		fxaa_destroy(s);
		return -1;
	}
	*out = s;
	return 0;
}

static int fxaa_render(struct aa_method_state *s, struct aa_frame_ctx *ctx, struct aa_error *err)
{
	int span = aa_gpu_timer_begin(ctx->cmd, ctx->timer, "scene");
	aa_renderer_draw_scene(s->r, ctx->cmd, &s->target, 0.0f, 0.0f);
	aa_gpu_timer_end(ctx->cmd, ctx->timer, span);
	span = aa_gpu_timer_begin(ctx->cmd, ctx->timer, "fxaa-luma");
	aa_fullscreen_pass_record(s->r, ctx->cmd, &s->luma_pass, NULL, 0);
	aa_gpu_timer_end(ctx->cmd, ctx->timer, span);
	span = aa_gpu_timer_begin(ctx->cmd, ctx->timer, "fxaa");
	aa_fullscreen_pass_record(s->r, ctx->cmd, &s->fxaa_pass, &s->push, sizeof s->push);
	aa_gpu_timer_end(ctx->cmd, ctx->timer, span);
	ctx->output = &s->output;
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
