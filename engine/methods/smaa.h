/* What `smaa` (smaa.c) hands its passes, from its parameters: the published SMAA 2.8 preset values and the
 * rules that combine them with the `threshold` and `edge` parameters (tests compare them with notes). */
#ifndef AA_SMAA_H
#define AA_SMAA_H

#include "types/method.h"

struct aa_smaa_settings {
	float threshold;       /* the edge pass's: the preset's or `threshold`, a tenth of it for depth edges */
	float contrast_factor; /* SMAA_LOCAL_CONTRAST_ADAPTATION_FACTOR */
	int search_steps;      /* SMAA_MAX_SEARCH_STEPS */
	int diag_steps;        /* SMAA_MAX_SEARCH_STEPS_DIAG; 0: diagonal detection off */
	float corner_keep;     /* 1 - SMAA_CORNER_ROUNDING / 100; -1: corner detection off */
};

/* p holds smaa's parameters (preset, edge, threshold), as parsed by aa_method_parse. */
void aa_smaa_settings(const struct aa_method_params *p, struct aa_smaa_settings *out);

#endif
