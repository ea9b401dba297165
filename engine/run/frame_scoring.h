/* Scoring a job's frames beside its rendering: each frame's method outputs are compared with its
 * reference (PSNR, SSIM, FLIP, Fourier bands, pixels over the threshold, flicker), its difference and
 * FLIP images made, and its events emitted (whose handlers encode and write the PNGs), on a thread of
 * their own, while the next frame's reference is rendered or read from the store. The rendering thread
 * waits for that work to end before it times a method's frame, so no method's measured time runs beside
 * it (docs/architecture.md). Events keep their order: a frame's reference, then its methods. */
#ifndef AA_FRAME_SCORING_H
#define AA_FRAME_SCORING_H

#include <stdbool.h>

#include "image/image.h"
#include "types/job.h"

/* A frame handed to the scorer: filled by the rendering thread between aa_scoring_next and
 * aa_scoring_submit. */
struct aa_scoring_frame {
	int ordinal, frame;
	struct aa_image_rgbaf full;        /* the reference, linear */
	struct aa_image_rgba8 ref8;        /* the reference, 8-bit sRGB (what methods are scored against) */
	struct aa_image_rgbaf outputs[AA_MAX_METHODS]; /* each method's linear output (the scored render) */
	int order[AA_MAX_METHODS];         /* the methods in the order they rendered */
	char key_text[4096];               /* spec.explain_key: the reference key's explanation, or "" */
};

struct aa_scoring;
/* inline (or $AALAB_SCORING=inline): every frame is scored on the rendering thread when it is handed over
 * (to measure what running beside the rendering changes) */
int aa_scoring_create(const struct aa_job_spec *spec, struct aa_job_result *result, aa_event_fn on_event,
		      void *user, bool inline_scoring, struct aa_scoring **out, struct aa_error *err);
/* Waits for the scorer and frees it (frames handed over and not scored are dropped). */
void aa_scoring_destroy(struct aa_scoring *sc);
/* The frame to fill next; the scorer may still be working on the one before. */
struct aa_scoring_frame *aa_scoring_next(struct aa_scoring *sc);
/* Hands the frame over. Returns -1 with err when an earlier frame failed or a handler cancelled. */
int aa_scoring_submit(struct aa_scoring *sc, struct aa_scoring_frame *f, struct aa_error *err);
/* Waits until every frame handed over is scored and its events emitted; -1 with the first error (a metric
 * that failed, a handler that cancelled the job). */
int aa_scoring_wait(struct aa_scoring *sc, struct aa_error *err);

/* NaN/Inf values of a float image. */
long aa_count_nonfinite(const struct aa_image_rgbaf *img);

#endif
