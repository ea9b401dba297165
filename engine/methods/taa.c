/* `taa`: seed 001's baseline temporal AA ("Uncharted TAA", after Xu 2016 and Pedersen 2016): Halton
 * jitter, reprojection with the velocity of the closest-depth pixel in 3x3, history clipped toward the
 * current colour at the averaged 3x3/cross colour box in YCoCg, luminance-difference feedback, and
 * Xu's sharpen for display. */
#include "taa_impl.h"

static const int taa_jitter_lengths[] = {8, 16, 0};
static const char *const taa_sharpen_kinds[] = {"off", "original", "normalized", NULL};

/* Defaults: INSIDE's feedback range (0.88-0.97), which seed 001 builds on but does not state; 16 Halton
 * points as seed 001 uses; sharpen off: against a box-filtered reference every sharpening kernel lowers
 * PSNR (thin-wires, 16 static frames: original -4 dB, normalized -2.6 dB), so it is opt-in. */
#define TAA_PARAMS(sharpen_default)                                                                         \
	{.name = "jitter_length", .type = AA_PARAM_INT, .def = 16, .min = 8, .max = 16,                      \
	 .allowed = taa_jitter_lengths, .help = "Halton(2,3) points per jitter cycle"},                      \
	{.name = "feedback_min", .type = AA_PARAM_FLOAT, .def = 0.88, .min = 0.0, .max = 0.99,              \
	 .help = "history weight when current and history luminance differ most"},                          \
	{.name = "feedback_max", .type = AA_PARAM_FLOAT, .def = 0.97, .min = 0.0, .max = 0.99,              \
	 .help = "history weight when their luminance is equal (higher: smoother, more ghosting)"},         \
	{.name = "sharpen", .type = AA_PARAM_ENUM, .def = sharpen_default, .min = 0, .max = 2,              \
	 .choices = taa_sharpen_kinds,                                                                       \
	 .help = "display sharpen: Xu's original [0 -1 0;-1 5 -1;0 -1 0] or seed 001's normalized kernel"}

static const struct aa_param_def taa_params[] = {TAA_PARAMS(AA_TAA_SHARPEN_OFF)};

static int taa_config(const struct aa_method_params *p, bool master, struct aa_taa_config *c,
		      struct aa_error *err)
{
	*c = (struct aa_taa_config){
		.master = master, .jitter_length = (int)p->v[0], .feedback_min = (float)p->v[1],
		.feedback_max = (float)p->v[2], .sharpen = (enum aa_taa_sharpen)(int)p->v[3],
	};
	if (c->feedback_min > c->feedback_max)
		return aa_error_set(err, AA_ERR_INVALID, "params.feedback_min", "feedback_min (%g) must not exceed "
				    "feedback_max (%g)", p->v[1], p->v[2]);
	return 0;
}

static int taa_create(struct aa_renderer *r, const struct aa_method_params *p, struct aa_method_result *info,
		      struct aa_method_state **out, struct aa_error *err)
{
	struct aa_taa_config c;
	return taa_config(p, false, &c, err) || aa_taa_create(r, &c, info, out, err) ? -1 : 0;
}

const struct aa_method aa_method_taa = {
	.name = "taa",
	.summary = "temporal AA, seed 001's baseline: jitter, reprojection, colour-box clipping, feedback",
	.seed = "seed 001 (Uncharted/INSIDE TAA)",
	.params = taa_params,
	.param_count = 4,
	.needs = AA_NEED_VELOCITY | AA_NEED_HISTORY | AA_NEED_DEPTH,
	.create = taa_create,
	.render = aa_taa_render,
	.reset = aa_taa_reset,
	.destroy = aa_taa_destroy,
};

/* `taa-sobel`: seed 001's Master TAA. The same machinery; the colour box is chosen between cross and
 * 3x3 and shrunk toward the current colour per pixel by aliasedValue, from model IDs, depth
 * pseudo-variance (0.002 floor) and its temporal 4th-power term, and a temporally stabilised Sobel
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
	.summary = "seed 001's Master TAA: clip box from Sobel edges, model IDs and depth variance",
	.seed = "seed 001 (Master TAA, chapter 4)",
	.params = taa_params,
	.param_count = 4,
	.needs = AA_NEED_VELOCITY | AA_NEED_HISTORY | AA_NEED_DEPTH | AA_NEED_IDS,
	.create = taa_sobel_create,
	.render = aa_taa_render,
	.reset = aa_taa_reset,
	.destroy = aa_taa_destroy,
};
