/* RSAA's resampling-offset table (Reshetov, HPG 2012, section 2.3): for every mask of "subsample similar
 * to the pixel centre" bits, the (x, y) offset in pixels (y down) of the one bilinear fetch that best
 * reproduces the exact covered area over random one- and two-line cases. Trained here, not copied. */
#ifndef AA_RSAA_TABLE_H
#define AA_RSAA_TABLE_H

#include <stdint.h>

#define RSAA_MAX_SAMPLES 8
#define RSAA_MAX_MASKS (1 << RSAA_MAX_SAMPLES)
#define RSAA_TRAINING_CASES 1000000L /* the paper's 10^6 */
#define RSAA_TRAINING_SEED UINT64_C(0x525341412012)

/* How a mask's offset was found. The full mask (every subsample similar) is always (0, 0). */
enum rsaa_mask_class {
	RSAA_CLASS_FULL,      /* all bits set: nothing to resample */
	RSAA_CLASS_ONE_LINE,  /* seen in one-line cases: trained on those only (Ockham's razor) */
	RSAA_CLASS_TWO_LINE,  /* seen only in two-line cases: trained on those */
	RSAA_CLASS_FALLBACK,  /* never seen, and mask 0: toward the most distant dissimilar subsample */
};

struct rsaa_table {
	int samples;                          /* n: 4 or 8 (any 1..8 trains) */
	int masks;                            /* 1 << n */
	float offset[RSAA_MAX_MASKS][2];      /* pixels, y down, within [-1, 1]^2 */
	unsigned char mask_class[RSAA_MAX_MASKS];
	int class_count[4];                   /* masks per enum rsaa_mask_class */
	uint32_t cases[RSAA_MAX_MASKS];       /* training cases behind each trained mask */
	double mean_abs_error[RSAA_MAX_MASKS]; /* mean |fetched - exact coverage| at the chosen offset */
	long training_cases;
	uint64_t seed;
	double train_ms;                      /* wall time of the training */
};

/* Trains a table for n sample positions pos[i] in [0,1)^2 of the pixel (y down), from `cases` random
 * cases (half with one line, half with two, each line through a uniform point of the pixel in a uniform
 * direction) drawn from a generator seeded with `seed`. Each trained mask gets the offset in [-1, 1]^2
 * minimising the mean absolute difference between one bilinear fetch of the case's 1-spp image (white
 * where a pixel centre shares the centre's region) and the exact covered area. Deterministic: the same
 * inputs give bit-identical tables (only +, -, *, / and sqrt; no libm transcendental). Returns 0, or -1
 * for bad arguments (cases 2..10^8) or no memory. */
int rsaa_table_train(const float (*pos)[2], int n, long cases, uint64_t seed, struct rsaa_table *out);

/* The table for the Vulkan standard positions of n (4 or 8) samples with the full training set, trained
 * on first use (about a second) and kept for the life of the process; thread-safe. NULL for other n. */
const struct rsaa_table *rsaa_table_get(int n);

/* The fallback rule for masks no training case explains: toward the most distant dissimilar subsample
 * (ties: the higher index), scaled to reach the next pixel centre, times (dissimilar count) / (n + 1). */
void rsaa_fallback_offset(const float (*pos)[2], int n, unsigned mask, float out[2]);

/* SADP, the sum of absolute dot products: (|n1.r| + |n2.r|) / |r| with r = p2 - p1 (unit normals). 0 when
 * the positions coincide to float precision (|r| <= 1e-6 max(|p1|_inf, 1)): no direction to measure along.
 * Symmetric, 0 on one plane, camera-independent. shaders/rsaa_common.glsl has the same formula. */
double rsaa_sadp(const double p1[3], const double n1[3], const double p2[3], const double n2[3]);

#endif
