/* The comparison of two runs for people and CI servers: a text table, JUnit XML (one test case per case x
 * method x gate, as Jenkins and GitLab read it) and a markdown summary for a merge-request comment.
 * Everything is read from the comparison JSON, so the three say exactly what --json says. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "compare/compare.h"

static double number(json_t *o, const char *key)
{
	json_t *v = json_object_get(o, key);
	return json_is_number(v) ? json_number_value(v) : NAN;
}

static const char *string(json_t *o, const char *key)
{
	const char *s = json_string_value(json_object_get(o, key));
	return s ? s : "";
}

/* "commit=A, branch=main", or the source when there are no labels. */
static void run_name(json_t *run, char *out, size_t size)
{
	const char *key;
	json_t *v;
	size_t used = 0;
	out[0] = '\0';
	json_object_foreach(json_object_get(run, "labels"), key, v)
		if (used < size)
			used += (size_t)snprintf(out + used, size - used, "%s%s=%s", used ? ", " : "", key,
						 json_string_value(v) ? json_string_value(v) : "");
	if (!used)
		snprintf(out, size, "%s", string(run, "source"));
}

/* NEW's value and its change, "18.79 -0.08" ("identical" for an infinite PSNR); a '!' marks a change
 * that tripped a gate. */
static void quality_cell(json_t *q, int decimals, bool psnr, bool tripped, char *out, size_t size)
{
	double n = number(q, "new"), c = number(q, "change");
	char nt[32], ct[32];
	if (psnr && json_is_true(json_object_get(q, "new_identical")))
		snprintf(nt, sizeof nt, "identical");
	else if (isfinite(n))
		snprintf(nt, sizeof nt, "%.*f", decimals, n);
	else
		snprintf(nt, sizeof nt, "-");
	if (psnr && json_is_true(json_object_get(q, "base_identical")) && !json_is_true(json_object_get(q, "new_identical")))
		snprintf(ct, sizeof ct, "(was identical)");
	else if (isfinite(c))
		snprintf(ct, sizeof ct, "%+.*f", decimals, c);
	else
		ct[0] = '\0';
	snprintf(out, size, "%.31s %.31s%s", nt, ct, tripped ? "!" : "");
}

/* "1.04>1.43 +23% [+11,+28]": the medians, then the judged change of the p10 and its interval. */
static void cost_cell(json_t *c, bool tripped, char *out, size_t size)
{
	json_t *b = json_object_get(c, "base"), *n = json_object_get(c, "new"), *iv = json_object_get(c, "interval_pct");
	int written = snprintf(out, size, "%.2f>%.2f %+.0f%%", number(b, "median"), number(n, "median"),
			       number(c, "judged_pct"));
	if (json_is_number(json_array_get(iv, 0)) && written > 0 && (size_t)written < size)
		written += snprintf(out + written, size - (size_t)written, " [%+.0f,%+.0f]",
				    json_number_value(json_array_get(iv, 0)), json_number_value(json_array_get(iv, 1)));
	if (tripped && written > 0 && (size_t)written < size)
		snprintf(out + written, size - (size_t)written, "!");
}

/* Whether a gate on metric tripped for this method. */
static bool tripped_on(json_t *m, const char *metric)
{
	size_t i;
	json_t *g;
	json_array_foreach(json_object_get(m, "gates"), i, g)
		if (!strcmp(string(g, "metric"), metric) && !strcmp(string(g, "result"), "tripped"))
			return true;
	return false;
}

/* The cells of one method's row. */
struct row {
	char psnr[72], ssim[72], flip[72], flicker[72], gpu[96];
};

static void row_of(json_t *m, struct row *r)
{
	json_t *mt = json_object_get(m, "metrics");
	quality_cell(json_object_get(mt, "psnr"), 2, true, tripped_on(m, "psnr"), r->psnr, sizeof r->psnr);
	quality_cell(json_object_get(mt, "ssim"), 4, false, tripped_on(m, "ssim"), r->ssim, sizeof r->ssim);
	quality_cell(json_object_get(mt, "flip"), 4, false, tripped_on(m, "flip"), r->flip, sizeof r->flip);
	quality_cell(json_object_get(mt, "flicker"), 3, false, tripped_on(m, "flicker"), r->flicker, sizeof r->flicker);
	cost_cell(json_object_get(mt, "gpu_ms"), tripped_on(m, "gpu_ms"), r->gpu, sizeof r->gpu);
}

/* "was fxaa (paired by name): preset 12 -> 10, edge_threshold 0.166 -> 0.333", or "" when the label is
 * the same in both runs. */
static void pairing_note(json_t *m, char *out, size_t size)
{
	size_t used = 0, k;
	json_t *pc;
	out[0] = '\0';
	if (!strcmp(string(m, "label"), string(m, "base_label")))
		return;
	used = (size_t)snprintf(out, size, "was %s (paired by %s)", string(m, "base_label"), string(m, "paired_by"));
	json_array_foreach(json_object_get(m, "params_changed"), k, pc) {
		char *bv = json_dumps(json_object_get(pc, "base"), JSON_ENCODE_ANY | JSON_REAL_PRECISION(6));
		char *nv = json_dumps(json_object_get(pc, "new"), JSON_ENCODE_ANY | JSON_REAL_PRECISION(6));
		if (used < size)
			used += (size_t)snprintf(out + used, size - used, "%s %s %s -> %s", k ? "," : ":",
						 string(pc, "param"), bv ? bv : "?", nv ? nv : "?");
		free(bv);
		free(nv);
	}
}

void aa_compare_print_table(const json_t *cmp_const, FILE *out)
{
	json_t *cmp = (json_t *)cmp_const;
	char bn[512], nn[512];
	run_name(json_object_get(cmp, "base"), bn, sizeof bn);
	run_name(json_object_get(cmp, "new"), nn, sizeof nn);
	fprintf(out, "BASE %s (%s)\nNEW  %s (%s)\ngates:", string(json_object_get(cmp, "base"), "source"), bn,
		string(json_object_get(cmp, "new"), "source"), nn);
	size_t i, j;
	json_t *g, *c, *m;
	json_array_foreach(json_object_get(cmp, "gates"), i, g)
		fprintf(out, "%s %s", i ? "," : "", json_string_value(g));
	fprintf(out, "\nquality: NEW and its change; GPU ms: median BASE>NEW, then the judged change of the p10 (over the "
		"case's machine factor) and its %.0f%% interval; ! a tripped gate\n",
		100 * number(json_object_get(cmp, "cost_rule"), "interval_level"));
	json_array_foreach(json_object_get(cmp, "cases"), i, c) {
		fprintf(out, "\ncase %s", string(c, "id"));
		json_t *mf = json_object_get(json_object_get(c, "machine_factor"), "gpu_ms");
		if (isfinite(number(mf, "value")))
			fprintf(out, "  (machine factor x%.2f)", number(mf, "value"));
		json_t *fc = json_object_get(c, "frames_changed");
		if (fc)
			fprintf(out, "  (frames %lld -> %lld)", json_integer_value(json_object_get(fc, "base")),
				json_integer_value(json_object_get(fc, "new")));
		int width = 6;
		json_array_foreach(json_object_get(c, "methods"), j, m)
			if ((int)strlen(string(m, "label")) > width)
				width = (int)strlen(string(m, "label"));
		fprintf(out, "\n  %-*s  %-16s %-17s %-17s %-15s %-26s %s\n", width, "method", "PSNR dB", "SSIM", "FLIP",
			"flicker", "GPU ms", "MB");
		json_array_foreach(json_object_get(c, "methods"), j, m) {
			struct row r;
			char note[600];
			row_of(m, &r);
			fprintf(out, "  %-*s  %-16s %-17s %-17s %-15s %-26s %.2f\n", width, string(m, "label"), r.psnr, r.ssim,
				r.flip, r.flicker, r.gpu,
				number(json_object_get(json_object_get(m, "metrics"), "memory_bytes"), "new") / 1048576.0);
			pairing_note(m, note, sizeof note);
			if (note[0])
				fprintf(out, "  %-*s  %s\n", width, "", note);
		}
		json_t *u = json_object_get(c, "unpaired");
		json_array_foreach(json_object_get(u, "base"), j, m)
			fprintf(out, "  %s: only in BASE, not compared\n", json_string_value(m));
		json_array_foreach(json_object_get(u, "new"), j, m)
			fprintf(out, "  %s: only in NEW, not compared\n", json_string_value(m));
	}
	json_t *miss = json_object_get(cmp, "missing");
	json_array_foreach(json_object_get(miss, "new"), i, g)
		fprintf(out, "\ncase %s: only in BASE, not compared (--allow-missing)", json_string_value(g));
	json_array_foreach(json_object_get(miss, "base"), i, g)
		fprintf(out, "\ncase %s: only in NEW, not compared (--allow-missing)", json_string_value(g));
	json_t *counts = json_object_get(cmp, "counts");
	fprintf(out, "\n%s: %lld gates checked, %lld held, %lld tripped, %lld not judged\n",
		aa_compare_tripped(cmp) ? "TRIPPED" : "HELD", json_integer_value(json_object_get(counts, "gates")),
		json_integer_value(json_object_get(counts, "held")), json_integer_value(json_object_get(counts, "tripped")),
		json_integer_value(json_object_get(counts, "unknown")));
	json_array_foreach(json_object_get(cmp, "tripped"), i, g)
		fprintf(out, "  tripped %s in %s, %s: %s\n", string(g, "gate"), string(g, "case"), string(g, "method"),
			string(g, "message"));
}

/* ------------------------------------------------------------------------------------------ JUnit */

static void xml_text(FILE *o, const char *s)
{
	for (; *s; s++) {
		unsigned char ch = (unsigned char)*s;
		switch (ch) {
		case '&': fputs("&amp;", o); break;
		case '<': fputs("&lt;", o); break;
		case '>': fputs("&gt;", o); break;
		case '"': fputs("&quot;", o); break;
		case '\'': fputs("&apos;", o); break;
		default:
			/* XML 1.0 allows no control characters but tab, newline and carriage return */
			fputc(ch < 0x20 && ch != '\t' && ch != '\n' && ch != '\r' ? '?' : ch, o);
		}
	}
}

int aa_compare_write_junit(const json_t *cmp_const, FILE *o)
{
	json_t *cmp = (json_t *)cmp_const;
	json_t *counts = json_object_get(cmp, "counts");
	size_t i, j, k;
	json_t *c, *m, *g;
	fprintf(o, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"aalab compare\" tests=\"%lld\" "
		"failures=\"%lld\" errors=\"0\" skipped=\"%lld\" time=\"0\">\n",
		json_integer_value(json_object_get(counts, "gates")), json_integer_value(json_object_get(counts, "tripped")),
		json_integer_value(json_object_get(counts, "unknown")));
	json_array_foreach(json_object_get(cmp, "cases"), i, c) {
		int tests = 0, failures = 0, skipped = 0;
		json_array_foreach(json_object_get(c, "methods"), j, m)
			json_array_foreach(json_object_get(m, "gates"), k, g) {
				tests++;
				failures += !strcmp(string(g, "result"), "tripped");
				skipped += !strcmp(string(g, "result"), "unknown");
			}
		fputs("  <testsuite name=\"", o);
		xml_text(o, string(c, "id"));
		fprintf(o, "\" tests=\"%d\" failures=\"%d\" errors=\"0\" skipped=\"%d\" time=\"0\">\n", tests, failures,
			skipped);
		/* what was compared with what, for the reader of the CI page */
		fputs("    <properties>\n", o);
		const char *sides[2] = {"base", "new"};
		for (int s = 0; s < 2; s++) {
			json_t *run = json_object_get(cmp, sides[s]), *v;
			const char *key;
			fprintf(o, "      <property name=\"%s.source\" value=\"", sides[s]);
			xml_text(o, string(run, "source"));
			fputs("\"/>\n", o);
			json_object_foreach(json_object_get(run, "labels"), key, v) {
				fprintf(o, "      <property name=\"%s.label.", sides[s]);
				xml_text(o, key);
				fputs("\" value=\"", o);
				xml_text(o, json_string_value(v) ? json_string_value(v) : "");
				fputs("\"/>\n", o);
			}
		}
		fputs("    </properties>\n", o);
		json_array_foreach(json_object_get(c, "methods"), j, m) {
			json_array_foreach(json_object_get(m, "gates"), k, g) {
				const char *result = string(g, "result");
				fputs("    <testcase classname=\"", o);
				xml_text(o, string(c, "id"));
				fputs("\" name=\"", o);
				xml_text(o, string(m, "label"));
				fputs(": ", o);
				xml_text(o, string(g, "gate"));
				fputs("\" time=\"0\"", o);
				if (!strcmp(result, "held")) {
					fputs("/>\n", o);
					continue;
				}
				fputs(">\n      <", o);
				fputs(!strcmp(result, "tripped") ? "failure type=\"gate\"" : "skipped", o);
				fputs(" message=\"", o);
				xml_text(o, string(g, "message"));
				fputs("\">", o);
				xml_text(o, string(g, "message"));
				if (strcmp(string(m, "label"), string(m, "base_label"))) {
					fputs("\nBASE method: ", o);
					xml_text(o, string(m, "base_label"));
				}
				fprintf(o, "</%s>\n    </testcase>\n", !strcmp(result, "tripped") ? "failure" : "skipped");
			}
		}
		fputs("  </testsuite>\n", o);
	}
	fputs("</testsuites>\n", o);
	return ferror(o) ? -1 : 0;
}

/* ------------------------------------------------------------------------------------------ markdown */

/* Inside a code span nothing is unescaped, so only what would end the span or the table is changed. */
static void md_code(FILE *o, const char *s)
{
	fputc('`', o);
	for (; *s; s++)
		fputc(*s == '`' || *s == '|' || *s == '\n' ? ' ' : *s, o);
	fputc('`', o);
}

/* Table cells must not break the table: '|' and newlines are escaped or dropped. */
static void md_text(FILE *o, const char *s)
{
	for (; *s; s++) {
		if (*s == '|')
			fputs("\\|", o);
		else if (*s == '\n' || *s == '\r')
			fputc(' ', o);
		else if (*s == '<')
			fputs("&lt;", o);
		else
			fputc(*s, o);
	}
}

int aa_compare_write_markdown(const json_t *cmp_const, FILE *o)
{
	json_t *cmp = (json_t *)cmp_const;
	json_t *counts = json_object_get(cmp, "counts");
	bool tripped = aa_compare_tripped(cmp);
	char bn[512], nn[512];
	run_name(json_object_get(cmp, "base"), bn, sizeof bn);
	run_name(json_object_get(cmp, "new"), nn, sizeof nn);
	fprintf(o, "### aalab compare: %s\n\n", tripped ? "**FAILED**, a gate tripped" : "passed, every gate held");
	fputs("BASE ", o);
	md_code(o, bn);
	fputs(" \xe2\x86\x92 NEW ", o);
	md_code(o, nn);
	fprintf(o, ": %lld gates checked, %lld held, **%lld tripped**, %lld not judged.\n\n",
		json_integer_value(json_object_get(counts, "gates")), json_integer_value(json_object_get(counts, "held")),
		json_integer_value(json_object_get(counts, "tripped")), json_integer_value(json_object_get(counts, "unknown")));
	size_t i, j;
	json_t *g, *c, *m;
	fputs("Gates:", o);
	json_array_foreach(json_object_get(cmp, "gates"), i, g) {
		fputs(i ? ", " : " ", o);
		md_code(o, json_string_value(g));
	}
	fputs(". A cost change counts only when its bootstrap interval (p10 of the timed renders) is past the gate.\n\n",
	      o);
	if (tripped) {
		fputs("| case | method | gate | what changed |\n| --- | --- | --- | --- |\n", o);
		json_array_foreach(json_object_get(cmp, "tripped"), i, g) {
			fputs("| ", o);
			md_text(o, string(g, "case"));
			fputs(" | ", o);
			md_text(o, string(g, "method"));
			fputs(" | ", o);
			md_code(o, string(g, "gate"));
			fputs(" | ", o);
			md_text(o, string(g, "message"));
			fputs(" |\n", o);
		}
		fputs("\n", o);
	}
	json_array_foreach(json_object_get(cmp, "cases"), i, c) {
		fputs("<details><summary>", o);
		md_text(o, string(c, "id"));
		fputs("</summary>\n\n| method | PSNR dB | SSIM | FLIP | flicker | GPU ms: median, judged change [interval] | MB |\n"
		      "| --- | --- | --- | --- | --- | --- | --- |\n", o);
		json_array_foreach(json_object_get(c, "methods"), j, m) {
			struct row r;
			char note[600];
			row_of(m, &r);
			pairing_note(m, note, sizeof note);
			fputs("| ", o);
			md_text(o, string(m, "label"));
			if (note[0]) {
				fputs("<br>", o);
				md_text(o, note);
			}
			const char *cells[5] = {r.psnr, r.ssim, r.flip, r.flicker, r.gpu};
			for (int k = 0; k < 5; k++) {
				fputs(" | ", o);
				md_text(o, cells[k]);
			}
			fprintf(o, " | %.2f |\n",
				number(json_object_get(json_object_get(m, "metrics"), "memory_bytes"), "new") / 1048576.0);
		}
		fputs("\n</details>\n\n", o);
	}
	return ferror(o) ? -1 : 0;
}
