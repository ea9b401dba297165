/* Sums N jittered scene renders in RGBA32F: the reference and virtual MSAA samples. The renders go into
 * up to AA_ACCUMULATE_BATCH scene targets, and one full-screen pass adds a whole batch to the running sum,
 * so the sum is read and written once per batch instead of once per render. */
#ifndef AA_SAMPLE_ACCUMULATOR_H
#define AA_SAMPLE_ACCUMULATOR_H

#include "render/renderer.h"

#define AA_ACCUMULATE_BATCH 7 /* + the previous sum: the eight sources a full-screen pass reads */

struct aa_sample_accumulator {
	struct aa_renderer *r;
	int batch;                                        /* renders per summing pass */
	struct aa_scene_target targets[AA_ACCUMULATE_BATCH];
	struct aa_gpu_image sums[2];                      /* RGBA32F running sums, written in turn */
	struct aa_fullscreen_pass add[2];                 /* add[i]: sums[1 - i] + the batch -> sums[i] */
	int current;                                      /* sums[current] holds the running sum */
	int pending;                                      /* renders in targets not yet added */
	float weight;                                     /* each render's weight in the sum */
	uint64_t memory_bytes;
};

/* Scene targets of the renderer's frame size described by desc; batch is at most AA_ACCUMULATE_BATCH
 * (fewer for fewer samples: every target is memory). Images are recorded in info when not NULL. */
int aa_sample_accumulator_create(struct aa_renderer *r, const struct aa_scene_target_desc *desc, int batch,
				 float weight, const char *name, struct aa_method_result *info,
				 struct aa_sample_accumulator *acc, struct aa_error *err);
void aa_sample_accumulator_destroy(struct aa_sample_accumulator *acc);
/* Records: the running sum set to zero. */
void aa_sample_accumulator_clear(struct aa_sample_accumulator *acc, VkCommandBuffer cmd);
/* Sets the running sum to `sum` (RGBA32F, frame-sized): a sum read back earlier, to add more renders to. */
int aa_sample_accumulator_load(struct aa_sample_accumulator *acc, const float *sum, struct aa_error *err);
/* Records one scene render jittered by (jx, jy) pixels; a full batch is added to the sum. */
void aa_sample_accumulator_render(struct aa_sample_accumulator *acc, VkCommandBuffer cmd, float jx, float jy);
/* Records the addition of any renders still pending; returns the image holding the sum of every render
 * since the clear (SHADER_READ_ONLY_OPTIMAL). */
struct aa_gpu_image *aa_sample_accumulator_sum(struct aa_sample_accumulator *acc, VkCommandBuffer cmd);

#endif
