/* The comparison of two runs for people and CI servers: a text table, JUnit XML (one test case per case x
 * method x gate, as Jenkins and GitLab read it) and a markdown summary for a merge-request comment.
 * Everything is read from the comparison JSON, so the three say exactly what --json says. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "compare/compare.h"
#include "util/json_text.h"

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
		snprintf(out, size, "%s", aa_json_string(run, "source"));
}

/* A quality value as the tables print it: "identical" for an infinite PSNR, "-" when missing. */
static void value_text(json_t *q, const char *side, int decimals, bool psnr, char *out, size_t size)
{
	char key[32];
	snprintf(key, sizeof key, "%s_identical", side);
	const double v = aa_json_number(q, side);
	if (psnr && json_is_true(json_object_get(q, key)))
		snprintf(out, size, "identical");
	else if (isfinite(v))
		snprintf(out, size, "%.*f", decimals, v);
	else
		snprintf(out, size, "-");
}

/* "30.60 -> 30.12 -0.48": BASE's value, NEW's and the change (exact: quality is deterministic). */
static void quality_cell(json_t *q, int decimals, bool psnr, char *out, size_t size)
{
	char bt[32], nt[32], ct[40];
	const double c = aa_json_number(q, "change");
	value_text(q, "base", decimals, psnr, bt, sizeof bt);
	value_text(q, "new", decimals, psnr, nt, sizeof nt);
	if (psnr && json_is_true(json_object_get(q, "base_identical")) != json_is_true(json_object_get(q, "new_identical")))
		snprintf(ct, sizeof ct, "%s", json_is_true(json_object_get(q, "new_identical")) ? "+inf" : "-inf");
	else if (isfinite(c))
		snprintf(ct, sizeof ct, "%+.*f", decimals, c);
	else
		ct[0] = '\0';
	snprintf(out, size, "%s -> %s %s", bt, nt, ct);
}

/* The cost cells: the medians "12.04 -> 15.93", their raw change "+32.3%", and the change the gates judge
 * (the p10 over the case's machine factor) with its interval, "+1% [-5%, +8%]". */
static void cost_cells(json_t *c, char *medians, size_t msize, char *raw, size_t rsize, char *judged, size_t jsize)
{
	json_t *b = json_object_get(c, "base"), *n = json_object_get(c, "new"), *iv = json_object_get(c, "interval_pct");
	snprintf(medians, msize, "%.2f -> %.2f", aa_json_number(b, "median"), aa_json_number(n, "median"));
	snprintf(raw, rsize, isfinite(aa_json_number(c, "change_median_pct")) ? "%+.1f%%" : "-", aa_json_number(c, "change_median_pct"));
	if (!isfinite(aa_json_number(c, "judged_pct")))
		snprintf(judged, jsize, "-");
	else if (json_is_number(json_array_get(iv, 0)))
		snprintf(judged, jsize, "%+.1f%% [%+.1f%%, %+.1f%%]", aa_json_number(c, "judged_pct"),
			 json_number_value(json_array_get(iv, 0)), json_number_value(json_array_get(iv, 1)));
	else
		snprintf(judged, jsize, "%+.1f%% [no interval]", aa_json_number(c, "judged_pct"));
}

/* What the gates of one kind (cost: gpu_ms and cpu_ms; quality: the others) said of a method: "TRIPPED
 * psnr < -0.1", "held", "held; not judged: flicker > +0.1", "not judged: gpu_ms > +50% (n<5)". */
static void gates_cell(json_t *m, bool cost, char *out, size_t size)
{
	size_t i, used = 0;
	json_t *g;
	int tripped = 0, held = 0, unknown = 0;
	char unknown_list[256] = "";
	size_t uused = 0;
	json_array_foreach(json_object_get(m, "gates"), i, g) {
		const char *metric = aa_json_string(g, "metric"), *result = aa_json_string(g, "result");
		if ((!strcmp(metric, "gpu_ms") || !strcmp(metric, "cpu_ms")) != cost)
			continue;
		if (!strcmp(result, "tripped")) {
			if (used < size)
				used += (size_t)snprintf(out + used, size - used, "%s%s", tripped ? ", " : "TRIPPED ",
							 aa_json_string(g, "gate"));
			tripped++;
		} else if (!strcmp(result, "held")) {
			held++;
		} else if (uused < sizeof unknown_list) {
			uused += (size_t)snprintf(unknown_list + uused, sizeof unknown_list - uused, "%s%s",
						  unknown ? ", " : "", aa_json_string(g, "gate"));
			unknown++;
		}
	}
	if (!tripped && !held && !unknown)
		snprintf(out, size, "-");
	else if (!tripped && !unknown)
		snprintf(out, size, "held");
	else if (!tripped)
		snprintf(out, size, "%snot judged: %s", held ? "held; " : "", unknown_list);
	else if (unknown && used < size)
		snprintf(out + used, size - used, "; not judged: %s", unknown_list);
}

/* "was fxaa (paired by name): preset 12 -> 10, edge_threshold 0.166 -> 0.333", or "" when the label is
 * the same in both runs. */
static void pairing_note(json_t *m, char *out, size_t size)
{
	size_t used = 0, k;
	json_t *pc;
	out[0] = '\0';
	if (!strcmp(aa_json_string(m, "label"), aa_json_string(m, "base_label")))
		return;
	used = (size_t)snprintf(out, size, "was %s (paired by %s)", aa_json_string(m, "base_label"), aa_json_string(m, "paired_by"));
	json_array_foreach(json_object_get(m, "params_changed"), k, pc) {
		char *bv = json_dumps(json_object_get(pc, "base"), JSON_ENCODE_ANY | JSON_REAL_PRECISION(6));
		char *nv = json_dumps(json_object_get(pc, "new"), JSON_ENCODE_ANY | JSON_REAL_PRECISION(6));
		if (used < size)
			used += (size_t)snprintf(out + used, size - used, "%s %s %s -> %s", k ? "," : ":",
						 aa_json_string(pc, "param"), bv ? bv : "?", nv ? nv : "?");
		free(bv);
		free(nv);
	}
}

/* "MB 2.6 -> 2.6 +0.0" */
static void memory_cell(json_t *m, char *out, size_t size)
{
	json_t *mem = json_object_get(json_object_get(m, "metrics"), "memory_bytes");
	snprintf(out, size, "%.1f -> %.1f %+.1f", aa_json_number(mem, "base") / 1048576.0, aa_json_number(mem, "new") / 1048576.0,
		 aa_json_number(mem, "change") / 1048576.0);
}

/* Each run's verdict of the case (its results.json's headline), when the runs have one. */
static void print_verdicts(json_t *c, FILE *out)
{
	json_t *v = json_object_get(c, "verdict");
	const char *b = aa_json_string(json_object_get(v, "base"), "headline"), *n = aa_json_string(json_object_get(v, "new"), "headline");
	if (*b)
		fprintf(out, "  verdict BASE: %s\n", b);
	if (*n)
		fprintf(out, "  verdict NEW:  %s\n", n);
}

void aa_compare_print_table(const json_t *cmp_const, FILE *out)
{
	json_t *cmp = (json_t *)cmp_const;
	char bn[512], nn[512];
	run_name(json_object_get(cmp, "base"), bn, sizeof bn);
	run_name(json_object_get(cmp, "new"), nn, sizeof nn);
	fprintf(out, "BASE %s (%s)\nNEW  %s (%s)\ngates:", aa_json_string(json_object_get(cmp, "base"), "source"), bn,
		aa_json_string(json_object_get(cmp, "new"), "source"), nn);
	size_t i, j;
	json_t *g, *c, *m;
	json_array_foreach(json_object_get(cmp, "gates"), i, g)
		fprintf(out, "%s %s", i ? "," : "", json_string_value(g));
	fprintf(out, "\nquality: BASE -> NEW and the change (renders are deterministic: any change is real).\n"
		"GPU ms: the median BASE -> NEW and its raw change; then the change the gates judge: the p10 of the\n"
		"timed renders, NEW's divided by the case's machine factor, with its %.0f%% interval. A > gate trips\n"
		"when the whole interval is past it.\n", 100 * aa_json_number(json_object_get(cmp, "cost_rule"), "interval_level"));
	json_array_foreach(json_object_get(cmp, "cases"), i, c) {
		fprintf(out, "\ncase %s", aa_json_string(c, "id"));
		json_t *fc = json_object_get(c, "frames_changed");
		if (fc)
			fprintf(out, "  (frames %lld -> %lld)", json_integer_value(json_object_get(fc, "base")),
				json_integer_value(json_object_get(fc, "new")));
		fputc('\n', out);
		print_verdicts(c, out);
		int width = 8;
		json_array_foreach(json_object_get(c, "methods"), j, m)
			if ((int)strlen(aa_json_string(m, "label")) > width)
				width = (int)strlen(aa_json_string(m, "label"));
		if (json_array_size(json_object_get(c, "methods"))) {
			fprintf(out, "  %-*s  %-24s %-26s %-26s %-22s %-18s %s\n", width, "quality", "PSNR dB", "SSIM", "FLIP",
				"flicker", "MB", "gates");
			json_array_foreach(json_object_get(c, "methods"), j, m) {
				json_t *mt = json_object_get(m, "metrics");
				char psnr[80], ssim[80], flip[80], flicker[80], mem[64], gates[400], note[600];
				quality_cell(json_object_get(mt, "psnr"), 2, true, psnr, sizeof psnr);
				quality_cell(json_object_get(mt, "ssim"), 4, false, ssim, sizeof ssim);
				quality_cell(json_object_get(mt, "flip"), 4, false, flip, sizeof flip);
				quality_cell(json_object_get(mt, "flicker"), 3, false, flicker, sizeof flicker);
				memory_cell(m, mem, sizeof mem);
				gates_cell(m, false, gates, sizeof gates);
				fprintf(out, "  %-*s  %-24s %-26s %-26s %-22s %-18s %s\n", width, aa_json_string(m, "label"), psnr, ssim,
					flip, flicker, mem, gates);
				pairing_note(m, note, sizeof note);
				if (note[0])
					fprintf(out, "  %-*s  %s\n", width, "", note);
			}
			fprintf(out, "  %-*s  %-20s %-11s %-34s %s\n", width, "time", "GPU ms median", "raw change",
				"judged change [interval]", "gates");
			json_array_foreach(json_object_get(c, "methods"), j, m) {
				char medians[64], raw[32], judged[96], gates[400];
				cost_cells(json_object_get(json_object_get(m, "metrics"), "gpu_ms"), medians, sizeof medians, raw,
					   sizeof raw, judged, sizeof judged);
				gates_cell(m, true, gates, sizeof gates);
				fprintf(out, "  %-*s  %-20s %-11s %-34s %s\n", width, aa_json_string(m, "label"), medians, raw, judged,
					gates);
			}
		}
		json_t *mf = json_object_get(json_object_get(c, "machine_factor"), "gpu_ms");
		const double f = aa_json_number(mf, "value");
		if (isfinite(f) && f != 1)
			fprintf(out, "  machine factor x%.2f: NEW ran this case %.0f%% %s than BASE; the judged change divides "
				"NEW's times by it\n", f, fabs(100 * (f - 1)), f > 1 ? "slower" : "faster");
		else if (isfinite(f))
			fprintf(out, "  machine factor x1.00 (none: fewer than 3 methods with 5 timed renders in both runs, "
				"or --raw-cost, or the case ran alike)\n");
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
		fprintf(out, "  tripped %s in %s, %s: %s\n", aa_json_string(g, "gate"), aa_json_string(g, "case"), aa_json_string(g, "method"),
			aa_json_string(g, "message"));
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
				failures += !strcmp(aa_json_string(g, "result"), "tripped");
				skipped += !strcmp(aa_json_string(g, "result"), "unknown");
			}
		fputs("  <testsuite name=\"", o);
		xml_text(o, aa_json_string(c, "id"));
		fprintf(o, "\" tests=\"%d\" failures=\"%d\" errors=\"0\" skipped=\"%d\" time=\"0\">\n", tests, failures,
			skipped);
		/* what was compared with what, for the reader of the CI page */
		fputs("    <properties>\n", o);
		const char *sides[2] = {"base", "new"};
		for (int s = 0; s < 2; s++) {
			json_t *run = json_object_get(cmp, sides[s]), *v;
			const char *key;
			fprintf(o, "      <property name=\"%s.source\" value=\"", sides[s]);
			xml_text(o, aa_json_string(run, "source"));
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
				const char *result = aa_json_string(g, "result");
				fputs("    <testcase classname=\"", o);
				xml_text(o, aa_json_string(c, "id"));
				fputs("\" name=\"", o);
				xml_text(o, aa_json_string(m, "label"));
				fputs(": ", o);
				xml_text(o, aa_json_string(g, "gate"));
				fputs("\" time=\"0\"", o);
				if (!strcmp(result, "held")) {
					fputs("/>\n", o);
					continue;
				}
				fputs(">\n      <", o);
				fputs(!strcmp(result, "tripped") ? "failure type=\"gate\"" : "skipped", o);
				fputs(" message=\"", o);
				xml_text(o, aa_json_string(g, "message"));
				fputs("\">", o);
				xml_text(o, aa_json_string(g, "message"));
				if (strcmp(aa_json_string(m, "label"), aa_json_string(m, "base_label"))) {
					fputs("\nBASE method: ", o);
					xml_text(o, aa_json_string(m, "base_label"));
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
			md_text(o, aa_json_string(g, "case"));
			fputs(" | ", o);
			md_text(o, aa_json_string(g, "method"));
			fputs(" | ", o);
			md_code(o, aa_json_string(g, "gate"));
			fputs(" | ", o);
			md_text(o, aa_json_string(g, "message"));
			fputs(" |\n", o);
		}
		fputs("\n", o);
	}
	json_array_foreach(json_object_get(cmp, "cases"), i, c) {
		fputs("<details><summary>", o);
		md_text(o, aa_json_string(c, "id"));
		fputs("</summary>\n\n", o);
		json_t *v = json_object_get(c, "verdict");
		const char *sides[2] = {"base", "new"}, *names[2] = {"BASE", "NEW"};
		for (int k = 0; k < 2; k++)
			if (*aa_json_string(json_object_get(v, sides[k]), "headline")) {
				fprintf(o, "Verdict %s: ", names[k]);
				md_text(o, aa_json_string(json_object_get(v, sides[k]), "headline"));
				fputs("  \n", o);
			}
		fputs("\n| method | PSNR dB | SSIM | FLIP | flicker | MB | GPU ms median | raw change | judged change "
		      "[interval] | gates |\n| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n", o);
		json_array_foreach(json_object_get(c, "methods"), j, m) {
			json_t *mt = json_object_get(m, "metrics");
			char psnr[80], ssim[80], flip[80], flicker[80], mem[64], medians[64], raw[32], judged[96],
			     quality_gates[400], cost_gates[400], gates[820], note[600];
			quality_cell(json_object_get(mt, "psnr"), 2, true, psnr, sizeof psnr);
			quality_cell(json_object_get(mt, "ssim"), 4, false, ssim, sizeof ssim);
			quality_cell(json_object_get(mt, "flip"), 4, false, flip, sizeof flip);
			quality_cell(json_object_get(mt, "flicker"), 3, false, flicker, sizeof flicker);
			memory_cell(m, mem, sizeof mem);
			cost_cells(json_object_get(mt, "gpu_ms"), medians, sizeof medians, raw, sizeof raw, judged, sizeof judged);
			gates_cell(m, false, quality_gates, sizeof quality_gates);
			gates_cell(m, true, cost_gates, sizeof cost_gates);
			snprintf(gates, sizeof gates, "quality %s; time %s", quality_gates, cost_gates);
			pairing_note(m, note, sizeof note);
			fputs("| ", o);
			md_text(o, aa_json_string(m, "label"));
			if (note[0]) {
				fputs("<br>", o);
				md_text(o, note);
			}
			const char *cells[9] = {psnr, ssim, flip, flicker, mem, medians, raw, judged, gates};
			for (int k = 0; k < 9; k++) {
				fputs(" | ", o);
				md_text(o, cells[k]);
			}
			fputs(" |\n", o);
		}
		fputs("\n</details>\n\n", o);
	}
	return ferror(o) ? -1 : 0;
}
