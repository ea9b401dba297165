/* report.html of a job and of a suite: one self-contained page (tables, charts, warnings, the image
 * viewer) beside the job's images; and writing a run's results.json with its reports. */
#ifndef AA_REPORT_H
#define AA_REPORT_H

#include <stdio.h>

#include "results/results.h"

/* Writes dir/report.html: the table, an SVG chart of GPU ms vs PSNR, per-method images. */
int aa_report_write_html(const struct aa_job_result *r, const char *dir, struct aa_error *err);

/* The report's style sheet and HTML escaping, shared by the report of a suite (suite_results.c). */
extern const char aa_report_style[];
void aa_report_esc(FILE *o, const char *s);

/* report.html's image viewer (report_viewer.c): its section of the page (data, viewer.css, viewer.js),
 * and viewer/NNNN.js beside the page, one per frame, carrying the frame's PNGs (read from dir). */
int aa_report_write_viewer(FILE *o, const struct aa_job_result *r, const char *dir, struct aa_error *err);
/* The count square tiles (side tile) where the methods' FLIP maps in dir sum highest over every method and
 * frame, worst first: [{x, y, w, h, ordinal (the frame where the tile is worst), flip_mean}]; empty
 * without kept frames or when a map cannot be read (report_regions.c). */
json_t *aa_report_worst_regions(const struct aa_job_result *r, const char *dir, int tile, int count);
int aa_report_write_viewer_frames(const struct aa_job_result *r, const char *dir, struct aa_error *err);
/* report.html's top (report_verdict.c): the verdict object and the warnings[] of results.json, as they
 * are (either may be NULL). */
void aa_report_write_verdict(FILE *o, const json_t *verdict, const json_t *warnings);
/* A chart point's label: its box x0..x1 (on entry: its text's width), y0..y1; where its text starts (x,
 * baseline y); and when it sits away from its point, the leader line's end (lx, ly) on the box.
 * aa_report_place_labels puts every label beside its point or on a leader line, over no other label and
 * no point, inside box (x0, y0, x1, y1) (report_charts.c). */
struct aa_point_label {
	double x, y, x0, y0, x1, y1, lx, ly;
	bool leader;
};
#define AA_LABEL_HEIGHT 15.0 /* px of a label's box */
#define AA_LABEL_DOT 10.0    /* px around a point that no label covers (its front ring included) */
void aa_report_place_labels(struct aa_point_label *l, const double *px, const double *py, int n, const double box[4]);

/* Writes results.json and report.html into dir (and each case's report.html into its directory). */
int aa_suite_results_write(const struct aa_suite_result *r, const char *dir, struct aa_error *err);
/* The report of a suite: the summary table across cases, linking each case's own report. */
int aa_suite_report_write_html(const struct aa_suite_result *r, const char *dir, struct aa_error *err);

#endif
