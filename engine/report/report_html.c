/* report.html: one self-contained page (inline CSS, SVG and script, nothing loaded but the job's own
 * files beside it) showing what each method's accuracy costs: warnings, the image viewer
 * (report_viewer.c), the summary table, cost-vs-accuracy and error-threshold charts, PSNR per frame and
 * the frame plan. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "results/results.h"
#include "methods/methods.h"
#include "report/report.h"
#include "results/front.h"
#include "results/warnings.h"
#include "run/job_spec.h"

/* The SVG coordinate box of every chart and its plot margins (left, right, top, bottom). */
#define CW 720.0
#define CH 380.0
#define ML 64.0
#define MR 24.0
#define MT 16.0
#define MB 48.0
/* Height of the strip above a PSNR plot where identical (infinite-PSNR) values are drawn. */
#define BAND 30.0

static const char *const palette[] = { "#2563eb", "#dc2626", "#16a34a", "#ea580c", "#7c3aed",
				       "#0891b2", "#db2777", "#65a30d", "#92400e", "#475569" };

static const char *color(int i)
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

static void esc(FILE *o, const char *s)
{
	aa_report_esc(o, s);
}

/* A number with fixed decimals, or a dash when there is none. */
static void put_num(FILE *o, double v, int decimals)
{
	if (isfinite(v))
		fprintf(o, "%.*f", decimals, v);
	else
		fputs("&mdash;", o);
}

static void put_psnr(FILE *o, double psnr, bool identical)
{
	if (identical)
		fputs("<span class=\"ident\" title=\"the images are identical: PSNR is infinite\">identical</span>", o);
	else
		put_num(o, psnr, 2);
}

/* Mean over frames of the share of pixels above threshold t, NAN if no frame has it. */
static double curve_mean(const struct aa_method_result *m, int t)
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

/* ------------------------------------------------------------------------------------------- charts */

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
	esc(o, aria);
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
	esc(o, xlabel);
	fprintf(o, "</text>\n<text class=\"axis\" transform=\"translate(16 %.1f) rotate(-90)\" text-anchor=\"middle\">",
		(top + bottom) / 2);
	esc(o, ylabel);
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
		fprintf(o, "<li><span class=\"swatch\" style=\"background:%s\"></span>", color(i));
		esc(o, r->methods[i].label);
		fputs("</li>", o);
	}
	fputs("</ul>\n", o);
}

/* GPU ms (x) against mean PSNR (y): the cost of accuracy at a glance. */
#define LABEL_CHAR 6.6    /* px per character, the chart's label font (an estimate: SVG text has no metrics) */

/* Labels are ordered by height and each moves down a line at a time until it overlaps none above it:
 * methods of about the same cost and PSNR (fxaa and fxaa-cs, say) once printed their names over each
 * other. */
void aa_report_spread_labels(struct aa_point_label *l, int n)
{
	int order[AA_MAX_METHODS];
	for (int i = 0; i < n; i++)
		order[i] = i;
	for (int i = 1; i < n; i++) /* by height, then by input order: stable */
		for (int j = i; j > 0 && l[order[j]].y < l[order[j - 1]].y; j--) {
			int t = order[j];
			order[j] = order[j - 1];
			order[j - 1] = t;
		}
	for (int k = 1; k < n; k++) {
		struct aa_point_label *a = &l[order[k]];
		for (bool moved = true; moved;) {
			moved = false;
			for (int m = 0; m < k; m++) {
				const struct aa_point_label *b = &l[order[m]];
				/* only ever down: where b->y + a line rounds to b->y (a chart whose PSNR range is
				 * next to nothing puts labels near 1e18 px) the label stays, rather than loop */
				const double below = b->y + AA_LABEL_LINE;
				if (a->x0 < b->x1 && b->x0 < a->x1 && fabs(a->y - b->y) < AA_LABEL_LINE && below > a->y) {
					a->y = below;
					moved = true;
				}
			}
		}
	}
}

static void chart_cost_accuracy(FILE *o, const struct aa_job_result *r, const struct aa_method_summary *sum,
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
	double px[AA_MAX_METHODS], py[AA_MAX_METHODS];
	for (int i = 0; i < r->method_count && n < AA_MAX_METHODS; i++) {
		const double psnr = sum[i].psnr_identical ? INFINITY : sum[i].psnr_mean;
		if (!isfinite(sum[i].gpu_ms_median) || !(psnr == INFINITY || isfinite(psnr)))
			continue;
		const double x = cx(&c, sum[i].gpu_ms_median), y = cy(&c, psnr);
		const bool right = x > CW - MR - 170; /* keep labels inside the chart */
		const double w = LABEL_CHAR * (double)strlen(r->methods[i].label);
		const double lx = right ? x - 9 : x + 9;
		labels[n] = (struct aa_point_label){.x = lx, .y = y - 7, .x0 = right ? lx - w : lx, .x1 = right ? lx : lx + w,
						  .end = right};
		px[n] = x, py[n] = y;
		plotted[n++] = i;
	}
	aa_report_spread_labels(labels, n);
	for (int k = 0; k < n; k++) {
		const int i = plotted[k];
		const double x = px[k], y = py[k];
		/* the time's spread over every timed render: an error bar from p10 to p90 */
		if (isfinite(sum[i].gpu_ms.p10) && isfinite(sum[i].gpu_ms.p90))
			fprintf(o, "<path class=\"spread\" stroke=\"%s\" d=\"M%.1f %.1fH%.1fM%.1f %.1fv8M%.1f %.1fv8\"/>\n",
				color(i), cx(&c, sum[i].gpu_ms.p10), y, cx(&c, sum[i].gpu_ms.p90), cx(&c, sum[i].gpu_ms.p10),
				y - 4, cx(&c, sum[i].gpu_ms.p90), y - 4);
		/* the front is ringed: the methods no other beats (verdict.methods[].place) */
		const char *place = json_string_value(json_object_get(json_array_get(json_object_get(verdict, "methods"),
										      (size_t)i), "place"));
		if (place && !strcmp(place, "front"))
			fprintf(o, "<circle class=\"front\" cx=\"%.1f\" cy=\"%.1f\" r=\"9\" fill=\"none\" stroke=\"%s\" "
				   "stroke-width=\"2\"/>\n", x, y, color(i));
		fprintf(o, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"5.5\" fill=\"%s\"><title>", x, y, color(i));
		esc(o, r->methods[i].label);
		fprintf(o, ": %.2f ms (p10-p90 %.2f-%.2f, n %d), ", sum[i].gpu_ms_median, sum[i].gpu_ms.p10,
			sum[i].gpu_ms.p90, sum[i].gpu_ms.n);
		if (sum[i].psnr_identical)
			fputs("identical", o);
		else
			fprintf(o, "%.2f dB", sum[i].psnr_mean);
		fprintf(o, "</title></circle><text class=\"point\" x=\"%.1f\" y=\"%.1f\" text-anchor=\"%s\">",
			labels[k].x, labels[k].y, labels[k].end ? "end" : "start");
		esc(o, r->methods[i].label);
		fputs("</text>\n", o);
	}
	fputs("</svg>\n<figcaption>Each point is one method: further left is cheaper, higher is closer to the "
	      "reference. Bars span the 10th to 90th percentile of the GPU time over every timed render; a ring marks "
	      "a method on the front (the verdict above).</figcaption>\n"
	      "</figure>\n", o);
}

/* Share of pixels whose luminance error exceeds each threshold, log scale: the tail where methods differ. */
static void chart_thresholds(FILE *o, const struct aa_job_result *r)
{
	double min_positive = 1;
	bool any = false;
	for (int i = 0; i < r->method_count; i++)
		for (int t = 0; t < AA_THRESHOLD_COUNT; t++) {
			const double v = curve_mean(&r->methods[i], t);
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
		struct series s = { .o = o, .color = color(i) };
		for (int t = 0; t < AA_THRESHOLD_COUNT; t++) {
			const double v = curve_mean(&r->methods[i], t);
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

static void chart_psnr_per_frame(FILE *o, const struct aa_job_result *r)
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
		struct series s = { .o = o, .color = color(i) };
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
	fputs("</figure>\n", o);
}

/* ------------------------------------------------------------------------------------------- page */

const char aa_report_style[] =
	":root{--fg:#0f172a;--mute:#64748b;--line:#e2e8f0;--bg:#f8fafc;--card:#fff;--accent:#2563eb}"
	"*{box-sizing:border-box}"
	"body{margin:0;background:var(--bg);color:var(--fg);font:15px/1.5 system-ui,-apple-system,'Segoe UI',"
	"Roboto,sans-serif}"
	"main{max-width:1120px;margin:0 auto;padding:28px 20px 48px}"
	"h1{font-size:26px;margin:0 0 4px}h2{font-size:19px;margin:36px 0 12px;padding-bottom:6px;"
	"border-bottom:1px solid var(--line)}h3{font-size:16px;margin:0 0 6px}"
	".sub{color:var(--mute);margin:0 0 20px}"
	".cards{display:grid;grid-template-columns:repeat(auto-fill,minmax(200px,1fr));gap:12px}"
	".card{background:var(--card);border:1px solid var(--line);border-radius:10px;padding:12px 14px}"
	".card .k{font-size:12px;text-transform:uppercase;letter-spacing:.05em;color:var(--mute)}"
	".card .v{font-size:18px;font-weight:600;overflow-wrap:anywhere}.card .d{font-size:13px;color:var(--mute);"
	"overflow-wrap:anywhere}"
	"table{border-collapse:collapse;width:100%;background:var(--card);border:1px solid var(--line);"
	"border-radius:10px;overflow:hidden}"
	"th,td{padding:7px 10px;border-bottom:1px solid var(--line);text-align:left;vertical-align:top}"
	"th{background:#f1f5f9;font-size:13px;font-weight:600}tr:last-child td{border-bottom:0}"
	"td.n,th.n{text-align:right;font-variant-numeric:tabular-nums;white-space:nowrap}"
	".swatch{display:inline-block;width:11px;height:11px;border-radius:3px;margin-right:7px;vertical-align:-1px}"
	".ident{color:#15803d;font-weight:600}.no{color:var(--mute)}.note{color:var(--mute)}"
	"figure{margin:0 0 8px;background:var(--card);border:1px solid var(--line);border-radius:10px;padding:12px}"
	"figcaption{color:var(--mute);font-size:13px;margin-top:4px}"
	"svg.chart{width:100%;max-width:880px;height:auto;display:block;margin:0 auto}"
	"svg .plot{fill:#fff;stroke:#cbd5e1}svg .grid{stroke:#eef2f7}svg .band{stroke:#94a3b8;stroke-dasharray:4 3}"
	"svg .tick{font-size:11px;fill:#64748b}svg .axis{font-size:13px;fill:#334155}"
	"svg .point{font-size:12px;fill:#0f172a;paint-order:stroke;stroke:#fff;stroke-width:3px}"
	"svg .series{fill:none;stroke-width:2;stroke-linejoin:round}"
	"svg .spread{fill:none;stroke-width:2;opacity:.55}"
	".legend{list-style:none;padding:0;margin:6px 0 0;display:flex;flex-wrap:wrap;gap:4px 16px;font-size:13px}"
	".method{background:var(--card);border:1px solid var(--line);border-radius:10px;padding:14px;margin:0 0 14px}"
	".method .meta{color:var(--mute);font-size:13px;margin:0 0 10px}"
	".imgs{display:grid;grid-template-columns:repeat(auto-fit,minmax(240px,1fr));gap:10px}"
	".imgs figure{padding:6px;margin:0}.imgs img{width:100%;height:auto;display:block;image-rendering:pixelated;"
	"background:#e2e8f0}"
	"footer{margin-top:40px;color:var(--mute);font-size:13px}"
	".warnings{background:#fef3c7;border:1px solid #f59e0b;border-radius:10px;padding:4px 16px;margin:0 0 16px}"
	".warnings h2{margin:8px 0 4px;border:0;font-size:17px}.warnings li{margin:4px 0}.warnings .todo{color:#78350f}"
	".verdict{background:#ecfdf5;border:1px solid #10b981;border-radius:10px;padding:4px 16px;margin:0 0 16px}"
	".verdict h2{margin:8px 0 4px;border:0;font-size:17px}.verdict .headline{font-size:17px;font-weight:600;margin:4px 0}"
	".verdict li{margin:2px 0}.verdict .note{margin:6px 0}";

static void card(FILE *o, const char *key, const char *value, const char *detail)
{
	fputs("<div class=\"card\"><div class=\"k\">", o);
	esc(o, key);
	fputs("</div><div class=\"v\">", o);
	esc(o, value);
	fputs("</div>", o);
	if (detail && *detail) {
		fputs("<div class=\"d\">", o);
		esc(o, detail);
		fputs("</div>", o);
	}
	fputs("</div>\n", o);
}

static void summary_cards(FILE *o, const struct aa_job_result *r)
{
	char v[160], d[1200];
	snprintf(d, sizeof d, "%s%s%llu triangles%s%s", r->scene_file, *r->scene_file ? " \xc2\xb7 " : "",
		 (unsigned long long)r->scene_triangles, " \xc2\xb7 camera path ", r->spec.path);
	card(o, "Scene", *r->scene_name ? r->scene_name : r->spec.scene, d);
	snprintf(v, sizeof v, "%d \xc3\x97 %d", r->spec.width, r->spec.height);
	snprintf(d, sizeof d, "%d frame%s from frame %d", r->spec.frames, r->spec.frames == 1 ? "" : "s",
		 r->spec.first_frame);
	card(o, "Size", v, d);

	const struct aa_reference_result *ref = &r->reference;
	bool identical;
	const double conv = aa_reference_convergence_psnr(ref, &identical);
	double *gpu = malloc((size_t)(ref->frame_count > 0 ? ref->frame_count : 1) * sizeof *gpu);
	double gpu_median = NAN;
	if (gpu && ref->frames) {
		for (int i = 0; i < ref->frame_count; i++)
			gpu[i] = ref->frames[i].gpu_ms;
		gpu_median = aa_percentile(gpu, ref->frame_count, 50);
	}
	free(gpu);
	if (ref->auto_samples) { /* the range of N the frames reached */
		int lo = 0, hi = 0;
		for (int i = 0; ref->frames && i < ref->frame_count; i++) {
			lo = i == 0 || ref->frames[i].samples < lo ? ref->frames[i].samples : lo;
			hi = ref->frames[i].samples > hi ? ref->frames[i].samples : hi;
		}
		if (lo == hi)
			snprintf(v, sizeof v, "auto: %d samples", hi);
		else
			snprintf(v, sizeof v, "auto: %d-%d samples", lo, hi);
	} else {
		snprintf(v, sizeof v, "%d samples", ref->samples);
	}
	if (ref->cache.used) { /* "64 samples, from the cache: 30 of 30 frames" */
		const size_t len = strlen(v);
		snprintf(v + len, sizeof v - len, ", from the cache: %d of %d frames", ref->cache.hits, ref->frame_count);
	}
	int n = snprintf(d, sizeof d, "%s \xc2\xb7 convergence PSNR ", *ref->pattern ? ref->pattern : "reference");
	if (identical)
		n += snprintf(d + n, sizeof d - (size_t)n, "identical");
	else if (isfinite(conv))
		n += snprintf(d + n, sizeof d - (size_t)n, "%.1f dB", conv);
	else
		n += snprintf(d + n, sizeof d - (size_t)n, "n/a");
	if (isfinite(gpu_median))
		n += snprintf(d + n, sizeof d - (size_t)n, " \xc2\xb7 %.1f ms/frame", gpu_median);
	snprintf(d + n, sizeof d - (size_t)n, " \xc2\xb7 %.1f MiB", (double)ref->memory_bytes / 1048576.0);
	card(o, "Reference", v, d);

	snprintf(d, sizeof d, "%s%s%s", r->driver_info, *r->driver_info ? " \xc2\xb7 " : "",
		 isfinite(r->timestamp_period_ns) ? "" : "no timestamps");
	if (isfinite(r->timestamp_period_ns))
		snprintf(d + strlen(d), sizeof d - strlen(d), "timestamp period %g ns", r->timestamp_period_ns);
	card(o, "Device", *r->device_name ? r->device_name : "unknown", d);
	if (r->spec.label_count > 0) { /* the run's labels: which commit, branch, build, machine */
		size_t used = 0;
		d[0] = '\0';
		for (int i = 0; i < r->spec.label_count && i < AA_MAX_LABELS && used < sizeof d; i++)
			used += (size_t)snprintf(d + used, sizeof d - used, "%s%s=%s", i ? " \xc2\xb7 " : "",
						 r->spec.labels[i].key, r->spec.labels[i].value);
		const char *commit = aa_job_label(&r->spec, "commit");
		card(o, "Labels", commit ? commit : r->spec.labels[0].value, d);
	}
	snprintf(v, sizeof v, "%d", r->method_count);
	d[0] = '\0';
	if (isfinite(r->wall_seconds))
		snprintf(d, sizeof d, "%.1f s wall time%s%s", r->wall_seconds, *r->started_at ? ", started " : "",
			 r->started_at);
	card(o, "Methods", v, d);
}

/* The verdict's word for method i: "front", "beaten by smaa", "not ranked" (results.json verdict.methods). */
static void put_place(FILE *o, const json_t *verdict, int i)
{
	const json_t *m = json_array_get(json_object_get(verdict, "methods"), (size_t)i);
	const json_t *by = json_object_get(m, "beaten_by");
	if (by) {
		fputs("beaten by ", o);
		esc(o, json_string_value(json_object_get(by, "method")));
	} else {
		esc(o, json_string_value(json_object_get(m, "place")) ? json_string_value(json_object_get(m, "place")) : "-");
	}
}

static void cost_table(FILE *o, const struct aa_job_result *r, const struct aa_method_summary *sum,
		       const json_t *verdict)
{
	fputs("<table>\n<tr><th>Method</th><th title=\"the verdict: on the cost-quality front, beaten by another "
	      "method, or not ranked (too few timed renders)\">Verdict</th><th>Path taken</th>"
	      "<th title=\"how cut-out (alpha-tested) materials were tested: per-pixel, per-sample or "
	      "alpha-to-coverage\">Alpha test</th><th class=\"n\">GPU ms/frame<br>median</th>"
	      "<th class=\"n\">GPU ms<br>p10&ndash;p90</th><th class=\"n\">GPU ms<br>min</th>"
	      "<th class=\"n\" title=\"timed renders: frames x repeat\">n</th>"
	      "<th class=\"n\">CPU ms<br>median</th><th class=\"n\">Memory<br>MiB</th>"
	      "<th class=\"n\">PSNR dB<br>mean</th><th class=\"n\">PSNR dB<br>worst frame</th><th class=\"n\">SSIM<br>mean</th>"
	      "<th class=\"n\" title=\"perceived difference when flipping between method and reference, 0 = none\">"
	      "FLIP<br>mean</th>"
	      "<th class=\"n\" title=\"mean |change between frames - the reference's change|, 8-bit levels\">"
	      "Flicker<br>mean</th></tr>\n",
	      o);
	for (int i = 0; i < r->method_count; i++) {
		const struct aa_method_summary *s = &sum[i];
		bool worst_identical = false;
		for (int f = 0; f < r->methods[i].frame_count; f++)
			if (r->methods[i].frames[f].frame == s->worst_frame)
				worst_identical = r->methods[i].frames[f].metrics.identical;
		fprintf(o, "<tr><td><span class=\"swatch\" style=\"background:%s\"></span>", color(i));
		esc(o, r->methods[i].label);
		fputs("</td><td>", o);
		put_place(o, verdict, i);
		fputs("</td><td>", o);
		esc(o, r->methods[i].path_taken);
		fputs("</td><td>", o);
		if (r->methods[i].method)
			esc(o, aa_alpha_rule_name(aa_method_alpha_rule(r->methods[i].method, &r->methods[i].params)));
		fputs("</td><td class=\"n\">", o);
		put_num(o, s->gpu_ms_median, 2);
		fputs("</td><td class=\"n\">", o);
		if (s->gpu_ms.n < AA_MIN_TIMED_RENDERS) { /* one value is no spread */
			fprintf(o, "n=%d: not ranked", s->gpu_ms.n);
		} else {
			put_num(o, s->gpu_ms.p10, 2);
			fputs("&ndash;", o);
			put_num(o, s->gpu_ms.p90, 2);
		}
		fputs("</td><td class=\"n\">", o);
		put_num(o, s->gpu_ms.min, 2);
		fprintf(o, "</td><td class=\"n\">%d</td><td class=\"n\">", s->gpu_ms.n);
		put_num(o, s->cpu_ms_median, 2);
		fputs("</td><td class=\"n\">", o);
		put_num(o, (double)r->methods[i].memory_bytes / 1048576.0, 1);
		fputs("</td><td class=\"n\">", o);
		put_psnr(o, s->psnr_mean, s->psnr_identical);
		fputs("</td><td class=\"n\">", o);
		put_psnr(o, s->worst_psnr, worst_identical);
		fputs("</td><td class=\"n\">", o);
		put_num(o, s->ssim_mean, 4);
		fputs("</td><td class=\"n\">", o);
		put_num(o, s->flip_mean, 4);
		fputs("</td><td class=\"n\">", o);
		put_num(o, s->flicker_mean, 3);
		fputs("</td></tr>\n", o);
	}
	fputs("</table>\n", o);
}

static void plan_table(FILE *o, const struct aa_job_result *r)
{
	if (r->plan_count == 0) {
		fputs("<p class=\"note\">The result lists no frame plan.</p>\n", o);
		return;
	}
	fputs("<table>\n<tr><th>Pass</th><th>Ran</th><th>Why</th></tr>\n", o);
	for (int i = 0; i < r->plan_count && i < AA_MAX_PASSES; i++) {
		fputs("<tr><td>", o);
		esc(o, r->plan[i].pass);
		fputs(r->plan[i].ran ? "</td><td>yes</td><td>" : "</td><td class=\"no\">no</td><td>", o);
		esc(o, r->plan[i].reason);
		fputs("</td></tr>\n", o);
	}
	fputs("</table>\n", o);
}

static void method_sections(FILE *o, const struct aa_job_result *r)
{
	for (int i = 0; i < r->method_count; i++) {
		const struct aa_method_result *m = &r->methods[i];
		fputs("<div class=\"method\"><h3>", o);
		fprintf(o, "<span class=\"swatch\" style=\"background:%s\"></span>", color(i));
		esc(o, m->label);
		fputs("</h3>\n<p class=\"meta\">", o);
		esc(o, *m->path_taken ? m->path_taken : "path not reported");
		/* GPU time of each of the method's passes over every timed render: median (p10-p90, n), from the
		 * first frame's pass list */
		for (int k = 0; m->frame_count > 0 && k < m->frames[0].pass_count && k < AA_MAX_PASSES; k++) {
			struct aa_timing_stats t;
			aa_pass_timing_stats(m, m->frames[0].passes[k].name, &t);
			fputs(k ? ", " : " \xc2\xb7 passes: ", o);
			esc(o, m->frames[0].passes[k].name);
			fputc(' ', o);
			put_num(o, t.median, 2);
			fputs(" ms (", o);
			put_num(o, t.p10, 2);
			fputs("&ndash;", o);
			put_num(o, t.p90, 2);
			fprintf(o, ", n %d)", t.n);
		}
		for (int k = 0; k < m->memory_count && k < AA_MAX_MEMORY_ITEMS; k++) {
			fputs(k ? ", " : " \xc2\xb7 memory: ", o);
			esc(o, m->memory[k].name);
			fprintf(o, " %.2f MiB", (double)m->memory[k].bytes / 1048576.0);
		}
		fputs("</p>\n", o);
		fputs("</div>\n", o); /* the images are in the viewer (report_viewer.c) */
	}
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
	esc(o, title);
	fprintf(o, "</title>\n<style>%s</style>\n</head>\n<body><main>\n<h1>", aa_report_style);
	esc(o, title);
	fputs("</h1>\n<p class=\"sub\">aalab render-and-compare report", o);
	if (*view.started_at) {
		fputs(" \xc2\xb7 ", o);
		esc(o, view.started_at);
	}
	fputs("</p>\n", o);
	/* first what a reader wants to know, as results.json says it: the verdict and what qualifies it */
	json_t *verdict = aa_verdict_json(&view), *warnings = verdict ? aa_results_warnings_json(&view, verdict) : NULL;
	aa_report_write_verdict(o, verdict, warnings);
	fputs("<div class=\"cards\">\n", o);
	summary_cards(o, &view);
	fputs("</div>\n<h2 id=\"cost-chart\">GPU time against PSNR</h2>\n", o);
	chart_cost_accuracy(o, &view, sum, verdict);
	fputs("<h2 id=\"cost\">Cost and accuracy</h2>\n", o);
	cost_table(o, &view, sum, verdict);
	json_decref(verdict);
	json_decref(warnings);
	fputs("<h2 id=\"images\">Images</h2>\n", o);
	if (aa_report_write_viewer(o, &view, dir, err)) {
		fclose(o);
		free(buf);
		return -1;
	}
	fputs("<h2 id=\"thresholds\">Error-threshold curves</h2>\n", o);
	chart_thresholds(o, &view);
	if (view.spec.frames > 1) {
		fputs("<h2 id=\"per-frame\">PSNR per frame</h2>\n", o);
		chart_psnr_per_frame(o, &view);
	}
	fputs("<h2 id=\"plan\">Frame plan</h2>\n<p class=\"note\">Only the passes the scene and the methods need run; "
	      "each row says why.</p>\n", o);
	plan_table(o, &view);
	fputs("<h2 id=\"methods\">Methods</h2>\n", o);
	method_sections(o, &view);
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
