/* The outputs of a run: results.json with each case's report.html, and for a suite the report whose
 * table runs across cases and links each case's own report. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "report/report.h"
#include "results/front.h"
#include "results/warnings.h"
#include "run/job_spec.h"

int aa_suite_results_write(const struct aa_suite_result *r, const char *dir, struct aa_error *err)
{
	if (!r->spec.is_suite) {
		if (r->case_count < 1)
			return aa_error_set(err, AA_ERR_INTERNAL, "", "no results to write");
		json_t *root = aa_suite_results_to_json(r);
		if (!root)
			return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory building results.json");
		int rc = aa_results_write_json_doc(root, dir, "results.json", err);
		json_decref(root);
		return rc || aa_report_write_html(r->cases[0], dir, err) ? -1 : 0;
	}
	for (int i = 0; i < r->case_count; i++) {
		char rel[600], path[4200];
		aa_case_relpath(&r->spec, i, rel, sizeof rel);
		snprintf(path, sizeof path, "%s/%s/", dir, rel);
		/* the case's directory exists once it has images; without images it may not yet */
		for (char *p = path + strlen(dir) + 1; *p; p++)
			if (*p == '/') {
				*p = '\0';
				mkdir(path, 0755);
				*p = '/';
			}
		path[strlen(path) - 1] = '\0';
		if (aa_report_write_html(r->cases[i], path, err) < 0)
			return -1;
	}
	json_t *root = aa_suite_results_to_json(r);
	if (!root)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory building results.json");
	int rc = aa_results_write_json_doc(root, dir, "results.json", err);
	json_decref(root);
	if (rc == 0)
		rc = aa_suite_report_write_html(r, dir, err);
	return rc;
}

static void cell_num(FILE *o, double v, int decimals)
{
	if (isfinite(v))
		fprintf(o, "<td class=\"n\">%.*f</td>", decimals, v);
	else
		fputs("<td class=\"n\">&mdash;</td>", o);
}

/* Mean FLIP over the frames that have one. */
static double flip_mean(const struct aa_method_result *m)
{
	double sum = 0;
	int n = 0;
	for (int i = 0; m->frames && i < m->frame_count; i++)
		if (isfinite(m->frames[i].metrics.flip_mean)) {
			sum += m->frames[i].metrics.flip_mean;
			n++;
		}
	return n ? sum / n : NAN;
}

/* Cases x methods: each cell the method's mean PSNR over `none` in its case, in dB, blue when better and
 * orange when worse (stronger with size), ringed when on the case's front; columns are the first case's
 * methods. The numbers at a glance, before the full table. */
static void psnr_matrix(FILE *o, const struct aa_suite_result *r)
{
	const struct aa_job_result *first = r->case_count > 0 ? r->cases[0] : NULL;
	if (!first || first->method_count < 1)
		return;
	double big = 0;
	for (int pass = 0; pass < 2; pass++) {
		if (pass == 1) {
			fputs("<h2 id=\"matrix\">PSNR over none, dB</h2>\n<p class=\"note\">Each cell: the method's mean PSNR "
			      "minus that of <code>none</code> in the same case; blue is better, orange worse; a ring marks a "
			      "method on its case's front. A case links its report.</p>\n<div class=\"matrix-wrap\"><table "
			      "class=\"matrix\">\n<tr><th>case</th>", o);
			for (int i = 0; i < first->method_count && i < AA_MAX_METHODS; i++) {
				fputs("<th class=\"m\"><span>", o);
				aa_report_esc(o, first->methods[i].label);
				fputs("</span></th>", o);
			}
			fputs("</tr>\n", o);
		}
		for (int c = 0; c < r->case_count; c++) {
			const struct aa_job_result *cr = r->cases[c];
			double none = NAN;
			for (int i = 0; i < cr->method_count && i < AA_MAX_METHODS; i++)
				if (!strcmp(cr->methods[i].label, "none")) {
					struct aa_method_summary s;
					aa_method_summarize(&cr->methods[i], &s);
					none = s.psnr_identical ? NAN : s.psnr_mean;
				}
			json_t *v = pass ? aa_verdict_json(cr) : NULL;
			if (pass) {
				char id[512], rel[600];
				aa_case_id(&r->spec, c, id, sizeof id);
				aa_case_relpath(&r->spec, c, rel, sizeof rel);
				fputs("<tr><th class=\"case\"><a href=\"", o);
				aa_report_esc(o, rel);
				fputs("/report.html\">", o);
				aa_report_esc(o, id);
				fputs("</a></th>", o);
			}
			for (int k = 0; k < first->method_count && k < AA_MAX_METHODS; k++) {
				int i = -1;
				for (int j = 0; j < cr->method_count && j < AA_MAX_METHODS; j++)
					if (!strcmp(cr->methods[j].label, first->methods[k].label))
						i = j;
				struct aa_method_summary s = { 0 };
				if (i >= 0)
					aa_method_summarize(&cr->methods[i], &s);
				const double d = i >= 0 && !s.psnr_identical ? s.psnr_mean - none : NAN;
				if (!pass) {
					if (isfinite(d))
						big = fmax(big, fabs(d));
					continue;
				}
				bool front = false;
				size_t f;
				json_t *l;
				json_array_foreach(json_object_get(v, "front"), f, l)
					front = front || (i >= 0 && !strcmp(json_string_value(l), cr->methods[i].label));
				const double a = isfinite(d) && big > 0 ? fabs(d) / big : 0;
				if (i >= 0 && s.psnr_identical)
					fprintf(o, "<td class=\"n%s\" style=\"background:hsl(210 70%% 55%%)\">ident.</td>", front ? " front" : "");
				else if (isfinite(d))
					fprintf(o, "<td class=\"n%s\" style=\"background:hsl(%d %d%% %.0f%%)\">%+.1f</td>", front ? " front" : "",
						d >= 0 ? 210 : 28, d >= 0 ? 70 : 90, 96 - 40 * a, d);
				else
					fputs("<td class=\"n\">&ndash;</td>", o);
			}
			if (pass)
				fputs("</tr>\n", o);
			json_decref(v);
		}
	}
	fputs("</table></div>\n", o);
}

int aa_suite_report_write_html(const struct aa_suite_result *r, const char *dir, struct aa_error *err)
{
	char *buf = NULL;
	size_t size = 0;
	FILE *o = open_memstream(&buf, &size);
	if (!o)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory writing report.html");
	const char *title = r->spec.name[0] ? r->spec.name : r->spec.suite[0] ? r->spec.suite : "suite";
	fputs("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
	      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>aalab: ", o);
	aa_report_esc(o, title);
	fprintf(o, "</title>\n<style>%s</style>\n</head>\n<body><main>\n<h1>", aa_report_style);
	aa_report_esc(o, title);
	fprintf(o, "</h1>\n<p class=\"sub\">aalab suite report \xc2\xb7 %d case%s \xc2\xb7 ", r->case_count,
		r->case_count == 1 ? "" : "s");
	aa_report_esc(o, r->started_at);
	fprintf(o, " \xc2\xb7 %.1f s</p>\n<div class=\"cards\">\n", r->wall_seconds);
	fputs("<div class=\"card\"><div class=\"k\">Suite</div><div class=\"v\">", o);
	aa_report_esc(o, r->spec.suite[0] ? r->spec.suite : "(none)");
	fputs("</div><div class=\"d\">", o);
	char hash[80];
	aa_job_hash(&r->spec, hash, sizeof hash);
	aa_report_esc(o, hash);
	fputs("</div></div>\n<div class=\"card\"><div class=\"k\">Labels</div><div class=\"d\">", o);
	for (int i = 0; i < r->spec.label_count; i++) {
		fputs(i ? "<br>" : "", o);
		aa_report_esc(o, r->spec.labels[i].key);
		fputs("=", o);
		aa_report_esc(o, r->spec.labels[i].value);
	}
	if (r->spec.label_count == 0)
		fputs("none", o);
	fputs("</div></div>\n", o);
	if (r->case_count > 0) {
		fputs("<div class=\"card\"><div class=\"k\">Device</div><div class=\"v\">", o);
		aa_report_esc(o, r->cases[0]->device_name);
		fputs("</div><div class=\"d\">", o);
		aa_report_esc(o, r->cases[0]->driver_info);
		fputs("</div></div>\n", o);
	}
	if (r->spec.timing_auto)
		fprintf(o, "<div class=\"card\"><div class=\"k\">Reference</div><div class=\"v\">%d samples</div>"
			"<div class=\"d\">timing.repeat auto: 5 timed renders per method at least</div></div>\n</div>\n",
			r->spec.reference_samples);
	else
		fprintf(o, "<div class=\"card\"><div class=\"k\">Reference</div><div class=\"v\">%d samples</div>"
			"<div class=\"d\">timing.repeat %d</div></div>\n</div>\n", r->spec.reference_samples,
			r->spec.timing_repeat);
	/* each case's verdict and warnings, as its results.json has them */
	fputs("<section id=\"verdict\" class=\"verdict\"><h2>Verdict per case</h2><ul>\n", o);
	int warned = 0;
	for (int c = 0; c < r->case_count; c++) {
		char id[512], rel[600];
		aa_case_id(&r->spec, c, id, sizeof id);
		aa_case_relpath(&r->spec, c, rel, sizeof rel);
		json_t *v = aa_verdict_json(r->cases[c]), *w = v ? aa_results_warnings_json(r->cases[c], v) : NULL;
		fputs("<li><a href=\"", o);
		aa_report_esc(o, rel);
		fputs("/report.html\">", o);
		aa_report_esc(o, id);
		fputs("</a>: ", o);
		aa_report_esc(o, json_string_value(json_object_get(v, "headline")));
		fputs("</li>\n", o);
		warned += (int)json_array_size(w);
		json_decref(v);
		json_decref(w);
	}
	fputs("</ul></section>\n", o);
	if (warned)
		fprintf(o, "<p class=\"note\">%d warning%s across the cases: each case's report lists its own, with what to "
			   "do.</p>\n", warned, warned == 1 ? "" : "s");
	psnr_matrix(o, r);
	fputs("<h2 id=\"summary\">Summary across cases</h2>\n<p class=\"note\">GPU ms: the median over every timed "
	      "render of the case (frames \xc3\x97 timing.repeat), with the 10th to 90th percentile. PSNR from the mean "
	      "MSE over frames. Each case links its own report.</p>\n<table>\n<tr><th>case</th><th>method</th>"
	      "<th class=\"n\">GPU ms</th><th class=\"n\">p10&ndash;p90</th><th class=\"n\">MB</th>"
	      "<th class=\"n\">PSNR dB</th><th class=\"n\">SSIM</th><th class=\"n\">FLIP</th>"
	      "<th class=\"n\">flicker</th></tr>\n", o);
	for (int c = 0; c < r->case_count; c++) {
		const struct aa_job_result *cr = r->cases[c];
		char id[512], rel[600];
		aa_case_id(&r->spec, c, id, sizeof id);
		aa_case_relpath(&r->spec, c, rel, sizeof rel);
		for (int i = 0; i < cr->method_count && i < AA_MAX_METHODS; i++) {
			const struct aa_method_result *m = &cr->methods[i];
			struct aa_method_summary s;
			aa_method_summarize(m, &s);
			fputs("<tr>", o);
			if (i == 0) {
				fprintf(o, "<td rowspan=\"%d\"><a href=\"", cr->method_count);
				aa_report_esc(o, rel);
				fputs("/report.html\">", o);
				aa_report_esc(o, id);
				fprintf(o, "</a><div class=\"note\">%d frame%s</div></td>", cr->spec.frames,
					cr->spec.frames == 1 ? "" : "s");
			}
			fputs("<td>", o);
			aa_report_esc(o, m->label);
			fputs("</td>", o);
			cell_num(o, s.gpu_ms.median, 2);
			fprintf(o, "<td class=\"n\">%.2f&ndash;%.2f</td>", s.gpu_ms.p10, s.gpu_ms.p90);
			cell_num(o, (double)m->memory_bytes / 1048576.0, 2);
			if (s.psnr_identical)
				fputs("<td class=\"n\"><span class=\"ident\">identical</span></td>", o);
			else
				cell_num(o, s.psnr_mean, 2);
			cell_num(o, s.ssim_mean, 4);
			cell_num(o, flip_mean(m), 4);
			cell_num(o, s.flicker_mean, 3);
			fputs("</tr>\n", o);
		}
	}
	fputs("</table>\n<footer>Every number on this page comes from results.json in the same directory.</footer>\n"
	      "</main></body>\n</html>\n", o);
	if (fclose(o) != 0 || !buf) {
		free(buf);
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory writing report.html");
	}
	int rc = aa_results_write_file_atomic(dir, "report.html", buf, size, err);
	free(buf);
	return rc;
}

