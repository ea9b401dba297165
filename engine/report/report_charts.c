/* report.html's charts, drawn as inline SVG: cost against accuracy (one labelled point per method, its
 * GPU time's p10-p90 bar, the front ringed), the error-threshold curves and PSNR per frame. */
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
#include "util/json_text.h"


/* The SVG coordinate box of every chart and its plot margins (left, right, top, bottom). */
#define CW 720.0
#define CH 380.0
#define ML 64.0
#define MR 24.0
#define MT 16.0
#define MB 48.0
/* Height of the strip above a PSNR plot where identical (infinite-PSNR) values are drawn. */
#define BAND 30.0

struct chart {
	FILE *o;
	double x0, x1, y0, y1; /* data range; y in log10 units when ylog */
	bool ylog;
	double band;           /* BAND when identical values are drawn above the plot, else 0 */
};

static double clampd(double v, double lo, double hi)
{
	return v < lo ? lo : v > hi ? hi : v;
}

static double cx(const struct chart *c, double x)
{
	const double px = ML + (x - c->x0) / (c->x1 - c->x0) * (CW - ML - MR);
	return isfinite(px) ? clampd(px, ML, CW - MR) : ML;
}

/* y of a value; identical values (passed as INFINITY) sit in the band above the plot. */
static double cy(const struct chart *c, double y)
{
	const double top = MT + c->band, bottom = CH - MB;
	if (y == INFINITY && c->band > 0)
		return MT + c->band / 2;
	if (c->ylog)
		y = log10(y);
	const double py = top + (c->y1 - y) / (c->y1 - c->y0) * (bottom - top);
	return isfinite(py) ? clampd(py, top, bottom) : bottom;
}

/* A step of 1, 2 or 5 times a power of ten giving about five ticks over span. */
static double nice_step(double span)
{
	const double raw = span / 5, e = pow(10, floor(log10(raw))), f = raw / e;
	return (f <= 1 ? 1 : f <= 2 ? 2 : f <= 5 ? 5 : 10) * e;
}

/* Widens [lo, hi] to whole steps; a degenerate range gets a unit of room so nothing divides by zero. */
static void nice_range(double *lo, double *hi, double *step)
{
	if (!isfinite(*lo) || !isfinite(*hi)) {
		*lo = 0;
		*hi = 1;
	}
	if (*hi - *lo < 1e-9 * fmax(1.0, fabs(*hi))) {
		const double pad = fmax(0.5, fabs(*hi) * 0.05);
		*lo -= *lo == 0 ? 0 : pad;
		*hi += pad;
	}
	*step = nice_step(*hi - *lo);
	*lo = floor(*lo / *step) * *step;
	*hi = ceil(*hi / *step) * *step;
}

static void chart_begin(struct chart *c, const char *aria, double xstep, double ystep, const char *xlabel,
			const char *ylabel)
{
	FILE *o = c->o;
	const double top = MT + c->band, bottom = CH - MB;
	fprintf(o, "<svg class=\"chart\" viewBox=\"0 0 %.0f %.0f\" role=\"img\" aria-label=\"", CW, CH);
	aa_report_esc(o, aria);
	fputs("\" xmlns=\"http://www.w3.org/2000/svg\">\n", o);
	fprintf(o, "<rect class=\"plot\" x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\"/>\n", ML, top,
		CW - ML - MR, bottom - top);
	/* Ticks are whole multiples of the step inside the range, computed as (first + k) * step rather than
	 * by accumulation so that labels stay exact. */
	const double xfirst = ceil(c->x0 / xstep - 1e-9), yfirst = ceil(c->y0 / ystep - 1e-9);
	for (int k = 0; k <= 40; k++) {
		double t = (xfirst + k) * xstep;
		if (t > c->x1 + xstep * 1e-6)
			break;
		if (fabs(t) < xstep * 1e-9)
			t = 0;
		const double x = cx(c, t);
		fprintf(o, "<line class=\"grid\" x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\"/>"
			   "<text class=\"tick\" x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">%g</text>\n",
			x, top, x, bottom, x, bottom + 16, t);
	}
	for (int k = 0; k <= 40; k++) {
		double t = (yfirst + k) * ystep;
		if (t > c->y1 + ystep * 1e-6)
			break;
		if (fabs(t) < ystep * 1e-9)
			t = 0;
		const double y = cy(c, c->ylog ? pow(10, t) : t);
		fprintf(o, "<line class=\"grid\" x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\"/>", ML, y, CW - MR, y);
		if (c->ylog) /* shares of pixels read best as percentages: 100%, 1%, 0.001% (ticks are decades) */
			fprintf(o, "<text class=\"tick\" x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\">%.*f%%</text>\n",
				ML - 6, y + 4, t < -2 ? (int)(-2 - t) : 0, pow(10, t) * 100);
		else
			fprintf(o, "<text class=\"tick\" x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\">%g</text>\n", ML - 6,
				y + 4, t);
	}
	if (c->band > 0)
		fprintf(o, "<line class=\"band\" x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\"/>"
			   "<text class=\"tick\" x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\">identical</text>\n",
			ML, top, CW - MR, top, ML - 6, MT + c->band / 2 + 4);
	fprintf(o, "<text class=\"axis\" x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">", (ML + CW - MR) / 2, CH - 8);
	aa_report_esc(o, xlabel);
	fprintf(o, "</text>\n<text class=\"axis\" transform=\"translate(16 %.1f) rotate(-90)\" text-anchor=\"middle\">",
		(top + bottom) / 2);
	aa_report_esc(o, ylabel);
	fputs("</text>\n", o);
}

/* Polylines that break at gaps (values that cannot be drawn). */
struct series {
	FILE *o;
	const char *color;
	bool open;
};

static void series_point(struct series *s, double x, double y)
{
	if (!s->open)
		fprintf(s->o, "<polyline class=\"series\" stroke=\"%s\" points=\"", s->color);
	fprintf(s->o, "%.1f,%.1f ", x, y);
	s->open = true;
}

static void series_break(struct series *s)
{
	if (s->open)
		fputs("\"/>\n", s->o);
	s->open = false;
}

static void legend(FILE *o, const struct aa_job_result *r)
{
	fputs("<ul class=\"legend\">", o);
	for (int i = 0; i < r->method_count; i++) {
		fprintf(o, "<li><span class=\"swatch\" style=\"background:%s\"></span>", aa_report_color(i));
		aa_report_esc(o, r->methods[i].label);
		fputs("</li>", o);
	}
	fputs("</ul>\n", o);
}

/* GPU ms (x) against mean PSNR (y): the cost of accuracy at a glance. */
#define LABEL_CHAR 6.6    /* px per character, the chart's label font (an estimate: SVG text has no metrics) */

static bool boxes_overlap(double ax0, double ay0, double ax1, double ay1, double bx0, double by0, double bx1, double by1)
{
	return ax0 < bx1 && bx0 < ax1 && ay0 < by1 && by0 < ay1;
}

/* Distance from (x, y) to the nearest point of a label's box (0 inside it). */
static double box_distance(const struct aa_point_label *b, double x, double y)
{
	return hypot(fmax(fmax(b->x0 - x, 0), x - b->x1), fmax(fmax(b->y0 - y, 0), y - b->y1));
}

/* Whether label i may take box b: inside the plot, over no placed label and no point, and (strict) with
 * no other point nearer to it than its own, since a label beside someone else's point reads as theirs. */
static bool label_fits(const struct aa_point_label *b, int i, const double *px, const double *py, int n,
		       const struct aa_point_label *placed, const bool *done, const double box[4], bool strict)
{
	if (b->x0 < box[0] || b->y0 < box[1] || b->x1 > box[2] || b->y1 > box[3])
		return false;
	for (int j = 0; j < n; j++) {
		if (done[j] && boxes_overlap(b->x0, b->y0, b->x1, b->y1, placed[j].x0, placed[j].y0, placed[j].x1, placed[j].y1))
			return false;
		if (boxes_overlap(b->x0, b->y0, b->x1, b->y1, px[j] - AA_LABEL_DOT, py[j] - AA_LABEL_DOT, px[j] + AA_LABEL_DOT,
				  py[j] + AA_LABEL_DOT))
			return false;
	}
	if (!strict)
		return true;
	const double own = box_distance(b, px[i], py[i]);
	for (int j = 0; j < n; j++)
		if (j != i && (px[j] != px[i] || py[j] != py[i]) && box_distance(b, px[j], py[j]) < fmin(own, 16))
			return false;
	return true;
}

/* Places each point's label (l[i].x1 - l[i].x0 its width on entry) beside its point if there is room,
 * else at the nearest free spot around it (rings of growing radius, eight directions each) with a
 * leader line back to it; points with the most neighbours choose first. Never over another label or a
 * point: methods of about the same cost and PSNR once printed their names over each other, and then
 * far below every point. box is the plot: x0, y0, x1, y1. The dashboard's charts place theirs the same
 * way (web/charts.js). */
void aa_report_place_labels(struct aa_point_label *l, const double *px, const double *py, int n, const double box[4])
{
	static const int dirs[8][2] = { { 1, 0 }, { -1, 0 }, { 1, -1 }, { 1, 1 }, { -1, -1 }, { -1, 1 }, { 0, -1 }, { 0, 1 } };
	int order[AA_MAX_METHODS], crowd[AA_MAX_METHODS];
	bool done[AA_MAX_METHODS] = { false };
	n = n > AA_MAX_METHODS ? AA_MAX_METHODS : n;
	for (int i = 0; i < n; i++) {
		order[i] = i;
		crowd[i] = 0;
		for (int j = 0; j < n; j++)
			crowd[i] += hypot(px[j] - px[i], py[j] - py[i]) < 60;
	}
	for (int i = 1; i < n; i++) /* most crowded first, then left to right: stable */
		for (int j = i; j > 0; j--) {
			const int a = order[j], b = order[j - 1];
			if (!(crowd[a] > crowd[b] || (crowd[a] == crowd[b] && px[a] < px[b])))
				break;
			order[j] = b;
			order[j - 1] = a;
		}
	for (int k = 0; k < n; k++) {
		const int i = order[k];
		const double w = l[i].x1 - l[i].x0 + 4;
		struct aa_point_label best = { 0 };
		bool found = false;
		for (int strict = 1; strict >= 0 && !found; strict--)
			for (double r = AA_LABEL_DOT + 1; r <= 240 && !found; r += 10)
				for (int d = 0; d < 8 && !found; d++) {
					const double cx0 = px[i] + dirs[d][0] * r, cy0 = py[i] + dirs[d][1] * r * 0.8;
					struct aa_point_label b = { 0 };
					b.x0 = dirs[d][0] > 0 ? cx0 : dirs[d][0] < 0 ? cx0 - w : cx0 - w / 2;
					b.y0 = dirs[d][1] > 0 ? cy0 : dirs[d][1] < 0 ? cy0 - AA_LABEL_HEIGHT : cy0 - AA_LABEL_HEIGHT / 2;
					b.x1 = b.x0 + w;
					b.y1 = b.y0 + AA_LABEL_HEIGHT;
					if (label_fits(&b, i, px, py, n, l, done, box, strict)) {
						best = b;
						found = true;
					}
				}
		if (!found) { /* nowhere free: beside the point, inside the plot, still joined by its line */
			best.x0 = fmin(fmax(px[i] + AA_LABEL_DOT + 1, box[0]), box[2] - w);
			best.y0 = py[i] - AA_LABEL_HEIGHT / 2;
			best.x1 = best.x0 + w;
			best.y1 = best.y0 + AA_LABEL_HEIGHT;
		}
		const double ex = fmin(fmax(px[i], best.x0), best.x1), ey = fmin(fmax(py[i], best.y0), best.y1);
		best.lx = ex;
		best.ly = ey;
		best.leader = hypot(ex - px[i], ey - py[i]) > AA_LABEL_DOT + 4;
		best.x = best.x0 + 2;
		best.y = best.y1 - 4;
		l[i] = best;
		done[i] = true;
	}
}

/* The plotted point of a label, or -1 (k indexes plotted[], px[], py[]). */
static int plotted_point(const struct aa_job_result *r, const int *plotted, int n, const char *label)
{
	for (int k = 0; label && k < n; k++)
		if (!strcmp(r->methods[plotted[k]].label, label))
			return k;
	return -1;
}

/* Under the points: the front (verdict.front) as a grey staircase, cheapest first, and each method
 * family (verdict.families) as a line through its configurations by ascending cost, in the colour of its
 * first method in job order, as the dashboard's case view draws them (web/suite.js). */
static void draw_front_and_families(FILE *o, const struct aa_job_result *r, const json_t *verdict, const int *plotted,
				    const double *px, const double *py, int n)
{
	int front[AA_MAX_METHODS], nf = 0;
	json_t *v;
	size_t i, j;
	json_array_foreach(json_object_get(verdict, "front"), i, v) {
		const int k = plotted_point(r, plotted, n, json_string_value(v));
		if (k >= 0 && nf < AA_MAX_METHODS)
			front[nf++] = k;
	}
	for (int a = 1; a < nf; a++) /* cheapest (leftmost) first */
		for (int b = a; b > 0 && px[front[b]] < px[front[b - 1]]; b--) {
			const int t = front[b];
			front[b] = front[b - 1];
			front[b - 1] = t;
		}
	if (nf > 1) {
		fprintf(o, "<path class=\"front-line\" d=\"M%.1f %.1f", px[front[0]], py[front[0]]);
		for (int a = 1; a < nf; a++)
			fprintf(o, "H%.1fV%.1f", px[front[a]], py[front[a]]);
		fputs("\"/>\n", o);
	}
	json_t *f;
	json_array_foreach(json_object_get(verdict, "families"), i, f) {
		int first = AA_MAX_METHODS, count = 0;
		json_array_foreach(json_object_get(f, "methods"), j, v) {
			const int k = plotted_point(r, plotted, n, json_string_value(v));
			if (k >= 0) {
				count++;
				first = plotted[k] < first ? plotted[k] : first;
			}
		}
		if (count < 2)
			continue;
		fputs("<polyline class=\"family-line\" data-family=\"", o);
		aa_report_esc(o, aa_json_string(f, "family"));
		fprintf(o, "\" stroke=\"%s\" points=\"", aa_report_color(first));
		json_array_foreach(json_object_get(f, "methods"), j, v) {
			const int k = plotted_point(r, plotted, n, json_string_value(v));
			if (k >= 0)
				fprintf(o, "%.1f,%.1f ", px[k], py[k]);
		}
		fputs("\"/>\n", o);
	}
}

/* Below the chart: one entry per family, its configurations by cost and its front (verdict.families). */
static void family_legend(FILE *o, const struct aa_job_result *r, const json_t *verdict)
{
	json_t *f, *v;
	size_t i, j;
	if (!json_array_size(json_object_get(verdict, "families")))
		return;
	fputs("<ul class=\"legend family-legend\">", o);
	json_array_foreach(json_object_get(verdict, "families"), i, f) {
		int first = 0;
		for (int m = r->method_count - 1; m >= 0; m--) /* the family's first method in job order */
			json_array_foreach(json_object_get(f, "methods"), j, v)
				if (!strcmp(r->methods[m].label, json_string_value(v) ? json_string_value(v) : ""))
					first = m;
		fputs("<li data-family=\"", o);
		aa_report_esc(o, aa_json_string(f, "family"));
		fprintf(o, "\"><span class=\"family-swatch\" style=\"border-color:%s\"></span>", aa_report_color(first));
		aa_report_esc(o, aa_json_string(f, "family"));
		fputs(": ", o);
		json_array_foreach(json_object_get(f, "methods"), j, v) {
			fputs(j ? " &rarr; " : "", o);
			aa_report_esc(o, json_string_value(v) ? json_string_value(v) : "");
		}
		fputs(" (front: ", o);
		if (!json_array_size(json_object_get(f, "front")))
			fputs("none, its costs are not ranked", o);
		json_array_foreach(json_object_get(f, "front"), j, v) {
			fputs(j ? ", " : "", o);
			aa_report_esc(o, json_string_value(v) ? json_string_value(v) : "");
		}
		fputs(")</li>", o);
	}
	fputs("</ul>\n", o);
}

void aa_report_chart_cost_accuracy(FILE *o, const struct aa_job_result *r, const struct aa_method_summary *sum,
				const json_t *verdict)
{
	double xmax = 0, ylo = INFINITY, yhi = -INFINITY;
	bool any_identical = false, any = false;
	for (int i = 0; i < r->method_count; i++) {
		if (!isfinite(sum[i].gpu_ms_median))
			continue;
		xmax = fmax(xmax, isfinite(sum[i].gpu_ms.p90) ? sum[i].gpu_ms.p90 : sum[i].gpu_ms_median);
		if (sum[i].psnr_identical) {
			any_identical = any = true;
		} else if (isfinite(sum[i].psnr_mean)) {
			ylo = fmin(ylo, sum[i].psnr_mean);
			yhi = fmax(yhi, sum[i].psnr_mean);
			any = true;
		}
	}
	if (!any) {
		fputs("<p class=\"note\">No method has both a GPU time and a PSNR to plot.</p>\n", o);
		return;
	}
	struct chart c = { .o = o, .x0 = 0, .x1 = xmax * 1.08, .y0 = ylo - 1, .y1 = yhi + 1,
			   .band = any_identical ? BAND : 0 };
	if (!isfinite(ylo)) { /* every plotted method is identical: any range will do */
		c.y0 = 0;
		c.y1 = 50;
	}
	double xstep, ystep;
	nice_range(&c.x0, &c.x1, &xstep);
	nice_range(&c.y0, &c.y1, &ystep);
	fputs("<figure>\n", o);
	chart_begin(&c, "GPU time per frame against mean PSNR, one point per method", xstep, ystep,
		    "GPU ms per frame (median, bar p10-p90)", "PSNR dB (mean; higher is better)");
	struct aa_point_label labels[AA_MAX_METHODS];
	int plotted[AA_MAX_METHODS], n = 0;
	double px[AA_MAX_METHODS] = { 0 }, py[AA_MAX_METHODS] = { 0 };
	for (int i = 0; i < r->method_count && n < AA_MAX_METHODS; i++) {
		const double psnr = sum[i].psnr_identical ? INFINITY : sum[i].psnr_mean;
		if (!isfinite(sum[i].gpu_ms_median) || !(psnr == INFINITY || isfinite(psnr)))
			continue;
		const double x = cx(&c, sum[i].gpu_ms_median), y = cy(&c, psnr);
		const double w = LABEL_CHAR * (double)strlen(r->methods[i].label);
		labels[n] = (struct aa_point_label){ .x0 = 0, .x1 = w };
		px[n] = x, py[n] = y;
		plotted[n++] = i;
	}
	const double plot[4] = { ML + 2, MT + 2, CW - MR - 2, CH - MB - 2 };
	aa_report_place_labels(labels, px, py, n, plot);
	draw_front_and_families(o, r, verdict, plotted, px, py, n);
	for (int k = 0; k < n; k++) {
		const int i = plotted[k];
		const double x = px[k], y = py[k];
		/* the time's spread over every timed render: an error bar from p10 to p90 */
		if (isfinite(sum[i].gpu_ms.p10) && isfinite(sum[i].gpu_ms.p90))
			fprintf(o, "<path class=\"spread\" stroke=\"%s\" d=\"M%.1f %.1fH%.1fM%.1f %.1fv8M%.1f %.1fv8\"/>\n",
				aa_report_color(i), cx(&c, sum[i].gpu_ms.p10), y, cx(&c, sum[i].gpu_ms.p90), cx(&c, sum[i].gpu_ms.p10),
				y - 4, cx(&c, sum[i].gpu_ms.p90), y - 4);
		/* the front is ringed: the methods no other beats (verdict.methods[].place) */
		const char *place = json_string_value(json_object_get(json_array_get(json_object_get(verdict, "methods"),
										      (size_t)i), "place"));
		if (place && !strcmp(place, "front"))
			fprintf(o, "<circle class=\"front\" cx=\"%.1f\" cy=\"%.1f\" r=\"9\" fill=\"none\" stroke=\"%s\" "
				   "stroke-width=\"2\"/>\n", x, y, aa_report_color(i));
		fprintf(o, "<circle class=\"method\" cx=\"%.1f\" cy=\"%.1f\" r=\"5.5\" fill=\"%s\"><title>", x, y, aa_report_color(i));
		aa_report_esc(o, r->methods[i].label);
		fprintf(o, ": %.2f ms (p10-p90 %.2f-%.2f, n %d), ", sum[i].gpu_ms_median, sum[i].gpu_ms.p10,
			sum[i].gpu_ms.p90, sum[i].gpu_ms.n);
		if (sum[i].psnr_identical)
			fputs("identical", o);
		else
			fprintf(o, "%.2f dB", sum[i].psnr_mean);
		fputs("</title></circle>", o);
		/* a label away from its point is tied back to it by a line in the point's colour */
		if (labels[k].leader)
			fprintf(o, "<line class=\"leader\" stroke=\"%s\" x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\"/>", aa_report_color(i),
				x, y, labels[k].lx, labels[k].ly);
		fprintf(o, "<text class=\"point\" x=\"%.1f\" y=\"%.1f\">", labels[k].x, labels[k].y);
		aa_report_esc(o, r->methods[i].label);
		fputs("</text>\n", o);
	}
	fputs("</svg>\n", o);
	family_legend(o, r, verdict);
	fprintf(o, "<figcaption>Each point is one method: further left is cheaper, higher is closer to the "
		   "reference. Bars span the 10th to 90th percentile of the GPU time over every timed render; a ring marks "
		   "a method on the front (the verdict above), joined by the grey staircase%s</figcaption>\n"
		   "</figure>\n", json_array_size(json_object_get(verdict, "families"))
		? "; a coloured line joins each method family's configurations by cost." : ".");
}

/* Share of pixels whose luminance error exceeds each threshold, log scale: the tail where methods differ. */
void aa_report_chart_thresholds(FILE *o, const struct aa_job_result *r)
{
	double min_positive = 1;
	bool any = false;
	for (int i = 0; i < r->method_count; i++)
		for (int t = 0; t < AA_THRESHOLD_COUNT; t++) {
			const double v = aa_report_curve_mean(&r->methods[i], t);
			if (isfinite(v))
				any = true;
			if (v > 0 && v < min_positive)
				min_positive = v;
		}
	if (!any) {
		fputs("<p class=\"note\">No error-threshold data.</p>\n", o);
		return;
	}
	/* Floor at the decade below the smallest share, between one in ten million and 1%. */
	const double floor_log = clampd(floor(log10(min_positive)), -7, -2);
	struct chart c = { .o = o, .x0 = 0, .x1 = 1, .y0 = floor_log, .y1 = 0, .ylog = true };
	fputs("<figure>\n", o);
	chart_begin(&c, "Share of pixels whose error exceeds each threshold, one line per method", 0.1, 1,
		    "luminance error threshold (0..1)", "share of pixels above threshold");
	for (int i = 0; i < r->method_count; i++) {
		struct series s = { .o = o, .color = aa_report_color(i) };
		for (int t = 0; t < AA_THRESHOLD_COUNT; t++) {
			const double v = aa_report_curve_mean(&r->methods[i], t);
			if (!isfinite(v)) {
				series_break(&s);
				continue;
			}
			/* The curve only falls; once it reaches zero, drop to the floor and stop drawing. */
			series_point(&s, cx(&c, t / 100.0), cy(&c, fmax(v, pow(10, floor_log))));
			if (v <= 0)
				break;
		}
		series_break(&s);
	}
	fputs("</svg>\n", o);
	legend(o, r);
	fputs("<figcaption>Lower is better. A line that ends at the bottom means no pixel exceeds larger "
	      "thresholds.</figcaption>\n</figure>\n", o);
}

void aa_report_chart_psnr_per_frame(FILE *o, const struct aa_job_result *r)
{
	double xlo = INFINITY, xhi = -INFINITY, ylo = INFINITY, yhi = -INFINITY;
	bool any_identical = false;
	for (int i = 0; i < r->method_count; i++)
		for (int f = 0; f < r->methods[i].frame_count; f++) {
			const struct aa_frame_result *fr = &r->methods[i].frames[f];
			xlo = fmin(xlo, fr->frame);
			xhi = fmax(xhi, fr->frame);
			if (fr->metrics.identical)
				any_identical = true;
			else if (isfinite(fr->metrics.psnr)) {
				ylo = fmin(ylo, fr->metrics.psnr);
				yhi = fmax(yhi, fr->metrics.psnr);
			}
		}
	if (!isfinite(xlo) || (!isfinite(ylo) && !any_identical)) {
		fputs("<p class=\"note\">No per-frame PSNR to plot.</p>\n", o);
		return;
	}
	struct chart c = { .o = o, .x0 = xlo, .x1 = xhi, .y0 = ylo - 1, .y1 = yhi + 1, .band = any_identical ? BAND : 0 };
	if (!isfinite(ylo)) {
		c.y0 = 0;
		c.y1 = 50;
	}
	/* The frame axis spans exactly the frames rendered; its ticks are whole frames. */
	if (c.x1 <= c.x0)
		c.x1 = c.x0 + 1;
	double xstep = fmax(1, round(nice_step(c.x1 - c.x0))), ystep;
	nice_range(&c.y0, &c.y1, &ystep);
	fputs("<figure>\n", o);
	chart_begin(&c, "PSNR of every frame, one line per method", xstep, ystep, "frame", "PSNR dB");
	for (int i = 0; i < r->method_count; i++) {
		const struct aa_method_result *m = &r->methods[i];
		struct series s = { .o = o, .color = aa_report_color(i) };
		for (int f = 0; f < m->frame_count; f++) {
			const struct aa_metrics *mt = &m->frames[f].metrics;
			const double v = mt->identical ? INFINITY : mt->psnr;
			if (v == INFINITY || isfinite(v))
				series_point(&s, cx(&c, m->frames[f].frame), cy(&c, v));
			else
				series_break(&s);
		}
		series_break(&s);
	}
	fputs("</svg>\n", o);
	legend(o, r);
	fputs("<figcaption>Each line is one method's PSNR against the reference, frame by frame: higher is closer; a "
	      "dip is a frame the method gets wrong.", o);
	if (any_identical)
		fputs(" Identical frames sit in the band at the top.", o);
	fputs("</figcaption>\n</figure>\n", o);
}

/* Each method's GPU time split by pass: one bar per method, its passes end to end (the median of each pass
 * over every timed render, from the first frame's pass list), named in order after the bar; a hover gives
 * p10-p90 and n. Colours go by a pass's place in its method, as pass names are mostly the method's own. */
void aa_report_chart_passes(FILE *o, const struct aa_job_result *r)
{
	static const char *const pass_colour[] = { "#0072b2", "#e69f00", "#009e73", "#cc79a7", "#56b4e9", "#d55e00",
						   "#8c564b", "#000000" };
	double total[AA_MAX_METHODS] = { 0 }, xmax = 0;
	int rows = 0;
	for (int i = 0; i < r->method_count && i < AA_MAX_METHODS; i++) {
		const struct aa_method_result *m = &r->methods[i];
		for (int k = 0; m->frame_count > 0 && k < m->frames[0].pass_count && k < AA_MAX_PASSES; k++) {
			struct aa_timing_stats ts;
			aa_pass_timing_stats(m, m->frames[0].passes[k].name, &ts);
			if (isfinite(ts.median))
				total[i] += ts.median;
		}
		xmax = fmax(xmax, total[i]);
		rows++;
	}
	if (xmax <= 0) {
		fputs("<p class=\"note\">No per-pass GPU times.</p>\n", o);
		return;
	}
	/* the names after the bars: the chart is as wide as the longest line (12 px text, at most about 7.4 px
	 * a character), so that no name is cut off at the chart's edge; the page scales the chart to its card */
	double widest = 0;
	for (int i = 0; i < rows; i++) {
		const struct aa_method_result *m = &r->methods[i];
		double chars = 0;
		for (int k = 0; m->frame_count > 0 && k < m->frames[0].pass_count && k < AA_MAX_PASSES; k++)
			chars += strlen(m->frames[0].passes[k].name) + 13; /* "■ ", " 12.34", 3 spaces, and slack */
		widest = fmax(widest, chars * 7.4);
	}
	const double L = 150, R = 440, T = 8, row = 24, W = fmax(1080, R + 60 + widest), H = T + row * rows + 40;
	double lo = 0, hi = xmax, step;
	nice_range(&lo, &hi, &step);
	fprintf(o, "<figure>\n<svg class=\"chart passes\" viewBox=\"0 0 %.0f %.0f\" role=\"img\" aria-label=\"GPU time of each "
		   "method split by pass\" xmlns=\"http://www.w3.org/2000/svg\">\n", W, H);
	for (int k = 0; k <= 40; k++) {
		const double v = k * step, x = L + (R - L) * v / hi;
		if (v > hi + step * 1e-6)
			break;
		fprintf(o, "<line class=\"grid\" x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\"/><text class=\"tick\" x=\"%.1f\" "
			   "y=\"%.1f\" text-anchor=\"middle\">%g</text>\n", x, T, x, H - 34, x, H - 20, v);
	}
	fprintf(o, "<text class=\"axis\" x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">GPU ms per frame, median of each pass</text>\n",
		(L + R) / 2, H - 4);
	for (int i = 0; i < rows; i++) {
		const struct aa_method_result *m = &r->methods[i];
		const double y = T + row * i;
		fprintf(o, "<text class=\"tick\" x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\">", L - 6, y + 15);
		aa_report_esc(o, m->label);
		fputs("</text>\n", o);
		double at = 0;
		fprintf(o, "<text class=\"pass-names\" x=\"%.1f\" y=\"%.1f\">", R + 60, y + 15);
		for (int k = 0; m->frame_count > 0 && k < m->frames[0].pass_count && k < AA_MAX_PASSES; k++) {
			struct aa_timing_stats ts;
			aa_pass_timing_stats(m, m->frames[0].passes[k].name, &ts);
			const char *c = pass_colour[k % (int)(sizeof pass_colour / sizeof pass_colour[0])];
			fprintf(o, "<tspan fill=\"%s\">\xe2\x96\xa0 </tspan><tspan>", c);
			aa_report_esc(o, m->frames[0].passes[k].name);
			fputc(' ', o);
			aa_report_put_num(o, ts.median, 2);
			fputs(k + 1 < m->frames[0].pass_count ? "\xc2\xa0\xc2\xa0 </tspan>" : "</tspan>", o);
			at += isfinite(ts.median) ? ts.median : 0;
		}
		fputs("</text>\n", o);
		at = 0;
		for (int k = 0; m->frame_count > 0 && k < m->frames[0].pass_count && k < AA_MAX_PASSES; k++) {
			struct aa_timing_stats ts;
			aa_pass_timing_stats(m, m->frames[0].passes[k].name, &ts);
			if (!isfinite(ts.median))
				continue;
			const char *c = pass_colour[k % (int)(sizeof pass_colour / sizeof pass_colour[0])];
			fprintf(o, "<rect class=\"pass\" x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"%s\"><title>",
				L + (R - L) * at / hi, y + 3, (R - L) * ts.median / hi, row - 7, c);
			aa_report_esc(o, m->label);
			fputs(" \xc2\xb7 ", o);
			aa_report_esc(o, m->frames[0].passes[k].name);
			fprintf(o, ": %.2f ms (p10-p90 %.2f-%.2f, n %d)</title></rect>\n", ts.median, ts.p10, ts.p90, ts.n);
			at += ts.median;
		}
		fprintf(o, "<text class=\"tick\" x=\"%.1f\" y=\"%.1f\">%.2f</text>\n", L + (R - L) * at / hi + 4, y + 15, at);
	}
	fputs("</svg>\n<figcaption>Which pass costs what: each bar is a method's passes end to end, named in order on the right "
	      "with their median GPU ms (hover a segment for its p10&ndash;p90 and n).</figcaption>\n</figure>\n", o);
}
