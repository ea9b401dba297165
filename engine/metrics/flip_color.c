/* FLIP's building blocks: colour spaces, the contrast-sensitivity and feature filters, tone mappers.
 * float32 throughout, in the reference implementation's order of operations. */
#include "metrics/flip.h"
#include "metrics/flip_internal.h"

#include <math.h>
#include <string.h>
#include <strings.h>

#define FLIP_PI 3.14159265358979f
#define FLIP_GW 0.082f /* feature filter width in degrees */

/* ------------------------------------------------------------------------------------------------ colour */

float aa_flip_srgb_to_linear(float c)
{
	if (c <= 0.04045f)
		return c / 12.92f;
	return powf((c + 0.055f) / 1.055f, 2.4f);
}

void aa_flip_linear_to_xyz(const float rgb[3], float xyz[3])
{
	flip_linear_to_xyz(rgb, xyz);
}

void aa_flip_xyz_to_linear(const float xyz[3], float rgb[3])
{
	flip_xyz_to_linear(xyz, rgb);
}

void aa_flip_xyz_to_ycxcz(const float xyz[3], float ycxcz[3])
{
	flip_xyz_to_ycxcz(xyz, ycxcz);
}

void aa_flip_ycxcz_to_xyz(const float ycxcz[3], float xyz[3])
{
	flip_ycxcz_to_xyz(ycxcz, xyz);
}

void aa_flip_xyz_to_lab(const float xyz[3], float lab[3])
{
	flip_xyz_to_lab(xyz, lab);
}

/* ------------------------------------------------------------------------------------------------ filters */

float aa_flip_ppd(float distance_m, float width_m, float resolution_x)
{
	return distance_m * (resolution_x / width_m) * (FLIP_PI / 180.0f);
}

/* The CSF Gaussian in the paper's (a, b) form, and its square-root form for the two Cz Gaussians, which
 * makes the product of a horizontal and a vertical tap the 2-D amplitude. x2 is in square degrees. */
static float csf_gaussian(float x2, float a, float b)
{
	const float pi_sq = FLIP_PI * FLIP_PI;
	return a * sqrtf(FLIP_PI / b) * expf(-pi_sq * x2 / b);
}

static float csf_gaussian_sqrt(float x2, float a, float b)
{
	const float pi_sq = FLIP_PI * FLIP_PI;
	return sqrtf(a * sqrtf(FLIP_PI / b)) * expf(-pi_sq * x2 / b);
}

/* Divides positive taps by their sum and the others by the magnitude of theirs: +1 and -1. */
static void normalise_signed(float *w, int taps)
{
	float pos = 0.0f, neg = 0.0f;
	for (int k = 0; k < taps; k++) {
		if (w[k] > 0.0f)
			pos += w[k];
		else
			neg += w[k];
	}
	neg = -neg;
	for (int k = 0; k < taps; k++)
		w[k] /= w[k] > 0.0f ? pos : neg;
}

int aa_flip_filters_init(float ppd, struct aa_flip_filters *f)
{
	memset(f, 0, sizeof *f);
	if (!(ppd > 0.0f) || ppd > AA_FLIP_MAX_PPD)
		return -1;
	f->ppd = ppd;
	/* CSF: one radius for all channels, from the widest Gaussian (b = 0.04). */
	const float pi_sq = FLIP_PI * FLIP_PI, b_max = 0.04f;
	int r = (int)ceilf(3.0f * sqrtf(b_max / (2.0f * pi_sq)) * ppd);
	f->csf_radius = r;
	const float dx = 1.0f / ppd;
	float sy = 0.0f, scx = 0.0f, s1 = 0.0f, s2 = 0.0f;
	for (int k = 0; k <= 2 * r; k++) {
		float x = (float)(k - r) * dx, x2 = x * x;
		f->csf_y[k] = csf_gaussian(x2, 1.0f, 0.0047f);
		f->csf_cx[k] = csf_gaussian(x2, 1.0f, 0.0053f);
		f->csf_cz1[k] = csf_gaussian_sqrt(x2, 34.1f, 0.04f);
		f->csf_cz2[k] = csf_gaussian_sqrt(x2, 13.5f, 0.025f);
		sy += f->csf_y[k];
		scx += f->csf_cx[k];
		s1 += f->csf_cz1[k];
		s2 += f->csf_cz2[k];
	}
	/* Cz is a sum of two rank-1 filters: normalised together so that the 2-D kernel sums to 1. */
	const float inv_y = 1.0f / sy, inv_cx = 1.0f / scx, inv_cz = 1.0f / sqrtf(s1 * s1 + s2 * s2);
	for (int k = 0; k <= 2 * r; k++) {
		f->csf_y[k] *= inv_y;
		f->csf_cx[k] *= inv_cx;
		f->csf_cz1[k] *= inv_cz;
		f->csf_cz2[k] *= inv_cz;
	}

	/* Features: Gaussian of sigma 0.5 * gw degrees and its first and second derivatives. */
	const float sigma = 0.5f * FLIP_GW * ppd;
	const int fr = (int)ceilf(3.0f * sigma);
	f->feature_sigma = sigma;
	f->feature_radius = fr;
	float sg = 0.0f;
	for (int k = 0; k <= 2 * fr; k++) {
		float x = (float)(k - fr);
		float g = expf(-(x * x) / (2.0f * sigma * sigma));
		f->g[k] = g;
		f->dg[k] = -x * g;
		f->ddg[k] = (x * x / (sigma * sigma) - 1.0f) * g;
		sg += g;
	}
	for (int k = 0; k <= 2 * fr; k++)
		f->g[k] /= sg;
	normalise_signed(f->dg, 2 * fr + 1);
	normalise_signed(f->ddg, 2 * fr + 1);
	return 0;
}

/* ------------------------------------------------------------------------------------------------ tone mapping */

/* (c0 x^2 + c1 x + c2) / (c3 x^2 + c4 x + c5) per channel; Reinhard maps on luminance instead. */
static const float tone_coefficients[3][6] = {
	[AA_FLIP_ACES] = { 0.6f * 0.6f * 2.51f, 0.6f * 0.03f, 0.0f, 0.6f * 0.6f * 2.43f, 0.6f * 0.59f, 0.14f },
	[AA_FLIP_HABLE] = { 0.231683f, 0.013791f, 0.0f, 0.18f, 0.3f, 0.018f },
	[AA_FLIP_REINHARD] = { 0.0f, 1.0f, 0.0f, 0.0f, 1.0f, 1.0f },
};

static inline float luminance(const float rgb[3])
{
	return 0.2126f * rgb[0] + 0.7152f * rgb[1] + 0.0722f * rgb[2];
}

void aa_flip_tone_map(enum aa_flip_tone_mapper tm, const float in[3], float out[3])
{
	if (tm == AA_FLIP_REINHARD) {
		float d = 1.0f + luminance(in);
		for (int i = 0; i < 3; i++)
			out[i] = in[i] / d;
		return;
	}
	const float *c = tone_coefficients[tm];
	for (int i = 0; i < 3; i++) {
		float x = in[i];
		out[i] = ((x * x) * c[0] + x * c[1] + c[2]) / (x * x * c[3] + x * c[4] + c[5]);
	}
}

float aa_flip_tone_xmax(enum aa_flip_tone_mapper tm)
{
	/* Solve (c0 - t c3) x^2 + (c1 - t c4) x + (c2 - t c5) = 0 for the exposure that maps to t = 0.85. */
	const float *tc = tone_coefficients[tm], t = 0.85f;
	float a = tc[0] - t * tc[3], b = tc[1] - t * tc[4], c = tc[2] - t * tc[5];
	if (a == 0.0f)
		return -c / b;
	float d1 = -0.5f * (b / a);
	float d2 = sqrtf((d1 * d1) - (c / a));
	return d1 + d2;
}

int aa_flip_tone_mapper_parse(const char *name)
{
	if (strcasecmp(name, "aces") == 0)
		return AA_FLIP_ACES;
	if (strcasecmp(name, "hable") == 0)
		return AA_FLIP_HABLE;
	if (strcasecmp(name, "reinhard") == 0)
		return AA_FLIP_REINHARD;
	return -1;
}

const char *aa_flip_tone_mapper_name(enum aa_flip_tone_mapper tm)
{
	return tm == AA_FLIP_HABLE ? "hable" : tm == AA_FLIP_REINHARD ? "reinhard" : "aces";
}
