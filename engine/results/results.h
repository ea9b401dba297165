/* Stored results of a job: results.json (docs/results-format.md), per-frame PNGs and report.html. */
#ifndef AA_RESULTS_H
#define AA_RESULTS_H

#include <stdio.h>

#include <jansson.h>

#include "../job.h"

/* Directory name of a method's images: the label with ':' -> '_', '=' -> '-', ',' -> '_'
 * ("ssaa:samples=16" -> "ssaa_samples-16"). The reference uses "reference". */
void aa_results_method_dirname(const char *label, char *out, size_t size);

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
/* Writes dir/results.json atomically (temp file, fsync, rename). */
int aa_results_write_json(const struct aa_job_result *r, const char *dir, struct aa_error *err);
/* Writes a JSON document (results.json of a job or a suite) atomically into dir, as results.json is written. */
int aa_results_write_json_doc(const json_t *root, const char *dir, const char *name, struct aa_error *err);
/* Writes dir/name atomically: a temp file in dir, fsync, rename over name, fsync dir. */
int aa_results_write_file_atomic(const char *dir, const char *name, const char *data, size_t size,
				 struct aa_error *err);
/* Writes dir/report.html: the table, an SVG chart of GPU ms vs PSNR, per-method images. */
int aa_report_write_html(const struct aa_job_result *r, const char *dir, struct aa_error *err);

/* PSNR of the reference's N/2- against its N-sample image from the mean MSE over its frames; NAN when none
 * or identical (*identical says which). */
double aa_reference_convergence_psnr(const struct aa_reference_result *ref, bool *identical);

/* The report's style sheet and HTML escaping, shared by the report of a suite (suite_results.c). */
extern const char aa_report_style[];
void aa_report_esc(FILE *o, const char *s);

/* exr/<dirname>/<NNNN>.exr: the frame's linear colour as float EXR (aalab run --exr; exr_frames.c). */
void aa_results_exr_relpath(const char *label, int ordinal, char *out, size_t size);
/* mkdir -p of every directory of path up to its last '/' (path is restored); -1 with err naming it. */
int aa_results_make_parents(char *path, struct aa_error *err);
/* Writes the EXR of a reference or method frame event (its linear image); other events write nothing. */
int aa_results_write_event_exr(const char *dir, const struct aa_event *ev, struct aa_error *err);

/* report.html's image viewer (report_viewer.c): its section of the page (data, viewer.css, viewer.js),
 * and viewer/NNNN.js beside the page, one per frame, carrying the frame's PNGs (read from dir). */
int aa_report_write_viewer(FILE *o, const struct aa_job_result *r, const char *dir, struct aa_error *err);
/* The count square tiles (side tile) where the methods' FLIP maps in dir sum highest over every method and
 * frame, worst first: [{x, y, w, h, ordinal (the frame where the tile is worst), flip_mean}]; empty
 * without kept frames or when a map cannot be read (report_regions.c). */
json_t *aa_report_worst_regions(const struct aa_job_result *r, const char *dir, int tile, int count);
int aa_report_write_viewer_frames(const struct aa_job_result *r, const char *dir, struct aa_error *err);
/* report.html's warnings panel (report_warnings.c): what makes numbers of this job untrustworthy. */
void aa_report_write_warnings(FILE *o, const struct aa_job_result *r, const struct aa_method_summary *sum);
/* A chart point's label: where it is drawn (x, baseline y; anchored at its right end when `end`) and the
 * span it takes, x0..x1. aa_report_spread_labels moves labels down until no two overlap (report_html.c). */
struct aa_point_label {
	double x, y, x0, x1;
	bool end;
};
#define AA_LABEL_LINE 13.0 /* px between two labels' baselines */
void aa_report_spread_labels(struct aa_point_label *labels, int n);

#endif
