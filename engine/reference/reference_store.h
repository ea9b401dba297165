/* A job's references through the store (reference_cache.h): before a frame's reference is rendered its
 * key is looked up, and a rendered one is stored after. The entry holds the running sums of the renders
 * (not their averages), so that a frame read from the store gives the same bits as one rendered, and an
 * auto reference can go on from a stored sum. */
#ifndef AA_REFERENCE_STORE_H
#define AA_REFERENCE_STORE_H

#include "reference/reference.h"
#include "reference/reference_cache.h"
#include "reference/reference_key.h"

struct aa_reference_store {
	struct aa_reference_cache *cache;  /* NULL: no store (every call below does nothing) */
	bool verify;                       /* render every reference and compare it with its entry */
	bool explain;                      /* keep the text of each frame's key (explanation) */
	struct aa_reference_cache_result *result; /* the job's counts (its result's reference.cache) */
	const char *pattern;               /* the results' pattern name */
	char recipe_head[1400];            /* the frame's job as JSON, without the frame (aa_reference_store_job) */
	/* the current frame */
	bool keyed;
	struct aa_reference_key_inputs in;
	int frame;
	int loaded, rendered;              /* levels of this frame from the store / rendered */
	char explanation[4096];
};

/* Once per job: the store (NULL: none), and what its entries record to be rendered again: the scene file
 * ("" when the scene is not a file), the camera path, size, samples (the cap when auto_samples). */
void aa_reference_store_job(struct aa_reference_store *s, struct aa_reference_cache *cache, bool verify, bool explain,
			    struct aa_reference_cache_result *result, const char *pattern, const char *scene_file,
			    const char *path, int width, int height, int samples, bool auto_samples);
/* Before each frame's reference: its key inputs (the frame's camera and time from ctx). */
struct aa_frame_ctx;
void aa_reference_store_frame(struct aa_reference_store *s, const struct aa_reference *ref,
			      const struct aa_frame_ctx *ctx);

/* A fixed reference: 1 when the store holds the frame (full and half filled, *gpu_ms and *cpu_ms what
 * rendering it cost), 0 when it must be rendered. */
int aa_reference_store_load(struct aa_reference_store *s, const struct aa_reference *ref, struct aa_image_rgbaf *full,
			    struct aa_image_rgbaf *half, double *gpu_ms, double *cpu_ms);
/* After aa_reference_render: stores the sums it read back (verify: compares them with the entry). */
void aa_reference_store_save(struct aa_reference_store *s, const struct aa_reference *ref, double gpu_ms, double cpu_ms);

/* An auto reference's level (levels[0..count) the sample counts from the first level to this one):
 * 1 when stored: *sum (malloc'ed) the running sum of its last level, *half_sum that of the first level's
 * N/2 (first level only, else NULL); 0 otherwise. */
int aa_reference_store_load_level(struct aa_reference_store *s, const struct aa_reference *ref, int n, float **sum,
				  float **half_sum, double *gpu_ms, double *cpu_ms);
/* Stores a rendered level (its sums read back in ref->readback and, first level, ref->readback_half). */
void aa_reference_store_save_level(struct aa_reference_store *s, const struct aa_reference *ref, int n, double gpu_ms,
				   double cpu_ms);
/* Puts a stored running sum of n renders back on the GPU (and this frame's shadow map), so that
 * aa_reference_extend(ref, ..., n, ...) goes on from it as if the n renders had just been made. */
int aa_reference_resume(struct aa_reference *ref, const float *sum, int n, struct aa_error *err);

/* The frame's outcome into rf->cache and the job's counts (after the frame's reference is whole). */
void aa_reference_store_frame_done(struct aa_reference_store *s, char *outcome, size_t size);

#endif
