/* report.html's cards and tables: the run at a glance (scene, size, reference, device, labels), cost and
 * accuracy per method, the frame plan, and each method's passes and memory. */
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

static void card(FILE *o, const char *key, const char *value, const char *detail)
{
	fputs("<div class=\"card\"><div class=\"k\">", o);
	aa_report_esc(o, key);
	fputs("</div><div class=\"v\">", o);
	aa_report_esc(o, value);
	fputs("</div>", o);
	if (detail && *detail) {
		fputs("<div class=\"d\">", o);
		aa_report_esc(o, detail);
		fputs("</div>", o);
	}
	fputs("</div>\n", o);
}

void aa_report_summary_cards(FILE *o, const struct aa_job_result *r)
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
		aa_report_esc(o, json_string_value(json_object_get(by, "method")));
	} else {
		aa_report_esc(o, json_string_value(json_object_get(m, "place")) ? json_string_value(json_object_get(m, "place")) : "-");
	}
}

void aa_report_cost_table(FILE *o, const struct aa_job_result *r, const struct aa_method_summary *sum,
		       const json_t *verdict)
{
	/* every column a number or a word; the long texts (path taken, alpha test) go in a detail row under
	 * each method, so that the table fits a 1280 px window */
	fputs("<table class=\"cost\">\n<tr><th title=\"the method's label in the job; its path and alpha test in the row "
	      "under it\">Method</th><th title=\"the verdict: on the cost-quality front, beaten by another "
	      "method, or not ranked (too few timed renders)\">Verdict</th>"
	      "<th class=\"n\" title=\"median GPU time of a frame over every timed render\">GPU ms<br>median</th>"
	      "<th class=\"n\" title=\"10th to 90th percentile of the GPU time over every timed render\">GPU ms<br>p10&ndash;p90</th>"
	      "<th class=\"n\" title=\"the fastest timed render\">GPU ms<br>min</th>"
	      "<th class=\"n\" title=\"timed renders: frames x repeat\">n</th>"
	      "<th class=\"n\" title=\"median wall time of a frame: record, submit and wait\">CPU ms<br>median</th>"
	      "<th class=\"n\" title=\"memory the method allocates (item by item under Memory)\">Memory<br>MiB</th>"
	      "<th class=\"n\" title=\"peak signal-to-noise ratio against the reference; higher is closer\">PSNR dB<br>mean</th>"
	      "<th class=\"n\" title=\"PSNR of the method's worst frame, and which frame\">PSNR dB<br>worst</th>"
	      "<th class=\"n\" title=\"structural similarity, 1 = same\">SSIM<br>mean</th>"
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
		fprintf(o, "<tr><td><span class=\"swatch\" style=\"background:%s\"></span>", aa_report_color(i));
		aa_report_esc(o, r->methods[i].label);
		fputs("</td><td>", o);
		put_place(o, verdict, i);
		fputs("</td><td class=\"n\">", o);
		aa_report_put_num(o, s->gpu_ms_median, 2);
		fputs("</td><td class=\"n\">", o);
		if (s->gpu_ms.n < AA_MIN_TIMED_RENDERS) { /* one value is no spread */
			fprintf(o, "n=%d: not ranked", s->gpu_ms.n);
		} else {
			aa_report_put_num(o, s->gpu_ms.p10, 2);
			fputs("&ndash;", o);
			aa_report_put_num(o, s->gpu_ms.p90, 2);
		}
		fputs("</td><td class=\"n\">", o);
		aa_report_put_num(o, s->gpu_ms.min, 2);
		fprintf(o, "</td><td class=\"n\">%d</td><td class=\"n\">", s->gpu_ms.n);
		aa_report_put_num(o, s->cpu_ms_median, 2);
		fputs("</td><td class=\"n\">", o);
		aa_report_put_num(o, (double)r->methods[i].memory_bytes / 1048576.0, 1);
		fputs("</td><td class=\"n\">", o);
		aa_report_put_psnr(o, s->psnr_mean, s->psnr_identical);
		fputs("</td><td class=\"n\">", o);
		aa_report_put_psnr(o, s->worst_psnr, worst_identical);
		fputs("</td><td class=\"n\">", o);
		aa_report_put_num(o, s->ssim_mean, 4);
		fputs("</td><td class=\"n\">", o);
		aa_report_put_num(o, s->flip_mean, 4);
		fputs("</td><td class=\"n\">", o);
		aa_report_put_num(o, s->flicker_mean, 3);
		fputs("</td></tr>\n<tr class=\"detail\"><td colspan=\"13\">", o);
		if (*r->methods[i].path_taken) {
			fputs("<b>path taken</b> ", o);
			aa_report_esc(o, r->methods[i].path_taken);
		}
		if (r->methods[i].method) {
			fputs(" \xc2\xb7 <b>alpha test</b> ", o);
			aa_report_esc(o, aa_alpha_rule_name(aa_method_alpha_rule(r->methods[i].method, &r->methods[i].params)));
		}
		fputs("</td></tr>\n", o);
	}
	fputs("</table>\n", o);
}

void aa_report_plan_table(FILE *o, const struct aa_job_result *r)
{
	if (r->plan_count == 0) {
		fputs("<p class=\"note\">The result lists no frame plan.</p>\n", o);
		return;
	}
	fputs("<table>\n<tr><th>Pass</th><th>Ran</th><th>Why</th></tr>\n", o);
	for (int i = 0; i < r->plan_count && i < AA_MAX_PASSES; i++) {
		fputs("<tr><td>", o);
		aa_report_esc(o, r->plan[i].pass);
		fputs(r->plan[i].ran ? "</td><td>yes</td><td>" : "</td><td class=\"no\">no</td><td>", o);
		aa_report_esc(o, r->plan[i].reason);
		fputs("</td></tr>\n", o);
	}
	fputs("</table>\n", o);
}

/* What each method allocates, item by item (the GPU time by pass is a chart: report_charts.c). */
void aa_report_method_sections(FILE *o, const struct aa_job_result *r)
{
	fputs("<table class=\"memory\">\n<tr><th>Method</th><th>Memory by item</th></tr>\n", o);
	for (int i = 0; i < r->method_count; i++) {
		const struct aa_method_result *m = &r->methods[i];
		fprintf(o, "<tr><td><span class=\"swatch\" style=\"background:%s\"></span>", aa_report_color(i));
		aa_report_esc(o, m->label);
		fputs("</td><td>", o);
		for (int k = 0; k < m->memory_count && k < AA_MAX_MEMORY_ITEMS; k++) {
			fputs(k ? ", " : "", o);
			aa_report_esc(o, m->memory[k].name);
			fprintf(o, " %.2f MiB", (double)m->memory[k].bytes / 1048576.0);
		}
		fputs("</td></tr>\n", o);
	}
	fputs("</table>\n", o);
}
