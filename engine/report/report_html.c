/* report.html: one self-contained page (inline CSS, SVG and script, nothing loaded but the job's own
 * files beside it) showing what each method's accuracy costs: the verdict and warnings, the cards, the
 * cost-vs-accuracy chart and the table (report_charts.c, report_tables.c), the image viewer
 * (report_viewer.c), error-threshold curves, PSNR per frame and the frame plan; the page's assembly and
 * the helpers its parts share. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "results/results.h"
#include "methods/methods.h"
#include "report/report.h"
#include "report/report_parts.h"
#include "results/front.h"
#include "results/warnings.h"
#include "run/job_spec.h"

/* Each method's colour, in job order, in every chart and table of the page. */
static const char *const palette[] = { "#2563eb", "#dc2626", "#16a34a", "#ea580c", "#7c3aed",
				       "#0891b2", "#db2777", "#65a30d", "#92400e", "#475569" };

const char *aa_report_color(int i)
{
	return palette[i % (int)(sizeof palette / sizeof palette[0])];
}

void aa_report_esc(FILE *o, const char *s)
{
	for (; s && *s; s++) {
		switch (*s) {
		case '&': fputs("&amp;", o); break;
		case '<': fputs("&lt;", o); break;
		case '>': fputs("&gt;", o); break;
		case '"': fputs("&quot;", o); break;
		case '\'': fputs("&#39;", o); break;
		default: fputc((unsigned char)*s < 0x20 ? ' ' : *s, o);
		}
	}
}


/* A number with fixed decimals, or a dash when there is none. */
void aa_report_put_num(FILE *o, double v, int decimals)
{
	if (isfinite(v))
		fprintf(o, "%.*f", decimals, v);
	else
		fputs("&mdash;", o);
}

void aa_report_put_psnr(FILE *o, double psnr, bool identical)
{
	if (identical)
		fputs("<span class=\"ident\" title=\"the images are identical: PSNR is infinite\">identical</span>", o);
	else
		aa_report_put_num(o, psnr, 2);
}

/* Mean over frames of the share of pixels above threshold t, NAN if no frame has it. */
double aa_report_curve_mean(const struct aa_method_result *m, int t)
{
	double sum = 0;
	int n = 0;
	for (int i = 0; i < m->frame_count; i++)
		if (isfinite(m->frames[i].metrics.exceed[t])) {
			sum += m->frames[i].metrics.exceed[t];
			n++;
		}
	return n ? sum / n : NAN;
}

int aa_report_write_html(const struct aa_job_result *r, const char *dir, struct aa_error *err)
{
	struct aa_method_summary sum[AA_MAX_METHODS];
	struct aa_job_result view = *r; /* a copy whose counts are clamped to the arrays */
	if (view.method_count > AA_MAX_METHODS)
		view.method_count = AA_MAX_METHODS;
	if (view.method_count < 0)
		view.method_count = 0;
	for (int i = 0; i < view.method_count; i++) {
		if (!view.methods[i].frames)
			view.methods[i].frame_count = 0;
		aa_method_summarize(&view.methods[i], &sum[i]);
	}

	char *buf = NULL;
	size_t size = 0;
	FILE *o = open_memstream(&buf, &size);
	if (!o)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory writing report.html");
	const char *title = *view.spec.name ? view.spec.name : (*view.scene_name ? view.scene_name : view.spec.scene);
	fputs("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
	      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>aalab: ", o);
	aa_report_esc(o, title);
	fprintf(o, "</title>\n<style>%s</style>\n</head>\n<body><main>\n<h1>", aa_report_style);
	aa_report_esc(o, title);
	fputs("</h1>\n<p class=\"sub\">aalab render-and-compare report", o);
	if (*view.started_at) {
		fputs(" \xc2\xb7 ", o);
		aa_report_esc(o, view.started_at);
	}
	fputs("</p>\n", o);
	/* first what a reader wants to know, as results.json says it: the verdict and what qualifies it */
	json_t *verdict = aa_verdict_json(&view), *warnings = verdict ? aa_results_warnings_json(&view, verdict) : NULL;
	aa_report_write_verdict(o, verdict, warnings);
	fputs("<div class=\"cards\">\n", o);
	aa_report_summary_cards(o, &view);
	fputs("</div>\n<h2 id=\"cost-chart\">GPU time against PSNR</h2>\n", o);
	aa_report_chart_cost_accuracy(o, &view, sum, verdict);
	fputs("<h2 id=\"cost\">Cost and accuracy</h2>\n", o);
	aa_report_cost_table(o, &view, sum, verdict);
	json_decref(verdict);
	json_decref(warnings);
	fputs("<h2 id=\"images\">Images</h2>\n", o);
	if (aa_report_write_viewer(o, &view, dir, err)) {
		fclose(o);
		free(buf);
		return -1;
	}
	fputs("<h2 id=\"thresholds\">Error-threshold curves</h2>\n", o);
	aa_report_chart_thresholds(o, &view);
	if (view.spec.frames > 1) {
		fputs("<h2 id=\"per-frame\">PSNR per frame</h2>\n", o);
		aa_report_chart_psnr_per_frame(o, &view);
	}
	fputs("<h2 id=\"plan\">Frame plan</h2>\n<p class=\"note\">Only the passes the scene and the methods need run; "
	      "each row says why.</p>\n", o);
	aa_report_plan_table(o, &view);
	fputs("<h2 id=\"methods\">Methods</h2>\n", o);
	aa_report_method_sections(o, &view);
	fputs("<footer>Every number on this page comes from results.json in the same directory. PSNR of identical "
	      "images is infinite and shown as &ldquo;identical&rdquo;.</footer>\n</main></body>\n</html>\n", o);
	if (fclose(o) != 0 || !buf) {
		free(buf);
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory writing report.html");
	}
	/* the frames' scripts first: the page never names a script that is not there yet */
	int rc = aa_report_write_viewer_frames(&view, dir, err);
	if (rc == 0)
		rc = aa_results_write_file_atomic(dir, "report.html", buf, size, err);
	free(buf);
	return rc;
}

