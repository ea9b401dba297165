/* results.json's warnings[]: what makes a number of the run less trustworthy than it looks, said once, with
 * what to do. Most important first: the reference, then the timings the verdict rests on, then broken
 * outputs, user methods, and what loading the scene dropped or approximated. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "methods/user_method.h"
#include "results/front.h"
#include "results/warnings.h"
#include "util/json_text.h"

static void __attribute__((format(printf, 4, 5)))
add(json_t *list, const char *code, const char *action, const char *fmt, ...)
{
	char message[1024];
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(message, sizeof message, fmt, ap);
	va_end(ap);
	json_array_append_new(list, json_pack("{s:s, s:s, s:s}", "code", code, "message", message, "action", action));
}

static void reference_warnings(json_t *list, const struct aa_job_result *r, const struct aa_method_summary *sum)
{
	const struct aa_reference_result *ref = &r->reference;
	bool identical;
	const double conv = aa_reference_convergence_psnr(ref, &identical);
	if (isfinite(conv) && conv < AA_REFERENCE_CONVERGED_DB) {
		if (ref->auto_samples)
			add(list, "reference-not-converged", "raise reference.max_samples",
			    "the reference is not converged: with reference.samples \"auto\" (cap %d) its N/2-sample "
			    "images differ from its N-sample images by %.1f dB PSNR (under %.0f dB); method PSNRs near "
			    "or above %.1f dB measure the reference's noise, not the method", ref->samples, conv,
			    AA_REFERENCE_CONVERGED_DB, conv);
		else
			add(list, "reference-not-converged", "raise reference.samples (--reference-samples), or use \"auto\"",
			    "the reference is not converged: its %d-sample image differs from its %d-sample image by "
			    "%.1f dB PSNR (under %.0f dB); method PSNRs near or above %.1f dB measure the reference's "
			    "noise, not the method", ref->samples / 2, ref->samples, conv, AA_REFERENCE_CONVERGED_DB, conv);
	}
	char names[1024] = "";
	size_t used = 0;
	for (int i = 0; isfinite(conv) && i < r->method_count && used < sizeof names; i++)
		if (isfinite(sum[i].psnr_mean) && sum[i].psnr_mean >= conv - AA_REFERENCE_NOISE_MARGIN_DB)
			used += (size_t)snprintf(names + used, sizeof names - used, "%s%s (%.1f dB)", used ? ", " : "",
						 r->methods[i].label, sum[i].psnr_mean);
	if (used)
		add(list, "psnr-at-reference-noise", "raise the reference's samples until its convergence PSNR is well "
		    "above the methods'", "PSNR within %.0f dB of the reference's own convergence (%.1f dB) is not "
		    "meaningful: %s", AA_REFERENCE_NOISE_MARGIN_DB, conv, names);
	int capped = 0;
	for (int f = 0; ref->auto_samples && ref->frames && f < ref->frame_count; f++) {
		const struct aa_reference_frame *rf = &ref->frames[f];
		capped += !rf->reused && !rf->convergence_identical && rf->samples >= ref->samples &&
			  !(rf->convergence_psnr >= ref->target_psnr);
	}
	if (capped)
		add(list, "reference-capped", "raise reference.max_samples, or lower reference.target_psnr",
		    "%d frame%s of the reference reached reference.max_samples (%d) before the target of %.1f dB "
		    "(reference.per_frame[].convergence_psnr)", capped, capped == 1 ? "" : "s", ref->samples,
		    ref->target_psnr);
}

/* A method of the verdict by label. */
static json_t *verdict_method(const json_t *verdict, const char *label)
{
	size_t i;
	json_t *m;
	json_array_foreach(json_object_get(verdict, "methods"), i, m)
		if (!strcmp(json_string_value(json_object_get(m, "label")), label))
			return m;
	return NULL;
}

static void timing_warnings(json_t *list, const struct aa_job_result *r, const json_t *verdict)
{
	const int repeat = r->spec.timing_repeat > 0 ? r->spec.timing_repeat : 1;
	int fewest = -1;
	size_t i, j;
	json_t *m, *pair;
	json_array_foreach(json_object_get(verdict, "methods"), i, m) {
		const int n = (int)json_integer_value(json_object_get(json_object_get(m, "gpu_ms"), "n"));
		fewest = fewest < 0 || n < fewest ? n : fewest;
	}
	if (fewest >= 0 && fewest < AA_FRONT_MIN_TIMED_RENDERS)
		add(list, "too-few-timed-renders", "leave timing.repeat at \"auto\" (the default), or raise it "
		    "(--repeat) so that frames x repeat is at least 5",
		    "n=%d: %d frame%s x timing.repeat %d gives too few timed renders to rank costs (%d needed); the "
		    "verdict ranks no method with fewer", fewest, r->spec.frames, r->spec.frames == 1 ? "" : "s", repeat,
		    AA_FRONT_MIN_TIMED_RENDERS);
	/* the ties that touch the front: pairs whose GPU time spreads overlap */
	char text[1500];
	size_t used = 0;
	json_array_foreach(json_object_get(verdict, "ties"), i, pair) {
		if (used >= sizeof text)
			break;
		for (j = 0; j < 2; j++) {
			const char *label = json_string_value(json_array_get(pair, j));
			json_t *gpu = json_object_get(verdict_method(verdict, label), "gpu_ms");
			used += (size_t)snprintf(text + used, sizeof text - used, "%s%s %.2f-%.2f ms",
						 j ? " and " : i ? "; " : "", label, aa_json_number(gpu, "p10"), aa_json_number(gpu, "p90"));
			if (used >= sizeof text)
				break;
		}
	}
	if (used)
		add(list, "timing-spread", "treat each pair as equal in cost, or raise timing.repeat (--repeat) or run "
		    "on a quieter machine to tell them apart", "GPU times too spread to rank (p10-p90 overlap): %s", text);
	if (!isfinite(r->timestamp_period_ns))
		add(list, "no-gpu-timestamps", "compare CPU times (cpu_ms) instead, or run on a device with timestamp "
		    "queries", "this device has no GPU timestamps: GPU times are missing and no cost is ranked");
}

static void output_warnings(json_t *list, const struct aa_job_result *r)
{
	for (int i = 0; i < r->method_count; i++) {
		long bad = 0;
		for (int f = 0; r->methods[i].frames && f < r->methods[i].frame_count; f++)
			bad += r->methods[i].frames[f].nonfinite;
		if (bad > 0)
			add(list, "nonfinite-output", "frames[].nonfinite names the frames; --debug-targets finds the pass "
			    "that wrote them", "%s wrote %ld NaN or Inf values: its output is broken", r->methods[i].label,
			    bad);
	}
	long ref_bad = 0;
	for (int f = 0; r->reference.frames && f < r->reference.frame_count; f++)
		ref_bad += r->reference.frames[f].nonfinite;
	if (ref_bad > 0)
		add(list, "reference-nonfinite", "reference.per_frame[].nonfinite names the frames; check the scene's "
		    "materials and lights", "the reference wrote %ld NaN or Inf values: every comparison is suspect",
		    ref_bad);
	for (int i = 0; i < r->method_count; i++) {
		const struct aa_user_method *um = aa_user_method_of(r->methods[i].method);
		if (um)
			add(list, "user-method", "keep the method file with the results, and compare only runs whose "
			    "methods[].user_method.sha256 match", "%s is a user method from %s (sha256 %.12s...): its "
			    "numbers hold for this version of the file and its shaders", r->methods[i].label, um->file,
			    um->sha256);
	}
}

static void scene_warnings(json_t *list, const struct aa_job_result *r)
{
	for (int i = 0; i < r->warning_count && i < AA_MAX_WARNINGS; i++)
		add(list, "scene", "the numbers are for the scene as drawn; change the file if that is not what you "
		    "want to measure", "%s", r->warnings[i]);
	if (r->warnings_dropped > 0)
		add(list, "scene-warnings-capped", "fix the ones above and load the scene again ('aalab scenes FILE')",
		    "... and %d more scene warnings, not kept (at most %d are)", r->warnings_dropped, AA_MAX_WARNINGS);
}

/* The store of reference frames: an entry that failed its check was removed and rendered again, or the
 * store could not be used; the numbers are sound either way, the store is not. */
static void reference_cache_warnings(json_t *list, const struct aa_job_result *r)
{
	const struct aa_reference_cache_result *c = &r->reference.cache;
	for (int i = 0; i < c->warning_count && i < AA_REFERENCE_CACHE_WARNINGS; i++)
		add(list, "reference-cache", "'aalab cache verify' checks the store; 'aalab cache clear' empties it",
		    "%s", c->warnings[i]);
}

json_t *aa_results_warnings_json(const struct aa_job_result *r, const json_t *verdict)
{
	json_t *list = json_array();
	if (!list)
		return NULL;
	struct aa_method_summary sum[AA_MAX_METHODS];
	for (int i = 0; i < r->method_count && i < AA_MAX_METHODS; i++)
		aa_method_summarize(&r->methods[i], &sum[i]);
	reference_warnings(list, r, sum);
	timing_warnings(list, r, verdict);
	output_warnings(list, r);
	scene_warnings(list, r);
	reference_cache_warnings(list, r);
	return list;
}
