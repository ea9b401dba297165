/* report.html's top: the verdict (the cost-quality front, its ties, what beats each other method) and the
 * warnings that qualify it, exactly as results.json has them (engine/results/front.c, warnings.c). */
#include <stdio.h>
#include <string.h>

#include "report/report.h"
#include "util/json_text.h"

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
