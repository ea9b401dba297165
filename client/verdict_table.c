/* The verdict table of a suite run with "verdicts": true (docs/hard-cases.md), read from results.json so
 * that local and remote runs print the same thing. */
#include <stdio.h>
#include <string.h>

#include "client.h"

static const char *const kinds[] = {"finite", "range", "stuck", "drift", "vs_none", "dip"};

/* "pass", "FAIL", "fail*" (a failure the docs expect) or "-" (not applicable), with the figure judged. */
static void cell(json_t *v, char *out, size_t size)
{
	const char *state = json_string_value(json_object_get(v, "state"));
	json_t *value = json_object_get(v, "value");
	const bool expected = json_object_get(v, "expected") != NULL;
	if (!state || !strcmp(state, "n/a")) {
		snprintf(out, size, "-");
		return;
	}
	const char *word = !strcmp(state, "pass") ? "pass" : expected ? "fail*" : "FAIL";
	if (json_is_integer(value) || (json_is_real(value) && json_real_value(value) == (long)json_real_value(value) &&
				       json_real_value(value) < 1e9 && json_real_value(value) > -1e9))
		snprintf(out, size, "%s %.3g", word, json_number_value(value));
	else if (json_is_real(value))
		snprintf(out, size, "%s %.2f", word, json_real_value(value));
	else if (json_is_string(value))
		snprintf(out, size, "%s %s", word, json_string_value(value));
	else
		snprintf(out, size, "%s", word);
}

int aa_print_verdict_table(json_t *results, FILE *out)
{
	json_t *verdicts = json_object_get(results, "verdicts"), *item;
	if (!verdicts)
		return 0;
	json_t *t = json_object_get(verdicts, "thresholds");
	fprintf(out, "\nverdicts (docs/hard-cases.md): finite = NaN/Inf values, range = negative values, stuck = the "
		"smallest\nchange/reference-change ratio (fail under %.2g), drift = late - early PSNR dB on a static "
		"path (fail\nunder -%.2g), vs_none = PSNR dB - none's (fail under -%.2g), dip = the worst frame's PSNR dB "
		"- none's\nin that frame (fail under -%.2g); fail* = an expected exception\n\n",
		json_number_value(json_object_get(t, "stuck_ratio")), json_number_value(json_object_get(t, "drift_db")),
		json_number_value(json_object_get(t, "vs_none_db")), json_number_value(json_object_get(t, "dip_db")));
	fprintf(out, "%-40s %-32s", "case", "method");
	for (size_t k = 0; k < sizeof kinds / sizeof kinds[0]; k++)
		fprintf(out, " %-12s", kinds[k]);
	fputc('\n', out);
	const char *last_case = "";
	size_t i;
	json_array_foreach(json_object_get(verdicts, "items"), i, item) {
		const char *id = json_string_value(json_object_get(item, "case"));
		fprintf(out, "%-40s %-32s", id && strcmp(id, last_case) ? id : "",
			json_string_value(json_object_get(item, "method")));
		last_case = id ? id : "";
		for (size_t k = 0; k < sizeof kinds / sizeof kinds[0]; k++) {
			char text[48];
			cell(json_object_get(json_object_get(item, "verdicts"), kinds[k]), text, sizeof text);
			fprintf(out, " %-12s", text);
		}
		fputc('\n', out);
	}
	const int failed = (int)json_integer_value(json_object_get(verdicts, "failed"));
	fprintf(out, "\n%d verdict%s failed that must hold; %d expected exception%s\n", failed, failed == 1 ? "" : "s",
		(int)json_integer_value(json_object_get(verdicts, "expected_failures")),
		json_integer_value(json_object_get(verdicts, "expected_failures")) == 1 ? "" : "s");
	return failed;
}
