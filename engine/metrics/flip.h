/* FLIP (NVIDIA, HPG 2020; HDR-FLIP, EGSR 2021): the perceived difference between a reference and a test
 * image shown alternately, per pixel in [0,1]. LDR-FLIP compares two displayed (sRGB or linear, [0,1])
 * images; HDR-FLIP tone maps linear HDR images at a range of exposures and keeps the largest LDR error.
 * The arithmetic follows the reference implementation (NVlabs/flip v1.6, CPU path) in float32 and in its
 * order of operations; tests/unit/test_flip.c checks its filter taps, colour transforms and constants. */
#ifndef AA_FLIP_H
#define AA_FLIP_H

#include <stdbool.h>
#include <stddef.h>

#include "util/error.h"
#include "image/image.h"

/* Pixels per degree of the default viewing conditions: a 0.7 m wide 3840-pixel monitor seen from 0.7 m
 * (67.0206451 in float32, 3840 pi / 180 exactly). */
#define AA_FLIP_DEFAULT_PPD 67.0206451f
/* Largest pixels per degree accepted: filters then have 137 taps on each side. */
#define AA_FLIP_MAX_PPD 1000.0f
#define AA_FLIP_MAX_RADIUS 140
#define AA_FLIP_MAX_TAPS (2 * AA_FLIP_MAX_RADIUS + 1)

enum aa_flip_tone_mapper { AA_FLIP_ACES, AA_FLIP_HABLE, AA_FLIP_REINHARD };

struct aa_flip_options {
	float ppd;                            /* pixels per degree; 0 means AA_FLIP_DEFAULT_PPD */
	int threads;                          /* 0: one per online core (at most 8) */
	/* HDR-FLIP only */
	enum aa_flip_tone_mapper tone_mapper; /* default ACES */
	bool have_start, have_stop;           /* exposures given by the user, else computed from the reference */
	float start_exposure, stop_exposure;  /* log2 of the exposure scale */
	int exposures;                        /* number of exposures; 0: max(2, ceil(stop - start)) */
};

/* The range HDR-FLIP evaluated. */
struct aa_flip_hdr_info {
	float start_exposure, stop_exposure;
	int exposures;
};

/* Pooled statistics of an error map, computed as the reference tool prints them: float32 running sums in
 * row-major order; the weighted percentiles weight each pixel by its own error (the first value, in
 * ascending order, whose running sum exceeds p times the total). */
struct aa_flip_stats {
	double mean;
	double weighted_median;
	double weighted_q1, weighted_q3;
	double min, max;
};

/* Pixels per degree for a monitor width_m metres wide with resolution_x pixels, seen from distance_m metres. */
float aa_flip_ppd(float distance_m, float width_m, float resolution_x);

/* LDR-FLIP of two 8-bit sRGB images of equal size (alpha ignored). map receives width*height errors, row-major.
 * Returns -1 with err on a size mismatch, a bad ppd or when memory runs out. */
int aa_flip_ldr_rgba8(const struct aa_image_rgba8 *ref, const struct aa_image_rgba8 *test,
		      const struct aa_flip_options *opt, float *map, struct aa_error *err);
/* LDR-FLIP of two linear-RGB float images (alpha ignored); values are clamped to [0,1] first. */
int aa_flip_ldr_linear(const struct aa_image_rgbaf *ref, const struct aa_image_rgbaf *test,
		       const struct aa_flip_options *opt, float *map, struct aa_error *err);

/* The reference side of LDR-FLIP (its colour transform, filtering and feature detection), computed once
 * and shared by every image compared against it, read-only (several threads may use one at once). */
struct aa_flip_reference;
/* From an 8-bit sRGB or a linear float image (alpha ignored) at opt's ppd (opt->threads is used to make it).
 * *out is NULL or a reference made before, which is remade in its own memory when the size is the same
 * (a scorer keeps one for all its frames). On failure *out is NULL and the old one freed. */
int aa_flip_reference_rgba8(const struct aa_image_rgba8 *ref, const struct aa_flip_options *opt,
			    struct aa_flip_reference **out, struct aa_error *err);
int aa_flip_reference_linear(const struct aa_image_rgbaf *ref, const struct aa_flip_options *opt,
			     struct aa_flip_reference **out, struct aa_error *err);
void aa_flip_reference_free(struct aa_flip_reference *ref);
/* The map of aa_flip_ldr_rgba8 (resp. _linear) of ref's image and test, the same to the bit. opt may be NULL;
 * a non-zero opt->ppd must be the reference's. */
int aa_flip_ldr_rgba8_against(const struct aa_flip_reference *ref, const struct aa_image_rgba8 *test,
			      const struct aa_flip_options *opt, float *map, struct aa_error *err);
int aa_flip_ldr_linear_against(const struct aa_flip_reference *ref, const struct aa_image_rgbaf *test,
			       const struct aa_flip_options *opt, float *map, struct aa_error *err);
/* HDR-FLIP of two linear-RGB float images (alpha ignored). Values must be finite. info may be NULL. */
int aa_flip_hdr(const struct aa_image_rgbaf *ref, const struct aa_image_rgbaf *test,
		const struct aa_flip_options *opt, float *map, struct aa_flip_hdr_info *info, struct aa_error *err);

/* Pooled statistics of n error values. Returns -1 when memory for sorting runs out (n > 0). */
int aa_flip_pool(const float *map, size_t n, struct aa_flip_stats *out);
/* The mean alone, summed as aa_flip_pool sums it (the same value), without the sort its weighted
 * quartiles need. 0 when n is 0. */
double aa_flip_mean(const float *map, size_t n);
/* Sorts n floats ascending into out (NaN after +Inf). Returns -1 when memory runs out. */
int aa_flip_sort_floats(const float *in, size_t n, float *out);

/* The error map as an image: the magma colour map (index int(v*255 + 0.5) % 256, as the reference tool
 * writes it) or, with magma false, grey levels. out must be allocated width x height. */
void aa_flip_colorize(const float *map, bool magma, struct aa_image_rgba8 *out);

/* Parsed tone mapper name ("aces", "hable", "reinhard", any case); -1 when unknown. */
int aa_flip_tone_mapper_parse(const char *name);
const char *aa_flip_tone_mapper_name(enum aa_flip_tone_mapper tm);

/* ---- building blocks, exposed for the unit tests (tests/unit/test_flip.c) ---- */

/* The 1-D filters at a given ppd: the contrast-sensitivity (CSF) filters of the colour pipeline and the
 * Gaussian, first and second derivative filters of the feature pipeline. Index k is offset k - radius. */
struct aa_flip_filters {
	float ppd;
	int csf_radius;
	float csf_y[AA_FLIP_MAX_TAPS], csf_cx[AA_FLIP_MAX_TAPS];
	float csf_cz1[AA_FLIP_MAX_TAPS], csf_cz2[AA_FLIP_MAX_TAPS];
	int feature_radius;
	float feature_sigma;
	float g[AA_FLIP_MAX_TAPS], dg[AA_FLIP_MAX_TAPS], ddg[AA_FLIP_MAX_TAPS];
};
/* Returns -1 unless 0 < ppd <= AA_FLIP_MAX_PPD. */
int aa_flip_filters_init(float ppd, struct aa_flip_filters *f);

/* Colour transforms of the pipeline, each on three floats. */
void aa_flip_linear_to_xyz(const float rgb[3], float xyz[3]);
void aa_flip_xyz_to_linear(const float xyz[3], float rgb[3]);
void aa_flip_xyz_to_ycxcz(const float xyz[3], float ycxcz[3]);
void aa_flip_ycxcz_to_xyz(const float ycxcz[3], float xyz[3]);
void aa_flip_xyz_to_lab(const float xyz[3], float lab[3]);
float aa_flip_srgb_to_linear(float c);
/* Largest colour distance (HyAB of Hunt-adjusted green and blue, raised to 0.7): 41.2760963. */
float aa_flip_max_color_distance(void);
/* FLIP colour error of two filtered YCxCz pixels, and the final error from colour and feature errors. */
float aa_flip_color_error(const float ref_ycxcz[3], const float test_ycxcz[3]);
float aa_flip_feature_error(float edge_ref, float edge_test, float point_ref, float point_test);
/* Per-channel tone mapping and the exposure range HDR-FLIP uses. */
void aa_flip_tone_map(enum aa_flip_tone_mapper tm, const float in[3], float out[3]);
/* The larger root x of tone_map(x) = 0.85: ACES 2.11887312, Hable 3.12774992, Reinhard 5.66666794. */
float aa_flip_tone_xmax(enum aa_flip_tone_mapper tm);
/* start = log2(xmax / max luminance), stop = log2(xmax / median luminance) of the reference. */
int aa_flip_exposure_range(const struct aa_image_rgbaf *ref, enum aa_flip_tone_mapper tm, float *start,
			   float *stop, struct aa_error *err);

#endif
