/* The verdict and the warnings of a results.json (docs/results-format.md, "verdict", "warnings"), printed
 * as the document says them: every command that shows results (run, watch, status, get, merge) prints
 * these lines, and report.html and the dashboard show the same text. */
#include <stdio.h>
#include <string.h>

#include "client.h"
#include "util/json_text.h"

/* One line per method family with several configurations (verdict.families): "  fxaa family front:
 * fxaa:preset=20 and fxaa:preset=39 (of 3 configurations, cheapest first)". */
static void print_families(json_t *verdict, FILE *out)
{
	json_t *f, *label;
	size_t i, j;
	json_array_foreach(json_object_get(verdict, "families"), i, f) {
		json_t *front = json_object_get(f, "front");
		const size_t n = json_array_size(front), of = json_array_size(json_object_get(f, "methods"));
		fprintf(out, "  %s family front: ", aa_json_string(f, "family"));
		if (n == 0)
			fprintf(out, "none, its costs are not ranked");
		json_array_foreach(front, j, label)
			fprintf(out, "%s%s", j == 0 ? "" : j + 1 == n ? " and " : ", ", json_string_value(label));
		fprintf(out, " (of %zu configurations, cheapest first)\n", of);
	}
}

void aa_print_verdict(json_t *results, FILE *out)
{
	json_t *cases = json_object_get(results, "cases"), *c, *v, *line;
	size_t i;
	if (!cases) { /* a job: the headline, then what beats each other method and by how much */
		if (!(v = json_object_get(results, "verdict")))
			return;
		fprintf(out, "verdict: %s\n", aa_json_string(v, "headline"));
		json_array_foreach(json_object_get(v, "lines"), i, line)
			fprintf(out, "  %s\n", json_string_value(line));
		print_families(v, out);
		return;
	}
	/* a suite: a headline per case and its family fronts; the table's verdict column names what beats each method, and each
	 * case's report and results.json say by how much */
	json_array_foreach(cases, i, c)
		if ((v = json_object_get(c, "verdict"))) {
			fprintf(out, "verdict, %s: %s\n", aa_json_string(c, "id"), aa_json_string(v, "headline"));
			print_families(v, out);
		}
}

/* One warning: "  CODE: MESSAGE" and "    what to do: ACTION". */
static void print_warning(json_t *w, const char *case_id, FILE *out)
{
	if (json_is_string(w)) { /* results.json written before warnings had codes */
		fprintf(out, "  %s%s%s\n", case_id ? case_id : "", case_id ? ": " : "", json_string_value(w));
		return;
	}
	fprintf(out, "  %s%s%s: %s\n", case_id ? case_id : "", case_id ? ": " : "", aa_json_string(w, "code"), aa_json_string(w, "message"));
	if (*aa_json_string(w, "action"))
		fprintf(out, "    what to do: %s\n", aa_json_string(w, "action"));
}

void aa_verdict_place(json_t *doc, const char *label, char *out, size_t size)
{
	size_t i;
	json_t *m;
	snprintf(out, size, "-");
	json_array_foreach(json_object_get(json_object_get(doc, "verdict"), "methods"), i, m) {
		if (strcmp(aa_json_string(m, "label"), label))
			continue;
		json_t *by = json_object_get(m, "beaten_by");
		if (by)
			snprintf(out, size, "beaten by %s", aa_json_string(by, "method"));
		else
			snprintf(out, size, "%s", aa_json_string(m, "place"));
	}
}

int aa_print_warnings(json_t *results, FILE *out)
{
	json_t *cases = json_object_get(results, "cases"), *c, *w;
	size_t i, j;
	int count = 0;
	if (!cases)
		count = (int)json_array_size(json_object_get(results, "warnings"));
	json_array_foreach(cases, i, c)
		count += (int)json_array_size(json_object_get(c, "warnings"));
	if (count == 0)
		return 0;
	fprintf(out, "\nwarnings (%d):\n", count);
	if (!cases)
		json_array_foreach(json_object_get(results, "warnings"), j, w)
			print_warning(w, NULL, out);
	json_array_foreach(cases, i, c)
		json_array_foreach(json_object_get(c, "warnings"), j, w)
			print_warning(w, aa_json_string(c, "id"), out);
	return count;
}

void aa_verdict_headline(json_t *results, char *out, size_t size)
{
	json_t *cases = json_object_get(results, "cases");
	if (!cases) {
		snprintf(out, size, "%s", aa_json_string(json_object_get(results, "verdict"), "headline"));
		return;
	}
	/* a suite: the one case's headline, or how many cases have one */
	if (json_array_size(cases) == 1) {
		snprintf(out, size, "%s", aa_json_string(json_object_get(json_array_get(cases, 0), "verdict"), "headline"));
		return;
	}
	snprintf(out, size, "one per case, %zu cases", json_array_size(cases));
}
