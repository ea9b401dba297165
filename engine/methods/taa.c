/* `taa`: temporal AA on seed 001's baseline ("Uncharted TAA", after Xu 2016 and Pedersen 2016): Halton
 * jitter, reprojection with the velocity of the closest-depth pixel in 3x3, history clipped toward the
 * centre of a colour box in YCoCg, luminance-difference feedback, Xu's sharpen for display. The default
 * preset, converge, adds what the production TAAs it descends from do so that a still image converges
 * (shaders/taa_converge.glsl); preset=seed001 runs the seed's algorithm as it was. */
#include <stdio.h>

#include "methods/taa_impl.h"

static const int taa_jitter_lengths[] = {8, 16, 0};
static const char *const taa_sharpen_kinds[] = {"off", "original", "normalized", NULL};
static const char *const taa_presets[] = {"converge", "seed001", NULL};
static const char *const taa_history_filters[] = {"bilinear", "catmull-rom", NULL};
static const char *const taa_clips[] = {"aabb", "variance", NULL};
static const char *const taa_clip_spaces[] = {"tonemapped", "linear", NULL};

enum { P_JITTER, P_FEEDBACK_MIN, P_FEEDBACK_MAX, P_SHARPEN, P_PRESET, P_HISTORY_FILTER, P_CLIP, P_GAMMA,
       P_MAX_SAMPLES, P_CLIP_SPACE, P_TONEMAPPED_RESOLVE, P_COUNT };

/* Defaults: INSIDE's feedback range (0.88-0.97), which seed 001 builds on but does not state; 16 Halton
 * points as seed 001 uses; sharpen off: against a box-filtered reference every sharpening kernel lowers
 * PSNR (thin-wires, 16 static frames: original -4 dB, normalized -2.6 dB), so it is opt-in. The converge
 * preset's choices are measured in docs/methods.md. */
static const struct aa_param_def taa_params[] = {
	{.name = "jitter_length", .type = AA_PARAM_INT, .def = 16, .min = 8, .max = 16,
	 .allowed = taa_jitter_lengths, .help = "Halton(2,3) points per jitter cycle"},
	{.name = "feedback_min", .type = AA_PARAM_FLOAT, .def = 0.88, .min = 0.0, .max = 0.99,
	 .help = "history weight when current and history luminance differ most (converge: on moving pixels)"},
	{.name = "feedback_max", .type = AA_PARAM_FLOAT, .def = 0.97, .min = 0.0, .max = 0.99,
	 .help = "history weight when their luminance is equal (higher: smoother, more ghosting; converge: on "
		 "moving pixels)"},
	{.name = "sharpen", .type = AA_PARAM_ENUM, .def = AA_TAA_SHARPEN_OFF, .min = 0, .max = 2,
	 .choices = taa_sharpen_kinds,
	 .help = "display sharpen: Xu's original [0 -1 0;-1 5 -1;0 -1 0] or seed 001's normalized kernel"},
	{.name = "preset", .type = AA_PARAM_ENUM, .def = AA_TAA_PRESET_CONVERGE, .min = 0, .max = 1,
	 .choices = taa_presets,
	 .help = "converge: current frame filtered at the pixel centre, clip in tonemapped YCoCg, still pixels "
		 "averaged over whole jitter cycles; seed001: seed 001's resolve exactly (the parameters below apply "
		 "to converge only)"},
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
	 .help = "cap on the per-pixel sample count of still pixels (the new frame's weight is at least "
		 "1/max_samples)"},
	{.name = "clip_space", .type = AA_PARAM_ENUM, .def = AA_TAA_CLIP_SPACE_TONEMAPPED, .min = 0, .max = 1,
	 .choices = taa_clip_spaces,
	 .help = "space of the clip box: YCoCg of c/(1+luma) (Karis) or of linear colour"},
	{.name = "tonemapped_resolve", .type = AA_PARAM_BOOL, .def = 0, .min = 0, .max = 1,
	 .help = "weight every colour the resolve sums or blends (the 3x3 filter, history and current, the "
		 "still pixels' means) by Karis' 1/(1+luma), so one HDR sample cannot dominate"},
};
_Static_assert(sizeof taa_params / sizeof taa_params[0] == P_COUNT, "taa_params lists every parameter");
_Static_assert(P_COUNT <= AA_MAX_PARAMS, "taa's parameters fit in struct aa_method_params");

/* A converge-only parameter set away from its default under preset=seed001 would be silently ignored:
 * refused instead, naming it. */
static int refuse_with_seed001(const struct aa_method_params *p, struct aa_error *err)
{
	for (int i = P_HISTORY_FILTER; i < P_COUNT; i++)
		if (p->v[i] != taa_params[i].def) {
			char path[48];
			snprintf(path, sizeof path, "params.%s", taa_params[i].name);
			return aa_error_set(err, AA_ERR_INVALID, path, "%s applies to preset=converge only "
					    "(preset=seed001 runs seed 001's resolve as it was)", taa_params[i].name);
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
	};
	if (c->feedback_min > c->feedback_max)
		return aa_error_set(err, AA_ERR_INVALID, "params.feedback_min", "feedback_min (%g) must not exceed "
				    "feedback_max (%g)", p->v[P_FEEDBACK_MIN], p->v[P_FEEDBACK_MAX]);
	return c->preset == AA_TAA_PRESET_SEED001 ? refuse_with_seed001(p, err) : 0;
}

static int taa_create(struct aa_renderer *r, const struct aa_method_params *p, struct aa_method_result *info,
		      struct aa_method_state **out, struct aa_error *err)
{
	struct aa_taa_config c;
	return taa_config(p, false, &c, err) || aa_taa_create(r, &c, info, out, err) ? -1 : 0;
}

const struct aa_method aa_method_taa = {
	.name = "taa",
	.summary = "temporal AA: jitter, reprojection, colour-box clipping; converges on still pixels "
		   "(preset=seed001: seed 001's baseline)",
	.seed = "seed 001 (Uncharted/INSIDE TAA); Karis 2014, Salvi 2016, Falcor, HDRP",
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
	.summary = "seed 001's Master TAA: clip box from Sobel edges, model IDs and depth variance; converges "
		   "on still pixels (preset=seed001: as the seed)",
	.seed = "seed 001 (Master TAA, chapter 4)",
	.params = taa_params,
	.param_count = P_COUNT,
	.needs = AA_NEED_VELOCITY | AA_NEED_HISTORY | AA_NEED_DEPTH | AA_NEED_IDS,
	.create = taa_sobel_create,
	.render = aa_taa_render,
	.reset = aa_taa_reset,
	.destroy = aa_taa_destroy,
};
