/* `taa`: temporal AA as engines ship it (preset=production, the default: Karis 2014 / UE4, Salvi 2016,
 * Falcor, HDRP): Halton jitter, the current frame reconstructed at the pixel centre, reprojection with the
 * velocity of the closest-depth pixel in 3x3, history read with Catmull-Rom and clipped every frame toward
 * a variance box in tonemapped YCoCg, and an exponential blend whose current-frame weight settles at
 * current_weight (HDRP's default 0.125), with Karis' 1/(1+luma) weights. Two other presets: accumulate, the best case
 * an accumulating TAA reaches (a still pixel becomes the exact mean of its own jittered samples over whole
 * cycles; shaders/taa_converge.glsl), and seed001, seed 001's baseline ("Uncharted TAA", after Xu 2016 and
 * Pedersen 2016) as it was. */
#include <stdio.h>
#include <string.h>

#include "methods/taa_impl.h"

static const int taa_jitter_lengths[] = {8, 16, 0};
static const char *const taa_sharpen_kinds[] = {"off", "original", "normalized", NULL};
static const char *const taa_presets[] = {"production", "accumulate", "seed001", NULL};
static const char *const taa_history_filters[] = {"bilinear", "catmull-rom", NULL};
static const char *const taa_clips[] = {"aabb", "variance", NULL};
static const char *const taa_clip_spaces[] = {"tonemapped", "linear", NULL};

enum { P_JITTER, P_FEEDBACK_MIN, P_FEEDBACK_MAX, P_SHARPEN, P_PRESET, P_HISTORY_FILTER, P_CLIP, P_GAMMA,
       P_MAX_SAMPLES, P_CLIP_SPACE, P_TONEMAPPED_RESOLVE, P_CURRENT_WEIGHT, P_COUNT };

/* Defaults: 16 Halton points as seed 001 uses; INSIDE's feedback range (0.88-0.97), which seed 001 builds
 * on but does not state; sharpen off: against a box-filtered reference every sharpening kernel lowers PSNR
 * (thin-wires, 16 static frames: original -4 dB, normalized -2.6 dB), so it is opt-in. current_weight 0.125
 * is HDRP's default (taaBaseBlendFactor 0.875 on history), paired there as here with a variance clip,
 * Catmull-Rom history and YCoCg; UE4's r.TemporalAACurrentFrameWeight is 0.04 and Falcor's alpha 0.1. The
 * choices are measured in docs/methods.md. */
static const struct aa_param_def taa_params[] = {
	{.name = "jitter_length", .type = AA_PARAM_INT, .def = 16, .min = 8, .max = 16,
	 .allowed = taa_jitter_lengths, .help = "Halton(2,3) points per jitter cycle"},
	{.name = "feedback_min", .type = AA_PARAM_FLOAT, .def = 0.88, .min = 0.0, .max = 0.99,
	 .help = "history weight when current and history luminance differ most (accumulate: on moving pixels; "
		 "not production)"},
	{.name = "feedback_max", .type = AA_PARAM_FLOAT, .def = 0.97, .min = 0.0, .max = 0.99,
	 .help = "history weight when their luminance is equal (higher: smoother, more ghosting; accumulate: on "
		 "moving pixels; not production)"},
	{.name = "sharpen", .type = AA_PARAM_ENUM, .def = AA_TAA_SHARPEN_OFF, .min = 0, .max = 2,
	 .choices = taa_sharpen_kinds,
	 .help = "display sharpen: Xu's original [0 -1 0;-1 5 -1;0 -1 0] or seed 001's normalized kernel"},
	{.name = "preset", .type = AA_PARAM_ENUM, .def = AA_TAA_PRESET_PRODUCTION, .min = 0, .max = 2,
	 .choices = taa_presets,
	 .help = "production: a TAA as engines ship it (exponential blend, clip every frame); accumulate: the "
		 "best case an accumulating TAA reaches (still pixels become the mean of their own samples over "
		 "whole jitter cycles, unclipped); seed001: seed 001's resolve exactly"},
	{.name = "history_filter", .type = AA_PARAM_ENUM, .def = AA_TAA_HISTORY_CATMULL_ROM, .min = 0, .max = 1,
	 .choices = taa_history_filters,
	 .help = "history read under motion: bilinear, or bicubic Catmull-Rom (sharper; Falcor, HDRP)"},
	{.name = "clip", .type = AA_PARAM_ENUM, .def = AA_TAA_CLIP_VARIANCE, .min = 0, .max = 1,
	 .choices = taa_clips,
	 .help = "clip box: aabb (3x3 and cross min/max averaged, seed 001) or variance (Salvi: mean +- "
		 "gamma sigma over 3x3)"},
	{.name = "gamma", .type = AA_PARAM_FLOAT, .def = 1.0, .min = 0.0, .max = 16.0,
	 .help = "variance clip width in standard deviations (larger keeps more history, smaller rejects more)"},
	{.name = "max_samples", .type = AA_PARAM_INT, .def = 64, .min = 1, .max = 4096,
	 .help = "accumulate only: cap on the per-pixel sample count of still pixels (the new frame's weight is "
		 "at least 1/max_samples)"},
	{.name = "clip_space", .type = AA_PARAM_ENUM, .def = AA_TAA_CLIP_SPACE_TONEMAPPED, .min = 0, .max = 1,
	 .choices = taa_clip_spaces,
	 .help = "space of the clip box: YCoCg of c/(1+luma) (Karis) or of linear colour"},
	{.name = "tonemapped_resolve", .type = AA_PARAM_BOOL, .def = 1, .min = 0, .max = 1,
	 .help = "weight every colour the resolve sums or blends (the 3x3 filter, history and current, the "
		 "accumulated means) by Karis' 1/(1+luma), so one HDR sample cannot dominate; false: linear"},
	{.name = "current_weight", .type = AA_PARAM_FLOAT, .def = 0.125, .min = 0.01, .max = 1.0,
	 .help = "production only: the current frame's weight in the exponential blend once history holds "
		 "1/current_weight frames (HDRP 0.125, Falcor 0.1, UE4 0.04); it rises toward 1 with speed up to "
		 "40 px/frame"},
};
_Static_assert(sizeof taa_params / sizeof taa_params[0] == P_COUNT, "taa_params lists every parameter");
_Static_assert(P_COUNT <= AA_MAX_PARAMS, "taa's parameters fit in struct aa_method_params");

/* The presets each parameter applies to (bit 1 << preset). One set away from its default under a preset
 * that ignores it would be silently ignored: refused instead, naming it. */
#define PRODUCTION (1u << AA_TAA_PRESET_PRODUCTION)
#define ACCUMULATE (1u << AA_TAA_PRESET_ACCUMULATE)
#define SEED001 (1u << AA_TAA_PRESET_SEED001)
static const unsigned taa_param_presets[P_COUNT] = {
	[P_JITTER] = PRODUCTION | ACCUMULATE | SEED001, [P_FEEDBACK_MIN] = ACCUMULATE | SEED001,
	[P_FEEDBACK_MAX] = ACCUMULATE | SEED001, [P_SHARPEN] = PRODUCTION | ACCUMULATE | SEED001,
	[P_PRESET] = PRODUCTION | ACCUMULATE | SEED001, [P_HISTORY_FILTER] = PRODUCTION | ACCUMULATE,
	[P_CLIP] = PRODUCTION | ACCUMULATE, [P_GAMMA] = PRODUCTION | ACCUMULATE, [P_MAX_SAMPLES] = ACCUMULATE,
	[P_CLIP_SPACE] = PRODUCTION | ACCUMULATE, [P_TONEMAPPED_RESOLVE] = PRODUCTION | ACCUMULATE,
	[P_CURRENT_WEIGHT] = PRODUCTION,
};

static int refuse_ignored(const struct aa_method_params *p, enum aa_taa_preset preset, struct aa_error *err)
{
	for (int i = 0; i < P_COUNT; i++)
		if (!(taa_param_presets[i] & (1u << preset)) && p->v[i] != taa_params[i].def) {
			char path[48], list[64] = "";
			snprintf(path, sizeof path, "params.%s", taa_params[i].name);
			for (int k = 0; taa_presets[k]; k++)
				if (taa_param_presets[i] & (1u << k))
					snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", list[0] ? ", " : "",
						 taa_presets[k]);
			return aa_error_set(err, AA_ERR_INVALID, path, "%s applies to preset %s only, not %s",
					    taa_params[i].name, list, taa_presets[preset]);
		}
	return 0;
}

static int taa_config(const struct aa_method_params *p, bool master, struct aa_taa_config *c,
		      struct aa_error *err)
{
	*c = (struct aa_taa_config){
		.master = master, .jitter_length = (int)p->v[P_JITTER], .feedback_min = (float)p->v[P_FEEDBACK_MIN],
		.feedback_max = (float)p->v[P_FEEDBACK_MAX], .sharpen = (enum aa_taa_sharpen)(int)p->v[P_SHARPEN],
		.preset = (enum aa_taa_preset)(int)p->v[P_PRESET],
		.history_filter = (enum aa_taa_history_filter)(int)p->v[P_HISTORY_FILTER],
		.clip = (enum aa_taa_clip)(int)p->v[P_CLIP], .gamma = (float)p->v[P_GAMMA],
		.max_samples = (int)p->v[P_MAX_SAMPLES],
		.clip_space = (enum aa_taa_clip_space)(int)p->v[P_CLIP_SPACE],
		.tonemapped_resolve = p->v[P_TONEMAPPED_RESOLVE] != 0,
		.current_weight = (float)p->v[P_CURRENT_WEIGHT]
	};
	if (c->feedback_min > c->feedback_max)
		return aa_error_set(err, AA_ERR_INVALID, "params.feedback_min", "feedback_min (%g) must not exceed "
				    "feedback_max (%g)", p->v[P_FEEDBACK_MIN], p->v[P_FEEDBACK_MAX]);
	return refuse_ignored(p, c->preset, err);
}

static int taa_create(struct aa_renderer *r, const struct aa_method_params *p, struct aa_method_result *info,
		      struct aa_method_state **out, struct aa_error *err)
{
	struct aa_taa_config c;
	return taa_config(p, false, &c, err) || aa_taa_create(r, &c, info, out, err) ? -1 : 0;
}

const struct aa_method aa_method_taa = {
	.name = "taa",
	.summary = "temporal AA as engines ship it: jitter, reprojection, clip every frame, exponential blend "
		   "(preset=accumulate: a still pixel's exact mean; preset=seed001: seed 001's baseline)",
	.seed = "Karis 2014 (UE4), Salvi 2016, Falcor, HDRP; seed 001 (Uncharted/INSIDE TAA)",
	.params = taa_params,
	.param_count = P_COUNT,
	.needs = AA_NEED_VELOCITY | AA_NEED_HISTORY | AA_NEED_DEPTH,
	.create = taa_create,
	.render = aa_taa_render,
	.reset = aa_taa_reset,
	.destroy = aa_taa_destroy,
};

/* `taa-sobel`: seed 001's Master TAA. The same machinery and parameters; the colour box is chosen
 * between cross and 3x3 and shrunk toward the current colour per pixel by aliasedValue, from model IDs,
 * depth pseudo-variance (0.002 floor) and its temporal 4th-power term, and a temporally stabilised Sobel
 * image of unlit luma, lit luma and linear depth; the thesis's normalised sharpen is sharpen=normalized
 * (off by default, as for taa). */

static int taa_sobel_create(struct aa_renderer *r, const struct aa_method_params *p,
			    struct aa_method_result *info, struct aa_method_state **out, struct aa_error *err)
{
	struct aa_taa_config c;
	return taa_config(p, true, &c, err) || aa_taa_create(r, &c, info, out, err) ? -1 : 0;
}

const struct aa_method aa_method_taa_sobel = {
	.name = "taa-sobel",
	.summary = "seed 001's Master TAA: clip box from Sobel edges, model IDs and depth variance, on taa's "
		   "production resolve (preset=accumulate, preset=seed001 as taa's)",
	.seed = "seed 001 (Master TAA, chapter 4)",
	.params = taa_params,
	.param_count = P_COUNT,
	.needs = AA_NEED_VELOCITY | AA_NEED_HISTORY | AA_NEED_DEPTH | AA_NEED_IDS,
	.create = taa_sobel_create,
	.render = aa_taa_render,
	.reset = aa_taa_reset,
	.destroy = aa_taa_destroy,
};
