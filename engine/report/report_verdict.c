/* report.html's top: the verdict (the cost-quality front, its ties, what beats each other method) and the
 * warnings that qualify it, exactly as results.json has them (engine/results/front.c, warnings.c). */
#include <stdio.h>
#include <string.h>

#include "report/report.h"
#include "util/json_text.h"

/* Each method family's front (verdict.families), worded as the terminal words it (client/verdict_lines.c). */
static void write_families(FILE *o, const json_t *verdict)
{
	json_t *f, *label;
	size_t i, j;
	if (!json_array_size(json_object_get(verdict, "families")))
		return;
	fputs("<ul class=\"families\">\n", o);
	json_array_foreach(json_object_get(verdict, "families"), i, f) {
		json_t *front = json_object_get(f, "front");
		const size_t n = json_array_size(front);
		fputs("<li>", o);
		aa_report_esc(o, aa_json_string(f, "family"));
		fputs(" family front: ", o);
		if (n == 0)
			fputs("none, its costs are not ranked", o);
		json_array_foreach(front, j, label) {
			fputs(j == 0 ? "" : j + 1 == n ? " and " : ", ", o);
			aa_report_esc(o, json_string_value(label) ? json_string_value(label) : "");
		}
		fprintf(o, " (of %zu configurations, cheapest first)</li>\n", json_array_size(json_object_get(f, "methods")));
	}
	fputs("</ul>\n", o);
}

void aa_report_write_verdict(FILE *o, const json_t *verdict, const json_t *warnings)
{
	size_t i;
	json_t *v;
	if (verdict) {
		fputs("<section id=\"verdict\" class=\"verdict\"><h2>Verdict</h2>\n<p class=\"headline\">", o);
		aa_report_esc(o, aa_json_string(verdict, "headline"));
		fputs("</p>\n", o);
		if (json_array_size(json_object_get(verdict, "lines"))) {
			fputs("<ul>\n", o);
			json_array_foreach(json_object_get(verdict, "lines"), i, v) {
				fputs("<li>", o);
				aa_report_esc(o, json_string_value(v));
				fputs("</li>\n", o);
			}
			fputs("</ul>\n", o);
		}
		write_families(o, verdict);
		fprintf(o, "<p class=\"note\">The front: the methods no other method beats, that is, none is at most as "
			   "costly and at least as good in PSNR and FLIP. Cost is the GPU time over the timed renders; one "
			   "is lower than another only when their 10th-90th percentile spreads are apart, and costs whose "
			   "spreads overlap are the same. A method with fewer than %lld timed renders is not ranked.</p>\n",
			json_integer_value(json_object_get(json_object_get(verdict, "rule"), "min_timed_renders")));
		fputs("</section>\n", o);
	}
	if (!json_array_size(warnings))
		return;
	fputs("<section id=\"warnings\" class=\"warnings\"><h2>Warnings</h2><ul>\n", o);
	json_array_foreach(warnings, i, v) {
		fputs("<li><b>", o);
		aa_report_esc(o, aa_json_string(v, "code"));
		fputs("</b>: ", o);
		aa_report_esc(o, json_is_string(v) ? json_string_value(v) : aa_json_string(v, "message"));
		if (*aa_json_string(v, "action")) {
			fputs("<br><span class=\"todo\">What to do: ", o);
			aa_report_esc(o, aa_json_string(v, "action"));
			fputs("</span>", o);
		}
		fputs("</li>\n", o);
	}
	fputs("</ul></section>\n", o);
}
