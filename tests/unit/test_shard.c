/* Shards without a GPU: "I/N" and its errors, the frame ranges (every frame in exactly one shard, in
 * order, balanced), a shard's job (warm-up clamped to the frames before it, the method order's ordinal),
 * shard.warmup in the job (parse, canonical form, defaults per method), and a results document read back
 * exactly as written. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "results/results.h"
#include "compare/shard_merge.h"
#include "run/shard.h"
#include "run/job_spec.h"

static int parse(const char *text, struct aa_job_spec *spec, struct aa_error *err)
{
	json_error_t jerr;
	json_t *j = json_loads(text, 0, &jerr);
	if (!j)
		fail_msg("test JSON does not parse: %s: %s", text, jerr.text);
	memset(err, 0, sizeof *err);
	int rc = aa_job_spec_from_json(j, spec, err);
	json_decref(j);
	return rc;
}

static void test_parse(void **state)
{
	(void)state;
	struct aa_error err = {0};
	int i = -1, n = -1;
	assert_int_equal(aa_shard_parse("0/4", &i, &n, &err), 0);
	assert_int_equal(i, 0);
	assert_int_equal(n, 4);
	assert_int_equal(aa_shard_parse("3/4", &i, &n, &err), 0);
	assert_int_equal(i, 3);
	const char *bad[] = {"", "4", "4/4", "-1/4", "1/0", "a/4", "1/4x", "1/", "/4", "1 /4", "0/10001"};
	for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
		memset(&err, 0, sizeof err);
		assert_int_equal(aa_shard_parse(bad[k], &i, &n, &err), -1);
		assert_string_equal(err.path, "shard");
		assert_true(err.message[0] != '\0');
	}
	aa_shard_parse("4/4", &i, &n, &err);
	assert_non_null(strstr(err.message, "valid: 0 to 3"));
	aa_shard_parse("0/10001", &i, &n, &err);
	assert_int_equal(err.code, AA_ERR_LIMIT);
}

/* Every frame in exactly one shard, the shards in order and contiguous, sizes differing by one at most. */
static void test_ranges(void **state)
{
	(void)state;
	for (int frames = 1; frames <= 40; frames++)
		for (int count = 1; count <= frames; count++) {
			int next = 0, smallest = frames, largest = 0;
			for (int s = 0; s < count; s++) {
				int b, e;
				aa_shard_range(frames, s, count, &b, &e);
				assert_int_equal(b, next);
				assert_true(e > b);
				next = e;
				smallest = e - b < smallest ? e - b : smallest;
				largest = e - b > largest ? e - b : largest;
			}
			assert_int_equal(next, frames);
			assert_true(largest - smallest <= 1);
		}
	int b, e;
	aa_shard_range(32, 2, 4, &b, &e);
	assert_int_equal(b, 16);
	assert_int_equal(e, 24);
	aa_shard_range(10, 0, 4, &b, &e); /* 3 3 2 2 */
	assert_int_equal(e - b, 3);
	aa_shard_range(10, 3, 4, &b, &e);
	assert_int_equal(b, 8);
	assert_int_equal(e, 10);
}

static void test_warmup_defaults(void **state)
{
	(void)state;
	struct aa_job_spec spec;
	struct aa_error err;
	assert_int_equal(parse("{\"methods\": [\"none\", \"fxaa\", \"ssaa:4\"]}", &spec, &err), 0);
	assert_int_equal(aa_job_shard_warmup(&spec), 0); /* no history: nothing to warm up */
	assert_int_equal(parse("{\"methods\": [\"none\", \"taa\", \"t2msaa\"]}", &spec, &err), 0);
	/* the largest of the methods' */
	assert_int_equal(aa_job_shard_warmup(&spec),
			 AA_TAA_SHARD_WARMUP > AA_T2MSAA_SHARD_WARMUP ? AA_TAA_SHARD_WARMUP : AA_T2MSAA_SHARD_WARMUP);
	assert_int_equal(parse("{\"methods\": [\"taa\", \"fxaa\"]}", &spec, &err), 0);
	assert_int_equal(aa_job_shard_warmup(&spec), AA_TAA_SHARD_WARMUP);
	assert_int_equal(parse("{\"methods\": [\"t2msaa\"]}", &spec, &err), 0);
	assert_int_equal(aa_job_shard_warmup(&spec), AA_T2MSAA_SHARD_WARMUP);
	assert_int_equal(parse("{\"methods\": [\"asaa\"]}", &spec, &err), 0);
	assert_int_equal(aa_job_shard_warmup(&spec), AA_ASAA_SHARD_WARMUP);
	assert_int_equal(parse("{\"methods\": [\"taa\"], \"shard\": {\"warmup\": 3}}", &spec, &err), 0);
	assert_int_equal(aa_job_shard_warmup(&spec), 3); /* the job's own */
	assert_int_equal(parse("{\"methods\": [\"taa\"], \"shard\": {\"warmup\": 0}}", &spec, &err), 0);
	assert_int_equal(aa_job_shard_warmup(&spec), 0);
}

static void test_warmup_field(void **state)
{
	(void)state;
	struct aa_job_spec spec;
	struct aa_error err;
	assert_int_equal(parse("{\"shard\": {\"warmup\": -1}}", &spec, &err), -1);
	assert_string_equal(err.path, "shard.warmup");
	assert_int_equal(parse("{\"shard\": {\"warmup\": 1001}}", &spec, &err), -1);
	assert_string_equal(err.path, "shard.warmup");
	assert_int_equal(parse("{\"shard\": {\"warm\": 1}}", &spec, &err), -1);
	assert_string_equal(err.path, "shard.warm");
	assert_int_equal(parse("{\"shard\": 4}", &spec, &err), -1);
	assert_string_equal(err.path, "shard");
	/* canonical form: written when given, and parsed back the same; absent otherwise */
	assert_int_equal(parse("{\"shard\": {\"warmup\": 7}}", &spec, &err), 0);
	json_t *j = aa_job_spec_to_json(&spec);
	assert_int_equal(json_integer_value(json_object_get(json_object_get(j, "shard"), "warmup")), 7);
	struct aa_job_spec again;
	assert_int_equal(aa_job_spec_from_json(j, &again, &err), 0);
	assert_int_equal(again.shard_warmup, 7);
	json_decref(j);
	assert_int_equal(parse("{}", &spec, &err), 0);
	j = aa_job_spec_to_json(&spec);
	assert_null(json_object_get(j, "shard"));
	json_decref(j);
}

static void test_shard_job(void **state)
{
	(void)state;
	struct aa_job_spec whole, s;
	struct aa_error err;
	assert_int_equal(parse("{\"frames\": 32, \"first_frame\": 10, \"methods\": [\"none\", \"taa\"], "
			       "\"shard\": {\"warmup\": 12}}", &whole, &err), 0);
	assert_int_equal(aa_shard_job(&whole, 0, 4, &s, &err), 0);
	assert_int_equal(s.first_frame, 10);
	assert_int_equal(s.frames, 8);
	assert_int_equal(s.warmup_frames, 0); /* shard 0 starts where the unsharded run starts */
	assert_int_equal(s.order_ordinal, 0);
	assert_int_equal(aa_shard_job(&whole, 1, 4, &s, &err), 0);
	assert_int_equal(s.first_frame, 18);
	assert_int_equal(s.warmup_frames, 8); /* never before the job's first frame */
	assert_int_equal(s.order_ordinal, 8);
	assert_int_equal(aa_shard_job(&whole, 3, 4, &s, &err), 0);
	assert_int_equal(s.first_frame, 34);
	assert_int_equal(s.warmup_frames, 12);
	assert_int_equal(s.order_ordinal, 24);
	/* every shard of a job carries the whole job's hash, not its own frames' */
	char a[80], b[80];
	aa_job_hash(&whole, a, sizeof a);
	json_t *j = aa_shard_json(&whole, 3, 4);
	assert_string_equal(json_string_value(json_object_get(j, "job_hash")), a);
	assert_int_equal(json_integer_value(json_object_get(json_object_get(j, "frames"), "first")), 34);
	assert_int_equal(json_integer_value(json_object_get(j, "warmup")), 12);
	json_decref(j);
	aa_job_hash(&s, b, sizeof b);
	assert_string_not_equal(a, b);
	/* more shards than frames, and suites, are refused with the field named */
	assert_int_equal(aa_shard_job(&whole, 0, 33, &s, &err), -1);
	assert_string_equal(err.path, "shard");
	assert_non_null(strstr(err.message, "1 to 32"));
}

/* A suite splits by whole cases: contiguous, at least one each, cut nearest the cost's shares. */
static void test_suite_cases(void **state)
{
	(void)state;
	struct aa_job_spec suite, s;
	struct aa_error err;
	/* costs (frames x pixels) 1, 1, 1, 4, 1, 1, 1 (units of 10x10 x 10 frames) */
	assert_int_equal(parse("{\"suite\": \"x\", \"cases\": [{\"size\": \"10x10\", \"frames\": 10}, "
			       "{\"size\": \"10x10\", \"frames\": 10, \"path\": \"static\"}, {\"size\": \"10x10\", "
			       "\"frames\": 10, \"first_frame\": 5}, {\"size\": \"20x20\", \"frames\": 10}, {\"size\": "
			       "\"10x10\", \"frames\": 10, \"first_frame\": 9}, {\"size\": \"10x10\", \"frames\": 10, "
			       "\"first_frame\": 7}, {\"size\": \"10x10\", \"frames\": 10, \"first_frame\": 8}]}",
			       &suite, &err), 0);
	assert_int_equal(suite.case_count, 7);
	for (int count = 1; count <= 7; count++) {
		int next = 0;
		for (int i = 0; i < count; i++) {
			int b, e;
			aa_shard_cases(&suite, i, count, &b, &e);
			assert_int_equal(b, next);
			assert_true(e > b);
			next = e;
		}
		assert_int_equal(next, 7);
	}
	int b, e;
	aa_shard_cases(&suite, 0, 2, &b, &e); /* half of 10: after 3 cases (3) or 4 (7) are as near; the earlier */
	assert_int_equal(e, 3);
	aa_shard_cases(&suite, 1, 3, &b, &e); /* the large case alone in the middle */
	assert_int_equal(b, 3);
	assert_int_equal(e, 4);
	assert_int_equal(aa_shard_job(&suite, 1, 3, &s, &err), 0);
	assert_true(s.is_suite);
	assert_int_equal(s.case_count, 1);
	assert_int_equal(s.cases[0].width, 20);
	assert_int_equal(s.warmup_frames, 0);
	json_t *j = aa_shard_json(&suite, 1, 3);
	assert_int_equal(json_integer_value(json_object_get(json_object_get(j, "cases"), "first")), 3);
	assert_null(json_object_get(j, "frames"));
	json_decref(j);
	assert_int_equal(aa_shard_job(&suite, 0, 8, &s, &err), -1);
	assert_string_equal(err.path, "shard");
	assert_non_null(strstr(err.message, "valid: 1 to 7"));
}

/* A results document made here, written and read back: every per-frame value the writer stores comes
 * back as it was (the merge depends on it). */
static void test_read_back(void **state)
{
	(void)state;
	struct aa_job_spec spec;
	struct aa_error err;
	assert_int_equal(parse("{\"frames\": 3, \"first_frame\": 5, \"methods\": [\"none\", \"ssaa:4\"], "
			       "\"timing\": {\"repeat\": 2}}", &spec, &err), 0);
	struct aa_job_result r = {.spec = spec, .method_count = 2};
	snprintf(r.scene_name, sizeof r.scene_name, "thin-wires");
	snprintf(r.device_name, sizeof r.device_name, "llvmpipe");
	r.plan_count = 1;
	snprintf(r.plan[0].pass, sizeof r.plan[0].pass, "scene");
	r.plan[0].ran = true;
	r.reference.samples = 64;
	r.reference.frame_count = 3;
	r.reference.frames = calloc(3, sizeof *r.reference.frames);
	for (int k = 0; k < 3; k++)
		r.reference.frames[k] = (struct aa_reference_frame){.frame = 5 + k, .gpu_ms = 1.0 / 3 + k,
			.cpu_ms = 2, .convergence_mse = 0.1 * (k + 1), .convergence_psnr = NAN};
	for (int i = 0; i < 2; i++) {
		struct aa_method_result *m = &r.methods[i];
		snprintf(m->label, sizeof m->label, "%s", spec.methods[i].label);
		m->method = spec.methods[i].method;
		m->params = spec.methods[i].params;
		m->frame_count = 3;
		m->timed_count = 6;
		m->frames = calloc(3, sizeof *m->frames);
		m->timed = calloc(6, sizeof *m->timed);
		for (int k = 0; k < 3; k++) {
			struct aa_frame_result *f = &m->frames[k];
			f->frame = 5 + k;
			f->pass_count = 1;
			snprintf(f->passes[0].name, sizeof f->passes[0].name, "scene");
			f->passes[0].gpu_ms = f->gpu_ms = 0.7 + k / 7.0;
			f->metrics = (struct aa_metrics){.mse = 12.3456789012345678 * (k + 1) * (i + 1), .ssim = 0.9 - k / 9.0,
							 .flip_mean = 0.01 * k, .max_abs = 40, .snr = 20, .rmsd = 3};
			f->metrics.psnr = aa_psnr_from_mse(f->metrics.mse, 255.0);
			for (int t = 0; t < AA_THRESHOLD_COUNT; t++)
				f->metrics.exceed[t] = 1.0 / (t + k + 3);
			f->flicker = k ? 0.5 + k / 3.0 : NAN;
			for (int rep = 0; rep < 2; rep++)
				m->timed[k * 2 + rep] = (struct aa_timed_render){.ordinal = k, .repeat = rep, .position = (k + rep) % 2,
					.gpu_ms = 0.7 + k / 7.0 + rep, .cpu_ms = 1.1, .pass_count = 1, .pass_ms = {0.7 + k / 7.0 + rep}};
		}
	}
	json_t *doc = aa_results_to_json(&r);
	assert_non_null(doc);
	struct aa_job_result back;
	assert_int_equal(aa_results_from_json(doc, NULL, &back, &err), 0);
	assert_int_equal(back.spec.first_frame, 5);
	assert_int_equal(back.method_count, 2);
	for (int i = 0; i < 2; i++)
		for (int k = 0; k < 3; k++) {
			const struct aa_frame_result *a = &r.methods[i].frames[k], *b = &back.methods[i].frames[k];
			assert_int_equal(a->frame, b->frame);
			/* the document in memory holds the doubles themselves: exact */
			assert_true(a->metrics.mse == b->metrics.mse);
			assert_true(a->metrics.ssim == b->metrics.ssim);
			assert_true(a->gpu_ms == b->gpu_ms);
			assert_true(isnan(a->flicker) ? isnan(b->flicker) : a->flicker == b->flicker);
			assert_string_equal(b->passes[0].name, "scene");
			for (int rep = 0; rep < 2; rep++) {
				const struct aa_timed_render *ta = &r.methods[i].timed[k * 2 + rep], *tb = &back.methods[i].timed[k * 2 + rep];
				assert_int_equal(ta->ordinal, tb->ordinal);
				assert_int_equal(ta->position, tb->position);
				assert_true(ta->gpu_ms == tb->gpu_ms);
				assert_int_equal(tb->pass_count, 1);
				assert_true(ta->pass_ms[0] == tb->pass_ms[0]);
			}
		}
	for (int k = 0; k < 3; k++)
		assert_true(back.reference.frames[k].convergence_mse == r.reference.frames[k].convergence_mse);
	/* a method of another job is refused, naming it */
	json_t *m1 = json_array_get(json_object_get(doc, "methods"), 1);
	json_object_set_new(m1, "label", json_string("ssaa:16"));
	struct aa_job_result bad;
	assert_int_equal(aa_results_from_json(doc, NULL, &bad, &err), -1);
	assert_string_equal(err.path, "methods[1]");
	aa_job_result_free(&bad);
	json_decref(doc);
	aa_job_result_free(&back);
	aa_job_result_free(&r);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_parse),          cmocka_unit_test(test_ranges),
		cmocka_unit_test(test_warmup_defaults), cmocka_unit_test(test_warmup_field),
		cmocka_unit_test(test_shard_job),      cmocka_unit_test(test_suite_cases),
		cmocka_unit_test(test_read_back),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
