/* Stored results of a job: results.json (docs/results-format.md), per-frame PNGs and report.html. */
#ifndef AA_RESULTS_H
#define AA_RESULTS_H

#include <stdio.h>

#include <jansson.h>

#include "run/farm.h"
#include "types/job.h"
#include "util/file_name.h"


/* Image files of a job directory, relative to it:
 *   frames/<dirname>/<NNNN>.png   method output (and frames/reference/<NNNN>.png)
 *   diff/<dirname>/<NNNN>.png     |method - reference| x 4
 *   flip/<dirname>/<NNNN>.png     the FLIP error map (magma colour map)
 * NNNN is the frame ordinal (0-based) with 4 digits. */
void aa_results_frame_relpath(const char *kind, const char *label, int ordinal, char *out, size_t size);
/* linear/<dirname>/<NNNN>.rgba16f: the frame's linear colour as raw RGBA16F (jobs with linear_frames). */
void aa_results_linear_relpath(const char *label, int ordinal, char *out, size_t size);
/* Writes an image under dir at the relative path, creating directories. */
int aa_results_write_image(const char *dir, const char *relpath, const struct aa_image_rgba8 *img,
			   struct aa_error *err);

/* Writes the images an event carries into dir: the reference frame (frames/reference/NNNN.png) or a
 * method's frame, its diff image and its FLIP error map. Other events write nothing. Shared by
 * `aalab run` and aalabd. */
int aa_results_write_event_images(const char *dir, const struct aa_event *ev, struct aa_error *err);

json_t *aa_results_to_json(const struct aa_job_result *r);
/* A results.json document of a job that is not a suite (or one case of a suite's), read back into a
 * result: what its writer (results_json.c) stores per frame and per timed render. results.json keeps the
 * error-threshold curve as a mean only: each frame gets its curve from curves_per_method ([method][frame],
 * a shard's), or the mean when it is NULL. The error names the key at fault. */
int aa_results_from_json(const json_t *doc, const json_t *curves_per_method, struct aa_job_result *out,
			 struct aa_error *err);
/* Writes dir/results.json atomically (temp file, fsync, rename). */
int aa_results_write_json(const struct aa_job_result *r, const char *dir, struct aa_error *err);
/* Writes a JSON document (results.json of a job or a suite) atomically into dir, as results.json is written. */
int aa_results_write_json_doc(const json_t *root, const char *dir, const char *name, struct aa_error *err);
/* Writes dir/name atomically: a temp file in dir, fsync, rename over name, fsync dir. */
int aa_results_write_file_atomic(const char *dir, const char *name, const char *data, size_t size,
				 struct aa_error *err);
/* exr/<dirname>/<NNNN>.exr: the frame's linear colour as float EXR (aalab run --exr; exr_frames.c). */
void aa_results_exr_relpath(const char *label, int ordinal, char *out, size_t size);
/* mkdir -p of every directory of path up to its last '/' (path is restored); -1 with err naming it. */
int aa_results_make_parents(char *path, struct aa_error *err);
/* Writes the EXR of a reference or method frame event (its linear image); other events write nothing. */
int aa_results_write_event_exr(const char *dir, const struct aa_event *ev, struct aa_error *err);

/* ---- results of a suite (suite_results.c) ---- */

/* results.json of the job: for a suite {"cases": [...]} around one results document per case, for a job
 * that is not a suite the document of its one case; both with labels, suite and job_hash. */
json_t *aa_suite_results_to_json(const struct aa_suite_result *r);
/* Writes the images an event carries, into the directory of the event's case. */
int aa_suite_write_event_images(const char *dir, const struct aa_job_spec *spec, const struct aa_event *ev,
				struct aa_error *err);

/* ---- summaries (summary.c) ---- */

/* A distribution of times: median, 10th and 90th percentile, minimum, mean and the count of values. */
struct aa_timing_stats {
	double median, p10, p90, min, mean;
	int n;
};
/* Over n values (non-finite ones skipped); every field NAN and n 0 when there are none. */
void aa_timing_stats_of(const double *values, int n, struct aa_timing_stats *out);
/* The GPU time of the pass named `name` over every timed render of m that ran it. */
void aa_pass_timing_stats(const struct aa_method_result *m, const char *name, struct aa_timing_stats *out);

/* Per-method summary over frames (computed, never stored separately). Times are over every timed
 * render (frames x timing.repeat); quality over the scored frames. */
struct aa_method_summary {
	double gpu_ms_median, gpu_ms_p90, gpu_ms_mean;
	struct aa_timing_stats gpu_ms, cpu_ms; /* the full distributions (gpu_ms_median = gpu_ms.median) */
	double cpu_ms_median;
	double mse_mean;
	double psnr_mean;          /* from mse_mean; NAN if every frame identical */
	bool psnr_identical;
	double ssim_mean;
	double flip_mean;          /* mean over the frames that have a FLIP value, NAN when none */
	double flicker_mean;       /* over frames 1.., NAN for one frame */
	double over_threshold_mean; /* pixels over the job's over_threshold, mean over frames */
	int best_frame, worst_frame; /* by PSNR (identical counts as best) */
	double best_psnr, worst_psnr;
};
void aa_method_summarize(const struct aa_method_result *m, struct aa_method_summary *out);
/* PSNR of the reference's N/2- against its N-sample image from the mean MSE over its frames; NAN when none
 * or identical (*identical says which). */
double aa_reference_convergence_psnr(const struct aa_reference_result *ref, bool *identical);
/* Median and p-th percentile (0..100, linear interpolation) of n values (the array is not modified). */
double aa_percentile(const double *values, int n, double p);

#endif
