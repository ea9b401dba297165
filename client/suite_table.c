/* The summary table of a suite's results across its cases, read from results.json so that local and
 * remote runs print the same thing. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "client.h"
#include "util/json_text.h"

static double metric_mean(json_t *method, const char *name)
{
	return aa_json_number(json_object_get(json_object_get(method, "metrics"), name), "mean");
}

void aa_print_suite_table(json_t *results, FILE *out)
{
	json_t *labels = json_object_get(results, "labels"), *v, *c, *m;
	const char *key, *suite = json_string_value(json_object_get(results, "suite"));
	size_t i, j;
	fprintf(out, "suite %s, %zu cases", suite && *suite ? suite : "(unnamed)",
		json_array_size(json_object_get(results, "cases")));
	json_object_foreach(labels, key, v)
		fprintf(out, ", %s=%s", key, json_string_value(v));
	/* references from the store, over every case's frames */
	long hits = 0, frames = 0;
	bool cached = false;
	json_array_foreach(json_object_get(results, "cases"), i, c) {
		json_t *ref = json_object_get(c, "reference"), *cache = json_object_get(ref, "cache");
		cached |= json_is_object(cache);
		hits += (long)json_integer_value(json_object_get(cache, "hits"));
		frames += (long)json_array_size(json_object_get(ref, "per_frame"));
	}
	if (cached)
		fprintf(out, ", references from the cache: %ld of %ld frames", hits, frames);
	fprintf(out, ", %s\n\n", json_string_value(json_object_get(json_object_get(results, "device"), "name")) ?
				    json_string_value(json_object_get(json_object_get(results, "device"), "name")) : "");
	/* the method column fits the longest label, so parameters do not push the columns */
	int width = 24;
	json_array_foreach(json_object_get(results, "cases"), i, c)
		json_array_foreach(json_object_get(c, "methods"), j, m) {
			const char *label = json_string_value(json_object_get(m, "label"));
			width = label && (int)strlen(label) > width ? (int)strlen(label) : width;
		}
	/* GPU ms: the median over every timed render, with the 10th-90th percentile range */
	fprintf(out, "%-34s %-*s %9s %-19s %8s %9s %7s %7s %8s  %s\n", "case", width, "method", "GPU ms",
		"p10-p90 ms (n)", "MB", "PSNR dB", "SSIM", "FLIP", "flicker", "verdict");
	json_array_foreach(json_object_get(results, "cases"), i, c) {
		json_array_foreach(json_object_get(c, "methods"), j, m) {
			json_t *gpu = json_object_get(m, "gpu_ms");
			json_t *psnr = json_object_get(json_object_get(m, "metrics"), "psnr");
			char psnr_text[32], spread[48], place[160];
			if (json_is_number(json_object_get(psnr, "mean")))
				snprintf(psnr_text, sizeof psnr_text, "%.2f", json_number_value(json_object_get(psnr, "mean")));
			else
				snprintf(psnr_text, sizeof psnr_text, "%s",
					 json_is_true(json_object_get(psnr, "identical")) ? "identical" : "-");
			/* one timed render has no spread: an interval of one value would only look like one */
			const long long n = json_integer_value(json_object_get(gpu, "n"));
			if (n < AA_MIN_TIMED_RENDERS)
				snprintf(spread, sizeof spread, "n=%lld: not ranked", n);
			else
				snprintf(spread, sizeof spread, "%.2f-%.2f (%lld)", aa_json_number(gpu, "p10"), aa_json_number(gpu, "p90"), n);
			aa_verdict_place(c, json_string_value(json_object_get(m, "label")), place, sizeof place);
			fprintf(out, "%-34s %-*s %9.2f %-19s %8.2f %9s %7.4f %7.4f %8.3f  %s\n",
				j == 0 ? json_string_value(json_object_get(c, "id")) : "", width,
				json_string_value(json_object_get(m, "label")), aa_json_number(gpu, "median"), spread,
				aa_json_number(m, "memory_bytes") / 1048576.0, psnr_text, metric_mean(m, "ssim"),
				metric_mean(m, "flip"), metric_mean(m, "flicker"), place);
		}
	}
}
