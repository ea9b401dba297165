/* The machinery shared by `taa` (seed 001's baseline) and `taa-sobel` (its "Master TAA"): a G-buffer
 * scene pass with Halton jitter, the resolve into float history, and the display sharpen. */
#ifndef AA_TAA_IMPL_H
#define AA_TAA_IMPL_H

#include "../renderer.h"
#include "method.h"

enum aa_taa_sharpen { AA_TAA_SHARPEN_OFF, AA_TAA_SHARPEN_ORIGINAL, AA_TAA_SHARPEN_NORMALIZED };

struct aa_taa_config {
	bool master;           /* Sobel/ID/depth clip box (taa-sobel) */
	int jitter_length;     /* Halton(2,3) points per cycle */
	float feedback_min, feedback_max;
	enum aa_taa_sharpen sharpen;
};

int aa_taa_create(struct aa_renderer *r, const struct aa_taa_config *config, struct aa_method_result *info,
		  struct aa_method_state **out, struct aa_error *err);
int aa_taa_render(struct aa_method_state *s, struct aa_frame_ctx *ctx, struct aa_error *err);
void aa_taa_reset(struct aa_method_state *s);
void aa_taa_destroy(struct aa_method_state *s);

#endif
