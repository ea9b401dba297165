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

/* Every figure of the page in a sentence, linked from the top. */
void aa_report_glossary(FILE *o)
{
	static const char *const terms[][2] = {
		{ "Reference", "the image every method is measured against: the same frame rendered with N jittered samples "
			       "per pixel and averaged (its own sample positions, never a method's)." },
		{ "Convergence PSNR", "the PSNR of the reference's N/2-sample image against its N-sample image: how much "
				      "noise is left in the reference. A method whose PSNR is near or above it is measured against "
				      "that noise, not against the true image; under 40 dB, raise reference.samples." },
		{ "PSNR", "peak signal-to-noise ratio of a method's frame against the reference, in dB: higher is closer; "
			  "identical images have infinite PSNR, shown as \xe2\x80\x9cidentical\xe2\x80\x9d." },
		{ "SSIM", "structural similarity against the reference, 1 for the same image." },
		{ "FLIP", "NVIDIA's FLIP: the difference a viewer perceives when flipping between the method and the "
			  "reference, per pixel from 0 (none) to 1; the mean over pixels and frames." },
		{ "Flicker", "the mean absolute difference between a method's change from one frame to the next and the "
			     "reference's change, in 8-bit levels: shimmer the reference does not have." },
		{ "GPU ms", "GPU time of a frame (every pass of the method) from timestamp queries, over every timed render "
			    "(frames x repeat): median, the 10th to 90th percentile (p10-p90) and the fastest (min)." },
		{ "Front", "the methods no other method beats: none is both cheaper (p10-p90 spreads apart) and at least as "
			   "good in PSNR and FLIP. A tie in cost means the spreads overlap." },
		{ "Error-threshold curve", "the share of pixels whose luminance error exceeds each threshold: the tail "
					   "where methods differ." },
		{ "Worst regions", "the 16-pixel tiles with the most FLIP error summed over every method and frame." },
	};
	fputs("<h2 id=\"glossary\">Glossary</h2>\n<dl class=\"glossary\">\n", o);
	for (size_t i = 0; i < sizeof terms / sizeof terms[0]; i++) {
		fputs("<dt>", o);
		aa_report_esc(o, terms[i][0]);
		fputs("</dt><dd>", o);
		aa_report_esc(o, terms[i][1]);
		fputs("</dd>\n", o);
	}
	fputs("</dl>\n", o);
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
	fputs("</div>\n<p class=\"note\">What every figure means: <a href=\"#glossary\">glossary</a> at the end of the "
	      "page; hover a column head for its short form.</p>\n<h2 id=\"cost-chart\">GPU time against PSNR</h2>\n", o);
	aa_report_chart_cost_accuracy(o, &view, sum, verdict);
	fputs("<h2 id=\"cost\">Cost and accuracy</h2>\n", o);
	aa_report_cost_table(o, &view, sum, verdict);
	fputs("<h2 id=\"passes\">GPU time by pass</h2>\n", o);
	aa_report_chart_passes(o, &view);
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
	fputs("<h2 id=\"memory\">Memory</h2>\n", o);
	aa_report_method_sections(o, &view);
	aa_report_glossary(o);
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

