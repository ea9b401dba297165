/* The cost-vs-accuracy table of one job's results.json (or one case of a suite's): read from the document,
 * so that a run in this process, a run on aalabd, a merge and `aalab get` print the same thing. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "client.h"
#include "util/json_text.h"

/* PSNR as the table prints it: "identical" for identical images, "-" when there is none. */
static void format_psnr(json_t *value, bool identical, char *out, size_t size)
{
	if (identical)
		snprintf(out, size, "identical");
	else if (json_is_number(value))
		snprintf(out, size, "%.2f", json_number_value(value));
	else
		snprintf(out, size, "-");
}

/* ", from the cache: 28 of 30 frames" when the run had a store (the frames it did not render). */
static void cache_text(json_t *ref, char *out, size_t size)
{
	json_t *c = json_object_get(ref, "cache");
	out[0] = 0;
	if (!json_is_object(c))
		return;
	const long long frames = (long long)json_array_size(json_object_get(ref, "per_frame"));
	const long long continued = json_integer_value(json_object_get(c, "continued"));
	int n = snprintf(out, size, ", from the cache: %lld of %lld frames",
			 json_integer_value(json_object_get(c, "hits")), frames);
	if (continued && n > 0 && (size_t)n < size)
		snprintf(out + n, size - (size_t)n, " (%lld went on from a stored sum)", continued);
}

/* "scene hard-edges, path default, 640x360, 1 frame, reference 64 samples (convergence 32 vs 64: 52.76 dB),
 * DEVICE" and how the times were taken. */
static void print_header(json_t *r, FILE *out)
{
	json_t *job = json_object_get(r, "job"), *ref = json_object_get(r, "reference"), *timing = json_object_get(r, "timing");
	const long long frames = json_integer_value(json_object_get(r, "frames"));
	char conv[32], cached[96];
	cache_text(ref, cached, sizeof cached);
	format_psnr(json_object_get(ref, "convergence_psnr"), json_is_true(json_object_get(ref, "convergence_identical")),
		    conv, sizeof conv);
	fprintf(out, "scene %s, path %s, %s, %lld frame%s, ", aa_json_string(json_object_get(r, "scene"), "name"), aa_json_string(job, "path"),
		aa_json_string(job, "size"), frames, frames == 1 ? "" : "s");
	const long long samples = json_integer_value(json_object_get(ref, "samples"));
	if (!strcmp(aa_json_string(ref, "mode"), "auto")) {
		/* the N each frame reached, as a range: "auto" alone would hide what the reference cost */
		long long lo = -1, hi = -1;
		size_t i;
		json_t *f;
		json_array_foreach(json_object_get(ref, "per_frame"), i, f) {
			const long long n = json_integer_value(json_object_get(f, "samples"));
			lo = lo < 0 || n < lo ? n : lo;
			hi = n > hi ? n : hi;
		}
		char reached[64];
		snprintf(reached, sizeof reached, lo == hi ? "%lld samples" : "%lld-%lld samples per frame", lo, hi);
		fprintf(out, "reference auto: %s (target %.1f dB, cap %lld; convergence N/2 vs N: %s dB)%s", reached,
			aa_json_number(ref, "target_psnr"), samples, conv, cached);
	} else {
		fprintf(out, "reference %lld samples%s (convergence %lld vs %lld: %s dB)", samples, cached, samples / 2, samples,
			conv);
	}
	fprintf(out, ", %s\n", aa_json_string(json_object_get(r, "device"), "name"));
	const long long repeat = json_integer_value(json_object_get(timing, "repeat"));
	fprintf(out, "timing: %lld timed render%s per method (%lld frame%s x repeat %lld%s), GPU ms the median with "
		"its p10-p90 spread\n\n", json_integer_value(json_object_get(timing, "timed_renders_per_method")),
		json_integer_value(json_object_get(timing, "timed_renders_per_method")) == 1 ? "" : "s", frames,
		frames == 1 ? "" : "s", repeat, json_is_true(json_object_get(timing, "auto")) ? ", auto" : "");
}

void aa_print_results_table(json_t *r, FILE *out)
{
	print_header(r, out);
	json_t *methods = json_object_get(r, "methods"), *m;
	size_t i;
	const bool sequence = json_integer_value(json_object_get(r, "frames")) > 1;
	/* the method column fits the longest label, so parameters do not push the columns */
	int width = 12;
	json_array_foreach(methods, i, m)
		width = (int)strlen(aa_json_string(m, "label")) > width ? (int)strlen(aa_json_string(m, "label")) : width;
	/* idiff's count: pixels with a channel off by more than the threshold, as a share of the pixels */
	char over_head[32];
	json_t *first_over = json_object_get(json_object_get(json_object_get(json_array_get(methods, 0), "metrics"),
							      "over_threshold"), "threshold");
	snprintf(over_head, sizeof over_head, "px >%g%% off", 100.0 * (json_is_number(first_over) ?
								  json_number_value(first_over) : 0.01));
	fprintf(out, "%-*s %9s %-19s %8s %9s %7s %7s %11s", width, "method", "GPU ms", "p10-p90 ms (n)", "MB", "PSNR dB",
		"SSIM", "FLIP", over_head);
	if (sequence) /* per-sequence figures: worst and best frame (index), and the temporal stability figure */
		fprintf(out, " %16s %16s %8s", "worst dB (frame)", "best dB (frame)", "flicker");
	fprintf(out, "  %s\n", "verdict");
	json_array_foreach(methods, i, m) {
		json_t *gpu = json_object_get(m, "gpu_ms"), *metrics = json_object_get(m, "metrics");
		json_t *psnr = json_object_get(metrics, "psnr");
		char psnr_text[32], spread[48], place[160], over[32];
		format_psnr(json_object_get(psnr, "mean"), json_is_true(json_object_get(psnr, "identical")), psnr_text,
			    sizeof psnr_text);
		const long long n = json_integer_value(json_object_get(gpu, "n"));
		/* one timed render has no spread: an interval of one value would only look like one */
		if (n < AA_MIN_TIMED_RENDERS)
			snprintf(spread, sizeof spread, "n=%lld: not ranked", n);
		else
			snprintf(spread, sizeof spread, "%.2f-%.2f (%lld)", aa_json_number(gpu, "p10"), aa_json_number(gpu, "p90"), n);
		const double share = aa_json_number(json_object_get(metrics, "over_threshold"), "mean_share");
		snprintf(over, sizeof over, isfinite(share) ? "%.2f%%" : "-", 100.0 * share);
		aa_verdict_place(r, aa_json_string(m, "label"), place, sizeof place);
		fprintf(out, "%-*s %9.2f %-19s %8.1f %9s %7.4f %7.4f %11s", width, aa_json_string(m, "label"), aa_json_number(gpu, "median"),
			spread, aa_json_number(m, "memory_bytes") / 1048576.0, psnr_text,
			aa_json_number(json_object_get(metrics, "ssim"), "mean"), aa_json_number(json_object_get(metrics, "flip"), "mean"),
			over);
		if (sequence) {
			char cell[48], value[32];
			json_t *worst = json_object_get(psnr, "worst"), *best = json_object_get(psnr, "best");
			format_psnr(json_object_get(worst, "value"), json_is_true(json_object_get(worst, "identical")), value,
				    sizeof value);
			snprintf(cell, sizeof cell, "%s (%lld)", value, json_integer_value(json_object_get(worst, "frame")));
			fprintf(out, " %16s", cell);
			format_psnr(json_object_get(best, "value"), json_is_true(json_object_get(best, "identical")), value,
				    sizeof value);
			snprintf(cell, sizeof cell, "%s (%lld)", value, json_integer_value(json_object_get(best, "frame")));
			fprintf(out, " %16s %8.3f", cell, aa_json_number(json_object_get(metrics, "flicker"), "mean"));
		}
		fprintf(out, "  %s\n", place);
	}
	/* cut-out materials: say how each method tested alpha, so that a ranking can be read fairly */
	bool cutouts = false;
	json_array_foreach(json_object_get(r, "passes"), i, m)
		cutouts = cutouts || (!strcmp(aa_json_string(m, "pass"), "alpha-test") && json_is_true(json_object_get(m, "ran")));
	if (cutouts) {
		fputs("\nalpha test of cut-out materials:", out);
		json_array_foreach(methods, i, m)
			fprintf(out, "%s %s %s", i ? "," : "", aa_json_string(m, "label"), aa_json_string(m, "alpha_rule"));
		fputs("; reference per-sample (docs/methods.md)\n", out);
	}
}

void aa_print_results(json_t *results, FILE *out)
{
	const bool suite = json_object_get(results, "cases") != NULL;
	aa_print_verdict(results, out);
	fputc('\n', out);
	if (suite)
		aa_print_suite_table(results, out);
	else
		aa_print_results_table(results, out);
	aa_print_warnings(results, out);
}
