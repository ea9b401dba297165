/* The ground truth: N renders jittered over the pixel by a low-discrepancy pattern of its own (Owen-scrambled
 * Sobol', owen_sobol.h: no method shares its positions), accumulated in float
 * (a box filter over the pixel). The N/2-sample image is kept to measure the reference's own error. */
#ifndef AA_REFERENCE_H
#define AA_REFERENCE_H

#include "image/image.h"
#include "render/renderer.h"
#include "reference/sample_accumulator.h"

struct aa_reference {
	struct aa_renderer *r;
	int samples;
	struct aa_sample_accumulator sum; /* RGBA32F sum of the renders, a batch per summing pass */
	struct aa_gpu_buffer readback, readback_half; /* the sums of N and of the first N/2 renders */
	float (*offsets)[2];           /* per sample, in pixels, within [-0.5, 0.5) */
	float lod_bias;                /* the texture LOD bias of its renders */
	uint64_t memory_bytes;
};

/* Each jittered render tests alpha at its own sample position. */
#define AA_REFERENCE_ALPHA_RULE "per-sample"

/* The reference's jitter: Owen-scrambled Sobol' points 0..n-1 mapped to [-0.5, 0.5)^2. */
#define AA_REFERENCE_PATTERN "owen-sobol"
void aa_reference_offsets(int n, float (*out)[2]);

int aa_reference_create(struct aa_renderer *r, int samples, struct aa_reference *ref, struct aa_error *err);
void aa_reference_destroy(struct aa_reference *ref);
/* Renders the current frame (aa_renderer_set_frame done) into full (N samples) and half (first N/2
 * samples), both linear float, in one submission. gpu_ms: all renders and accumulation; cpu_ms: wall
 * time. */
int aa_reference_render(struct aa_reference *ref, struct aa_gpu_timer *timer, struct aa_image_rgbaf *full,
			struct aa_image_rgbaf *half, double *gpu_ms, double *cpu_ms, struct aa_error *err);
/* The same with the first count samples (even, 2..samples): the pattern's points are nested, so the first
 * count of a longer pattern are the pattern of count. */
int aa_reference_render_count(struct aa_reference *ref, struct aa_gpu_timer *timer, int count,
			      struct aa_image_rgbaf *full, struct aa_image_rgbaf *half, double *gpu_ms, double *cpu_ms,
			      struct aa_error *err);
/* Adds samples [from, to) to the sum of the first `from` (the last render or extend of this frame) and
 * reads the average of all `to` into full. */
int aa_reference_extend(struct aa_reference *ref, struct aa_gpu_timer *timer, int from, int to,
			struct aa_image_rgbaf *full, double *gpu_ms, double *cpu_ms, struct aa_error *err);

/* out = sum / count, as every reference image is read from its running sum. */
void aa_reference_average(const float *sum, int count, struct aa_image_rgbaf *out);

/* reference.samples "auto" (engine/reference/reference_auto.c): per frame, N starts at
 * AA_REFERENCE_AUTO_START and doubles until the N/2-vs-N convergence PSNR (8-bit sRGB) reaches
 * target_psnr or N reaches ref->samples (the cap). full/half get the N and N/2 images, full8/half8 their
 * sRGB encodings, conv their comparison, *samples the N reached. */
#define AA_REFERENCE_AUTO_START 8
struct aa_metrics;
struct aa_reference_store; /* reference_store.h: levels read from and written to the store, or NULL */
int aa_reference_render_auto(struct aa_reference *ref, struct aa_gpu_timer *timer, double target_psnr,
			     struct aa_image_rgbaf *full, struct aa_image_rgbaf *half, struct aa_image_rgba8 *full8,
			     struct aa_image_rgba8 *half8, int *samples, struct aa_metrics *conv, double *gpu_ms,
			     double *cpu_ms, struct aa_reference_store *store, struct aa_error *err);

#endif
