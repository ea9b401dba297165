/* The machinery shared by `taa` and `taa-sobel`: a G-buffer scene pass with Halton jitter, the resolve
 * into float history, and the display sharpen. Resolves: production (the default) and accumulate, one
 * compute shader (shaders/taa_converge.glsl), and seed 001's (preset=seed001). */
#ifndef AA_TAA_IMPL_H
#define AA_TAA_IMPL_H

#include "render/renderer.h"
#include "types/method.h"

enum aa_taa_sharpen { AA_TAA_SHARPEN_OFF, AA_TAA_SHARPEN_ORIGINAL, AA_TAA_SHARPEN_NORMALIZED };
enum aa_taa_preset { AA_TAA_PRESET_PRODUCTION, AA_TAA_PRESET_ACCUMULATE, AA_TAA_PRESET_SEED001 };
enum aa_taa_history_filter { AA_TAA_HISTORY_BILINEAR, AA_TAA_HISTORY_CATMULL_ROM };
enum aa_taa_clip { AA_TAA_CLIP_AABB, AA_TAA_CLIP_VARIANCE };
enum aa_taa_clip_space { AA_TAA_CLIP_SPACE_TONEMAPPED, AA_TAA_CLIP_SPACE_LINEAR };

struct aa_taa_config {
	bool master;           /* Sobel/ID/depth clip box (taa-sobel) */
	enum aa_taa_preset preset;
	int jitter_length;     /* Halton(2,3) points per cycle */
	float feedback_min, feedback_max;
	enum aa_taa_sharpen sharpen;
	/* preset=production and accumulate */
	enum aa_taa_history_filter history_filter;
	enum aa_taa_clip clip;
	float gamma;           /* variance clip: mean +- gamma * sigma */
	int max_samples;       /* accumulate: cap on the per-pixel sample count of still pixels */
	enum aa_taa_clip_space clip_space;
	bool tonemapped_resolve; /* Karis-weighted sums and blends */
	float current_weight;  /* production: the current frame's weight once history is full */
};

int aa_taa_create(struct aa_renderer *r, const struct aa_taa_config *config, struct aa_method_result *info,
		  struct aa_method_state **out, struct aa_error *err);
int aa_taa_render(struct aa_method_state *s, struct aa_frame_ctx *ctx, struct aa_error *err);
void aa_taa_reset(struct aa_method_state *s);
void aa_taa_destroy(struct aa_method_state *s);

#endif
