/* What `smaa` (smaa.c) hands its passes, from its parameters: the published SMAA 2.8 preset values and the
 * rules that combine them with the `threshold` and `edge` parameters, and where each mode samples (tests
 * compare them with notes and with the standard sample positions). */
#ifndef AA_SMAA_H
#define AA_SMAA_H

#include <stdint.h>

#include "types/method.h"

enum aa_smaa_mode { AA_SMAA_1X, AA_SMAA_T2X, AA_SMAA_S2X, AA_SMAA_4X };

struct aa_smaa_settings {
	float threshold;       /* the edge pass's: the preset's or `threshold`, a tenth of it for depth edges */
	float contrast_factor; /* SMAA_LOCAL_CONTRAST_ADAPTATION_FACTOR */
	int search_steps;      /* SMAA_MAX_SEARCH_STEPS */
	int diag_steps;        /* SMAA_MAX_SEARCH_STEPS_DIAG; 0: diagonal detection off */
	float corner_keep;     /* 1 - SMAA_CORNER_ROUNDING / 100; -1: corner detection off */
	int mode;              /* enum aa_smaa_mode */
};

/* p holds smaa's parameters (preset, edge, threshold, mode), as parsed by aa_method_parse. */
void aa_smaa_settings(const struct aa_method_params *p, struct aa_smaa_settings *out);

/* One sample image of a frame: where it samples, as an offset from the pixel centre in pixels (x right,
 * y down), and the subsample indices of the blending-weight pass (area texture slots for vertical lines,
 * horizontal lines, "/" and "\" diagonals; notes/smaa.md §3.9). */
struct aa_smaa_sample {
	float offset[2];
	int32_t indices[4];
};

/* The samples of frame `frame` in `mode` (1 for 1x and t2x, 2 for s2x and 4x, in *count). */
const struct aa_smaa_sample *aa_smaa_frame_samples(int mode, int frame, int *count);

#endif
