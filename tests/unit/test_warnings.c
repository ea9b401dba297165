/* results.json's warnings[] (engine/results/warnings.c) on hand-made results: each warning when its cause
 * is there, with the numbers it names, and none when nothing is wrong. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "results/front.h"
#include "results/results.h"
#include "results/warnings.h"
#include "run/job_spec.h"

/* Two methods, "plain" (31 dB) and "better" (36 dB), one frame each timed `timed` times at the given
 * milliseconds, a 16-sample reference converged at 68 dB. */
static struct aa_job_result *make_result(int timed, const double *plain_ms, const double *better_ms)
{
	struct aa_job_result *r = calloc(1, sizeof *r);
	aa_job_spec_defaults(&r->spec);
	r->spec.frames = 1;
	r->spec.timing_repeat = timed;
	r->spec.width = 40;
	r->spec.height = 20;
	r->timestamp_period_ns = 1.0;
	r->reference.samples = 16;
	r->reference.frame_count = 1;
	r->reference.frames = calloc(1, sizeof *r->reference.frames);
	r->reference.frames[0].convergence_mse = 0.01; /* 68 dB: converged */
	r->method_count = 2;
	snprintf(r->methods[0].label, sizeof r->methods[0].label, "plain");
	snprintf(r->methods[1].label, sizeof r->methods[1].label, "better");
	for (int i = 0; i < 2; i++) {
		struct aa_method_result *m = &r->methods[i];
		m->frame_count = 1;
		m->frames = calloc(1, sizeof *m->frames);
		m->frames[0].metrics.mse = 255.0 * 255.0 / pow(10, (i ? 36.0 : 31.0) / 10); /* 31 and 36 dB */
		m->frames[0].metrics.psnr = i ? 36.0 : 31.0;
		m->frames[0].metrics.flip_mean = i ? 0.02 : 0.05;
		m->timed_count = timed;
		m->timed = calloc((size_t)timed, sizeof *m->timed);
		for (int k = 0; k < timed; k++)
			m->timed[k] = (struct aa_timed_render){.repeat = k, .gpu_ms = (i ? better_ms : plain_ms)[k],
							       .cpu_ms = 1};
		m->frames[0].gpu_ms = m->timed[0].gpu_ms;
	}
	return r;
}

static void free_result(struct aa_job_result *r)
{
	aa_job_result_free(r);
	free(r);
}

static json_t *warnings_of(const struct aa_job_result *r)
{
	json_t *verdict = aa_verdict_json(r);
	assert_non_null(verdict);
	json_t *w = aa_results_warnings_json(r, verdict);
	json_decref(verdict);
	assert_non_null(w);
	return w;
}

/* The warning with this code, or NULL; its message must contain want when given. */
static json_t *find(json_t *warnings, const char *code, const char *want)
{
	size_t i;
	json_t *w;
	json_array_foreach(warnings, i, w)
		if (!strcmp(json_string_value(json_object_get(w, "code")), code)) {
			const char *message = json_string_value(json_object_get(w, "message"));
			assert_non_null(json_string_value(json_object_get(w, "action")));
			assert_true(strlen(json_string_value(json_object_get(w, "action"))) > 0);
			if (want && !strstr(message, want))
				fail_msg("%s: \"%s\" lacks \"%s\"", code, message, want);
			return w;
		}
	return NULL;
}

static const double apart_plain[5] = {1.0, 1.1, 1.2, 1.1, 1.0}, apart_better[5] = {2.0, 2.1, 2.2, 2.0, 2.1};

static void test_none(void **state)
{
	(void)state;
	struct aa_job_result *r = make_result(5, apart_plain, apart_better);
	json_t *w = warnings_of(r);
	if (json_array_size(w) != 0)
		fail_msg("warnings where nothing is wrong: %s", json_dumps(w, 0));
	json_decref(w);
	free_result(r);
}

static void test_reference(void **state)
{
	(void)state;
	struct aa_job_result *r = make_result(5, apart_plain, apart_better);
	/* MSE 13.0: 36.99 dB, under 40: not converged; better (36 dB) is within 3 dB of it, plain (31) is not */
	r->reference.frames[0].convergence_mse = 13.0;
	json_t *w = warnings_of(r);
	assert_non_null(find(w, "reference-not-converged", "its 8-sample image differs from its 16-sample image by 37.0 dB"));
	json_t *noise = find(w, "psnr-at-reference-noise", "better (36.0 dB)");
	assert_non_null(noise);
	assert_null(strstr(json_string_value(json_object_get(noise, "message")), "plain"));
	json_decref(w);
	/* MSE 0.5 (51 dB): converged, and no method within 3 dB of it */
	r->reference.frames[0].convergence_mse = 0.5;
	w = warnings_of(r);
	assert_null(find(w, "reference-not-converged", NULL));
	assert_null(find(w, "psnr-at-reference-noise", NULL));
	json_decref(w);
	/* "auto" stopped at its cap short of the target */
	r->reference.auto_samples = true;
	r->reference.target_psnr = 60;
	r->reference.frames[0].samples = 16;
	r->reference.frames[0].convergence_psnr = 51;
	w = warnings_of(r);
	assert_non_null(find(w, "reference-capped", "1 frame of the reference reached reference.max_samples (16) before "
						     "the target of 60.0 dB"));
	json_decref(w);
	free_result(r);
}

static void test_timing(void **state)
{
	(void)state;
	/* one render each: not ranked, whatever the times */
	struct aa_job_result *r = make_result(1, apart_plain, apart_better);
	json_t *w = warnings_of(r);
	assert_non_null(find(w, "too-few-timed-renders", "n=1: 1 frame x timing.repeat 1"));
	assert_null(find(w, "timing-spread", NULL));
	json_decref(w);
	free_result(r);
	/* plain's p90 (1.5 + 0.6 x 0.1 = 1.56) reaches better's p10 (1.5 + 0.4 x 0 = 1.5): a tie in cost */
	static const double a[5] = {1.0, 1.1, 1.2, 1.5, 1.6}, b[5] = {1.5, 1.5, 2.0, 2.1, 2.2};
	r = make_result(5, a, b);
	w = warnings_of(r);
	assert_null(find(w, "too-few-timed-renders", NULL));
	assert_non_null(find(w, "timing-spread", "plain 1.04-1.56 ms and better 1.50-2.16 ms"));
	json_decref(w);
	r->timestamp_period_ns = NAN;
	w = warnings_of(r);
	assert_non_null(find(w, "no-gpu-timestamps", NULL));
	json_decref(w);
	free_result(r);
}

static void test_outputs_and_scene(void **state)
{
	(void)state;
	struct aa_job_result *r = make_result(5, apart_plain, apart_better);
	r->methods[1].frames[0].nonfinite = 7;
	r->reference.frames[0].nonfinite = 3;
	r->warning_count = 1;
	snprintf(r->warnings[0], sizeof r->warnings[0], "material <glass> approximated");
	r->warnings_dropped = 4;
	json_t *w = warnings_of(r);
	assert_non_null(find(w, "nonfinite-output", "better wrote 7 NaN or Inf values"));
	assert_non_null(find(w, "reference-nonfinite", "wrote 3 NaN or Inf values"));
	assert_non_null(find(w, "scene", "material <glass> approximated"));
	assert_non_null(find(w, "scene-warnings-capped", "... and 4 more scene warnings"));
	json_decref(w);
	free_result(r);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_none),
		cmocka_unit_test(test_reference),
		cmocka_unit_test(test_timing),
		cmocka_unit_test(test_outputs_and_scene),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
