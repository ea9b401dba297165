/* Build-farm pieces without a GPU: SHA-256, suites in the job spec (matrix, cases, labels, baselines, the
 * job hash), the gate grammar, and aalab compare on results documents made here (pairing, exact
 * quality gates, the cost rule on synthetic timings, and refusals that name their field). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "run/farm.h"
#include "compare/compare.h"
#include "util/sha256.h"
#include "run/job_spec.h"

static json_t *load(const char *text)
{
	json_error_t jerr;
	json_t *j = json_loads(text, 0, &jerr);
	if (!j)
		fail_msg("test JSON does not parse: %s: %s", text, jerr.text);
	return j;
}

static int parse(const char *text, struct aa_job_spec *spec, struct aa_error *err)
{
	json_t *j = load(text);
	memset(err, 0, sizeof *err);
	int rc = aa_job_spec_from_json(j, spec, err);
	json_decref(j);
	return rc;
}

/* ----------------------------------------------------------------------------------------- SHA-256 */

static void test_sha256(void **state)
{
	(void)state;
	char hex[65];
	/* FIPS 180-4 examples: one block, two blocks, and the empty message */
	aa_sha256_hex("abc", 3, hex);
	assert_string_equal(hex, "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
	const char *two = "abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq";
	aa_sha256_hex(two, strlen(two), hex);
	assert_string_equal(hex, "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
	aa_sha256_hex("", 0, hex);
	assert_string_equal(hex, "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
	/* 55 and 56 bytes: the length still fits the last block, then no longer does */
	char a[1000];
	memset(a, 'a', sizeof a);
	aa_sha256_hex(a, 55, hex);
	assert_string_equal(hex, "9f4390f8d30c2dd92ec9f095b65e2b9ae9b0a925a5258e241c9f1e910f734318");
	aa_sha256_hex(a, 56, hex);
	assert_string_equal(hex, "b35439a4ac6f0948b6d6f9e3c6af0f5f590ce20f1bde7090ef7970686ec6738a");
}

/* ----------------------------------------------------------------------------------------- suites */

static void test_matrix(void **state)
{
	(void)state;
	struct aa_job_spec s;
	struct aa_error err;
	assert_int_equal(parse("{\"suite\": \"smoke\", \"scenes\": [\"thin-wires\", \"hard-edges\"], "
			       "\"paths\": [\"default\", \"static\"], \"sizes\": [\"64x36\", [96, 54]], \"frames\": 3, "
			       "\"labels\": {\"commit\": \"1a2b\", \"branch\": \"main\"}, \"methods\": [\"none\"]}",
			       &s, &err), 0);
	assert_true(s.is_suite);
	assert_int_equal(aa_job_case_count(&s), 8);
	char id[512];
	aa_case_id(&s, 0, id, sizeof id);
	assert_string_equal(id, "thin-wires/default/64x36");
	aa_case_id(&s, 3, id, sizeof id);
	assert_string_equal(id, "thin-wires/static/96x54"); /* scenes outermost, sizes innermost */
	aa_case_id(&s, 7, id, sizeof id);
	assert_string_equal(id, "hard-edges/static/96x54");
	aa_case_relpath(&s, 7, id, sizeof id);
	assert_string_equal(id, "cases/hard-edges_static_96x54");
	struct aa_job_spec one;
	aa_job_case(&s, 5, &one);
	assert_false(one.is_suite);
	assert_string_equal(one.scene, "hard-edges");
	assert_string_equal(one.path, "default");
	assert_int_equal(one.width, 96);
	assert_int_equal(one.frames, 3);
	assert_string_equal(aa_job_label(&one, "commit"), "1a2b");
	assert_null(aa_job_label(&one, "machine"));
	/* 8 cases of 3 frames, each frame a reference and the method's renders: timing.repeat "auto" gives
	 * 3 frames 2 repeats, so that the method has 6 >= 5 timed renders */
	assert_int_equal(one.timing_repeat, 2);
	assert_int_equal(aa_suite_total_units(&s), 8 * 3 * (1 + 2));

	/* the canonical form lists the cases and parses back to the same job */
	json_t *j = aa_job_spec_to_json(&s);
	assert_null(json_object_get(j, "scene"));
	assert_int_equal(json_array_size(json_object_get(j, "cases")), 8);
	assert_string_equal(json_string_value(json_object_get(j, "suite")), "smoke");
	struct aa_job_spec back;
	memset(&err, 0, sizeof err);
	assert_int_equal(aa_job_spec_from_json(j, &back, &err), 0);
	json_decref(j);
	assert_int_equal(back.case_count, 8);
	for (int i = 0; i < 8; i++) {
		char a[512], b[512];
		aa_case_id(&s, i, a, sizeof a);
		aa_case_id(&back, i, b, sizeof b);
		assert_string_equal(a, b);
	}
	assert_int_equal(back.label_count, 2);
	char h1[80], h2[80];
	aa_job_hash(&s, h1, sizeof h1);
	aa_job_hash(&back, h2, sizeof h2);
	assert_string_equal(h1, h2);
}

static void test_cases_and_hash(void **state)
{
	(void)state;
	struct aa_job_spec s, plain, other;
	struct aa_error err;
	assert_int_equal(parse("{\"scene\": \"thin-wires\", \"frames\": 4, \"cases\": [{\"size\": \"64x36\"}, "
			       "{\"scene\": \"moving-sphere\", \"first_frame\": 30, \"frames\": 2}], \"methods\": [\"none\"]}",
			       &s, &err), 0);
	char id[512];
	aa_case_id(&s, 0, id, sizeof id);
	assert_string_equal(id, "thin-wires/default/64x36");
	aa_case_id(&s, 1, id, sizeof id);
	assert_string_equal(id, "moving-sphere/default/640x360@30");
	assert_int_equal(s.cases[0].frames, 4); /* the job's keys are every case's defaults */
	assert_int_equal(s.cases[1].frames, 2);

	/* a plain job and a suite of that one case are the same work: the same hash, whatever the labels */
	assert_int_equal(parse("{\"scene\": \"thin-wires\", \"size\": \"64x36\", \"methods\": [\"none\"], "
			       "\"name\": \"a\"}", &plain, &err), 0);
	assert_int_equal(parse("{\"scenes\": [\"thin-wires\"], \"size\": \"64x36\", \"methods\": [\"none\"], "
			       "\"labels\": {\"commit\": \"x\"}, \"name\": \"b\", \"suite\": \"s\"}", &other, &err), 0);
	char h1[80], h2[80];
	aa_job_hash(&plain, h1, sizeof h1);
	aa_job_hash(&other, h2, sizeof h2);
	assert_string_equal(h1, h2);
	assert_int_equal(strlen(h1), 7 + 64);
	/* and any change of the work changes it */
	assert_int_equal(parse("{\"scene\": \"thin-wires\", \"size\": \"64x36\", \"methods\": [\"none\"], "
			       "\"timing\": {\"repeat\": 2}}", &other, &err), 0);
	aa_job_hash(&other, h2, sizeof h2);
	assert_string_not_equal(h1, h2);
}

struct bad_job {
	const char *json, *path, *words;
};

static void test_bad_suites(void **state)
{
	(void)state;
	static const struct bad_job bad[] = {
		{"{\"scene\": \"a\", \"scenes\": [\"b\"]}", "scenes", "not both"},
		{"{\"scenes\": []}", "scenes", "empty"},
		{"{\"scenes\": [\"thin-wires\", \"thin-wires\"]}", "scenes[1]", "same scene"},
		{"{\"scenes\": [\"../x\"]}", "scenes[0]", "neither a scene name"},
		{"{\"sizes\": [\"64x36\", \"-1x3\"]}", "sizes[1]", "not a size"},
		{"{\"size\": \"64x36\", \"sizes\": [\"64x36\"]}", "sizes", "not both"},
		{"{\"paths\": [\"default\", 3]}", "paths[1]", "expected a string"},
		{"{\"cases\": [{\"scene\": \"a\"}], \"scenes\": [\"b\"]}", "cases", "not both"},
		{"{\"cases\": [{\"colour\": 1}]}", "cases[0].colour", "unknown key"},
		{"{\"cases\": [{\"frames\": 0}]}", "cases[0].frames", "out of range"},
		{"{\"cases\": [{\"scene\": \"a\"}, {\"scene\": \"a\"}]}", "cases[1]", "same case"},
		{"{\"cases\": [{\"scene\": \"a.json\"}, {\"scene\": \"x/a.json\"}]}", "cases[1]", "image directory"},
		{"{\"cases\": [3]}", "cases[0]", "case object"},
		{"{\"labels\": {\"bad key\": \"x\"}}", "labels.bad key", "label key"},
		{"{\"labels\": {\"commit\": \"\"}}", "labels.commit", "empty value"},
		{"{\"labels\": {\"commit\": 3}}", "labels.commit", "expected a string"},
		{"{\"labels\": [\"commit=x\"]}", "labels", "expected an object"},
		{"{\"suite\": \"a b\"}", "suite", "not a suite name"},
		{"{\"baseline\": \"yesterday\"}", "baseline", "not a baseline"},
		{"{\"baseline\": \"latest:branch\"}", "baseline", "not a label"},
		{"{\"baseline\": \"latest:\"}", "baseline", "names no label"},
	};
	for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
		struct aa_job_spec s;
		struct aa_error err;
		if (parse(bad[i].json, &s, &err) == 0)
			fail_msg("accepted %s", bad[i].json);
		if (strcmp(err.path, bad[i].path) || !strstr(err.message, bad[i].words))
			fail_msg("%s: got \"%s: %s\", want path %s and \"%s\"", bad[i].json, err.path, err.message, bad[i].path,
				 bad[i].words);
	}
	/* a matrix larger than a suite may be */
	char big[4096] = "{\"scenes\": [";
	for (int i = 0; i < 9; i++)
		snprintf(big + strlen(big), sizeof big - strlen(big), "%s\"s%d\"", i ? ", " : "", i);
	strcat(big, "], \"sizes\": [\"1x1\", \"2x2\", \"3x3\", \"4x4\", \"5x5\", \"6x6\", \"7x7\", \"8x8\"]}");
	struct aa_job_spec s;
	struct aa_error err;
	assert_int_equal(parse(big, &s, &err), -1);
	assert_int_equal(err.code, AA_ERR_LIMIT);
	assert_string_equal(err.path, "scenes");
}

static void test_labels_and_baselines(void **state)
{
	(void)state;
	struct aa_label labels[AA_MAX_LABELS];
	int n = 0;
	struct aa_error err = {0};
	assert_int_equal(aa_label_parse("commit=1a2b", labels, &n, "label", &err), 0);
	assert_int_equal(aa_label_parse("build_url=https://ci/x?a=b", labels, &n, "label", &err), 0);
	assert_int_equal(aa_label_parse("commit=3c4d", labels, &n, "label", &err), 0); /* replaces */
	assert_int_equal(n, 2);
	assert_string_equal(labels[0].value, "3c4d");
	assert_string_equal(labels[1].value, "https://ci/x?a=b");
	assert_int_equal(aa_label_parse("=x", labels, &n, "label", &err), -1);
	assert_string_equal(err.path, "label");
	assert_int_equal(aa_label_parse("nokey", labels, &n, "label", &err), -1);

	struct aa_baseline b;
	assert_int_equal(aa_baseline_parse("000042", &b, "baseline", &err), 0);
	assert_false(b.latest);
	assert_string_equal(b.job, "000042");
	assert_int_equal(aa_baseline_parse("latest:branch=main,machine=ci-3", &b, "baseline", &err), 0);
	assert_true(b.latest);
	assert_int_equal(b.label_count, 2);
	assert_string_equal(b.labels[1].key, "machine");
	assert_int_equal(aa_baseline_parse("latest", &b, "baseline", &err), 0);
	assert_int_equal(b.label_count, 0);
}

/* ----------------------------------------------------------------------------------------- gates */

static void test_gates(void **state)
{
	(void)state;
	struct aa_gate g;
	struct aa_error err = {0};
	assert_int_equal(aa_gate_parse("psnr < -0.1", &g, "--fail-if", &err), 0);
	assert_int_equal(g.metric, AA_GATE_PSNR);
	assert_int_equal(g.op, AA_GATE_LT);
	assert_true(fabs(g.threshold + 0.1) < 1e-12);
	assert_false(g.percent);
	assert_int_equal(aa_gate_parse("  gpu_ms>=+10 % ", &g, "--fail-if", &err), 0);
	assert_int_equal(g.op, AA_GATE_GE);
	assert_true(g.percent);
	assert_string_equal(g.text, "gpu_ms >= +10%");
	assert_int_equal(aa_gate_parse("memory_bytes > 0", &g, "--fail-if", &err), 0);
	assert_int_equal(g.metric, AA_GATE_MEMORY);
	assert_string_equal(g.text, "memory > +0");
	static const char *const bad[] = {"psnr", "psnr -0.1", "psnr < ", "speed > 1", "psnr < nan", "psnr < 0x10",
					  "psnr < 1e3", "psnr < 1%%", "psnr = 1", "psnr < 1 dB", "", "psnr << 1"};
	for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
		memset(&err, 0, sizeof err);
		if (aa_gate_parse(bad[i], &g, "--fail-if", &err) == 0)
			fail_msg("accepted gate \"%s\"", bad[i]);
		assert_string_equal(err.path, "--fail-if");
		assert_non_null(strstr(err.message, "is not a gate"));
	}
	struct aa_gate set[AA_MAX_GATES];
	int n = aa_gates_default(set, AA_MAX_GATES);
	assert_int_equal(n, 6);
	assert_string_equal(set[4].text, "gpu_ms > +50%");
}

/* ----------------------------------------------------------------------------------------- compare */

/* A method of a results document: quality numbers and timed renders drawn around `ms` with noise that
 * only adds time, as on a shared machine (a fixed seed per method). */
static json_t *method_doc(const char *label, const char *name, double psnr, double ssim, double ms, int renders,
			  unsigned seed)
{
	json_t *timed = json_array();
	uint64_t x = 0x9e3779b97f4a7c15ULL * (seed + 1);
	for (int i = 0; i < renders; i++) {
		x ^= x << 13, x ^= x >> 7, x ^= x << 17;
		double u = (double)(x % 10000) / 10000.0;
		/* most renders within 3% of the cost, one in four delayed by up to 3x */
		double t = ms * (1 + 0.03 * u) + (i % 4 == 3 ? ms * 3 * u : 0);
		json_array_append_new(timed, json_pack("{s:f, s:f}", "gpu_ms", t, "cpu_ms", t + 0.1));
	}
	return json_pack("{s:s, s:s, s:{s:i}, s:{s:{s:f, s:b}, s:{s:f}, s:{s:f}, s:{s:f}}, s:i, s:o}", "label", label,
			 "name", name, "params", "preset", 12, "metrics", "psnr", "mean", psnr, "identical", 0, "ssim",
			 "mean", ssim, "flip", "mean", 0.05, "flicker", "mean", 1.5, "memory_bytes", 1000000,
			 "timed_renders", timed);
}

/* A suite's results with the given cases; each case has four methods. slow_factor multiplies fxaa's
 * renders; fxaa_label and fxaa_psnr stand in for fxaa. */
static json_t *suite_doc(const char *const *ids, int count, unsigned seed, const char *fxaa_label, double fxaa_psnr,
			 double slow_factor, double machine)
{
	json_t *cases = json_array();
	for (int c = 0; c < count; c++) {
		json_t *methods = json_array();
		json_array_append_new(methods, method_doc("none", "none", 18.0, 0.80, 1.0 * machine, 15, seed + 10 * c));
		json_array_append_new(methods, method_doc("ssaa:4", "ssaa", 21.0, 0.90, 4.0 * machine, 15, seed + 10 * c + 1));
		json_array_append_new(methods, method_doc(fxaa_label, "fxaa", fxaa_psnr, 0.85, 2.0 * machine * slow_factor, 15,
							  seed + 10 * c + 2));
		json_array_append_new(methods, method_doc("smaa", "smaa", 20.0, 0.86, 2.5 * machine, 15, seed + 10 * c + 3));
		json_array_append_new(cases, json_pack("{s:s, s:i, s:o}", "id", ids[c], "frames", 3, "methods", methods));
	}
	return json_pack("{s:i, s:s, s:{s:s}, s:o}", "version", 1, "suite", "t", "labels", "commit", "x", "cases", cases);
}

static const char *const two_cases[] = {"thin-wires/default/64x36", "cutout-fence/default/64x36"};

static json_t *compare(json_t *a, json_t *b, const char *const *gates, bool allow_missing, struct aa_error *err)
{
	struct aa_compare_options o = {.allow_missing = allow_missing};
	for (int i = 0; gates && gates[i]; i++)
		assert_int_equal(aa_gate_parse(gates[i], &o.gates[o.gate_count++], "", err), 0);
	memset(err, 0, sizeof *err);
	json_t *c = aa_compare_results(a, b, &o, err);
	json_decref(a);
	json_decref(b);
	return c;
}

static json_t *gate_of(json_t *cmp, int case_index, const char *label, const char *metric)
{
	size_t i, k;
	json_t *m, *g;
	json_array_foreach(json_object_get(json_array_get(json_object_get(cmp, "cases"), (size_t)case_index), "methods"), i, m)
		if (!strcmp(json_string_value(json_object_get(m, "label")), label))
			json_array_foreach(json_object_get(m, "gates"), k, g)
				if (!strcmp(json_string_value(json_object_get(g, "metric")), metric))
					return g;
	fail_msg("no %s gate for %s", metric, label);
	return NULL;
}

static void test_compare_self_and_noise(void **state)
{
	(void)state;
	struct aa_error err;
	json_t *cmp = compare(suite_doc(two_cases, 2, 1, "fxaa", 20.0, 1, 1), suite_doc(two_cases, 2, 1, "fxaa", 20.0, 1, 1),
			      NULL, false, &err);
	assert_non_null(cmp);
	assert_int_equal(aa_compare_tripped(cmp), 0);
	json_t *counts = json_object_get(cmp, "counts");
	assert_int_equal(json_integer_value(json_object_get(counts, "gates")), 2 * 4 * 6);
	assert_int_equal(json_integer_value(json_object_get(counts, "held")), 2 * 4 * 6);
	json_decref(cmp);
	/* other noise, and a machine 60% slower for every method: the factor takes it, nothing trips */
	cmp = compare(suite_doc(two_cases, 2, 1, "fxaa", 20.0, 1, 1), suite_doc(two_cases, 2, 7, "fxaa", 20.0, 1, 1.6),
		      NULL, false, &err);
	assert_int_equal(aa_compare_tripped(cmp), 0);
	double factor = json_real_value(json_object_get(json_object_get(json_object_get(
		json_array_get(json_object_get(cmp, "cases"), 0), "machine_factor"), "gpu_ms"), "value"));
	assert_true(factor > 1.5 && factor < 1.7);
	json_decref(cmp);
	/* judged as measured (--raw-cost), the same slower machine trips every cost gate */
	struct aa_compare_options o = {.raw_cost = true};
	json_t *base = suite_doc(two_cases, 2, 1, "fxaa", 20.0, 1, 1), *slow = suite_doc(two_cases, 2, 7, "fxaa", 20.0, 1, 1.6);
	cmp = aa_compare_results(base, slow, &o, &err);
	assert_int_equal(aa_compare_tripped(cmp), 1);
	assert_string_equal(json_string_value(json_object_get(gate_of(cmp, 0, "none", "gpu_ms"), "result")), "tripped");
	json_decref(cmp);
	json_decref(base);
	json_decref(slow);
}

static void test_compare_slowdown(void **state)
{
	(void)state;
	struct aa_error err;
	/* fxaa twice as slow in NEW, with other noise: its gate trips in both cases, no other method's */
	json_t *cmp = compare(suite_doc(two_cases, 2, 1, "fxaa", 20.0, 1, 1), suite_doc(two_cases, 2, 5, "fxaa", 20.0, 2, 1),
			      NULL, false, &err);
	assert_int_equal(aa_compare_tripped(cmp), 1);
	for (int c = 0; c < 2; c++) {
		json_t *g = gate_of(cmp, c, "fxaa", "gpu_ms");
		assert_string_equal(json_string_value(json_object_get(g, "result")), "tripped");
		double lo = json_real_value(json_array_get(json_object_get(g, "interval"), 0));
		assert_true(lo > 50 && lo < 130);
		assert_string_equal(json_string_value(json_object_get(gate_of(cmp, c, "smaa", "gpu_ms"), "result")), "held");
	}
	assert_int_equal(json_integer_value(json_object_get(json_object_get(cmp, "counts"), "tripped")), 2);
	json_decref(cmp);
	/* fewer than 5 renders: a cost gate cannot tell, and says so */
	json_t *a = suite_doc(two_cases, 1, 1, "fxaa", 20.0, 1, 1), *b = suite_doc(two_cases, 1, 1, "fxaa", 20.0, 3, 1);
	json_t *timed = json_object_get(json_array_get(json_object_get(json_array_get(json_object_get(b, "cases"), 0),
								      "methods"), 2), "timed_renders");
	while (json_array_size(timed) > 4)
		json_array_remove(timed, 0);
	cmp = compare(a, b, (const char *const[]){"gpu_ms > +10%", NULL}, false, &err);
	json_t *g = gate_of(cmp, 0, "fxaa", "gpu_ms");
	assert_string_equal(json_string_value(json_object_get(g, "result")), "unknown");
	assert_int_equal(aa_compare_tripped(cmp), 0);
	json_decref(cmp);
}

/* A change whose interval straddles the gate: its upper end is past +50%, its lower end is not, so the
 * gate holds; a gate below the lower end trips. */
static void test_compare_interval(void **state)
{
	(void)state;
	struct aa_error err;
	json_t *a = suite_doc(two_cases, 1, 1, "fxaa", 20.0, 1, 1), *b = suite_doc(two_cases, 1, 1, "fxaa", 20.0, 1, 1);
	json_t *timed = json_object_get(json_array_get(json_object_get(json_array_get(json_object_get(b, "cases"), 0),
								      "methods"), 2), "timed_renders");
	for (size_t i = 0; i < json_array_size(timed); i++) { /* fxaa's renders spread from 2.2 to 9 ms */
		double t = 2.2 + 6.8 * (double)((i * 7) % 15) / 14.0;
		json_object_set_new(json_array_get(timed, i), "gpu_ms", json_real(t));
	}
	json_t *cmp = compare(a, b, (const char *const[]){"gpu_ms > +50%", "gpu_ms > +5%", "gpu_ms < -50%", NULL},
			      false, &err);
	json_t *held = gate_of(cmp, 0, "fxaa", "gpu_ms");
	json_t *gates = json_object_get(json_array_get(json_object_get(json_array_get(json_object_get(cmp, "cases"), 0),
									 "methods"), 2), "gates");
	double change = json_real_value(json_object_get(held, "change"));
	double lo = json_real_value(json_array_get(json_object_get(held, "interval"), 0));
	double hi = json_real_value(json_array_get(json_object_get(held, "interval"), 1));
	if (!(change > 5 && lo > 5 && lo < 50 && hi > 50))
		fail_msg("the test needs an interval across +50%%: change %.1f, interval %.1f to %.1f", change, lo, hi);
	assert_string_equal(json_string_value(json_object_get(held, "result")), "held");
	assert_string_equal(json_string_value(json_object_get(json_array_get(gates, 1), "result")), "tripped");
	assert_string_equal(json_string_value(json_object_get(json_array_get(gates, 2), "result")), "held");
	json_decref(cmp);
}

static void test_compare_pairing_and_quality(void **state)
{
	(void)state;
	struct aa_error err;
	/* a label in NEW only pairs with the one fxaa of BASE; its lower PSNR trips the gate, naming the case */
	json_t *b = suite_doc(two_cases, 2, 1, "fxaa:preset=10,edge_threshold=0.333", 19.5, 1, 1);
	json_object_set_new(json_object_get(json_array_get(json_object_get(json_array_get(json_object_get(b, "cases"), 1),
									  "methods"), 2), "params"), "preset", json_integer(10));
	json_t *cmp = compare(suite_doc(two_cases, 2, 1, "fxaa", 20.0, 1, 1), b, NULL, false, &err);
	assert_int_equal(aa_compare_tripped(cmp), 1);
	json_t *t = json_array_get(json_object_get(cmp, "tripped"), 0);
	assert_string_equal(json_string_value(json_object_get(t, "case")), two_cases[0]);
	assert_string_equal(json_string_value(json_object_get(t, "method")), "fxaa:preset=10,edge_threshold=0.333");
	assert_string_equal(json_string_value(json_object_get(t, "gate")), "psnr < -0.1");
	json_t *m = json_array_get(json_object_get(json_array_get(json_object_get(cmp, "cases"), 1), "methods"), 2);
	assert_string_equal(json_string_value(json_object_get(m, "base_label")), "fxaa");
	assert_string_equal(json_string_value(json_object_get(m, "paired_by")), "name");
	json_t *pc = json_array_get(json_object_get(m, "params_changed"), 0);
	assert_string_equal(json_string_value(json_object_get(pc, "param")), "preset");
	assert_int_equal(json_integer_value(json_object_get(pc, "new")), 10);
	/* the three outputs say the same */
	char *text = NULL;
	size_t size = 0;
	FILE *f = open_memstream(&text, &size);
	assert_int_equal(aa_compare_write_junit(cmp, f), 0);
	fclose(f);
	assert_non_null(strstr(text, "tests=\"48\" failures=\"2\""));
	assert_non_null(strstr(text, "<failure type=\"gate\""));
	free(text);
	f = open_memstream(&text, &size);
	assert_int_equal(aa_compare_write_markdown(cmp, f), 0);
	fclose(f);
	assert_non_null(strstr(text, "**FAILED**"));
	assert_non_null(strstr(text, "| thin-wires/default/64x36 | fxaa:preset=10,edge_threshold=0.333 | `psnr < -0.1` |"));
	free(text);
	json_decref(cmp);

	/* a gate as strict as the change trips; one just past it holds */
	cmp = compare(suite_doc(two_cases, 1, 1, "fxaa", 20.0, 1, 1), suite_doc(two_cases, 1, 1, "fxaa", 19.75, 1, 1),
		      (const char *const[]){"psnr <= -0.25", "psnr < -0.26", "psnr < -1%", NULL}, false, &err);
	json_t *gates = json_object_get(json_array_get(json_object_get(json_array_get(json_object_get(cmp, "cases"), 0),
									 "methods"), 2), "gates");
	assert_string_equal(json_string_value(json_object_get(json_array_get(gates, 0), "result")), "tripped");
	assert_string_equal(json_string_value(json_object_get(json_array_get(gates, 1), "result")), "held");
	assert_string_equal(json_string_value(json_object_get(json_array_get(gates, 2), "result")), "tripped");
	json_decref(cmp);
}

static void test_compare_refusals(void **state)
{
	(void)state;
	struct aa_error err;
	/* runs that do not share their cases: refused, naming what is missing where */
	static const char *const other[] = {"thin-wires/default/64x36", "hairball/default/64x36"};
	json_t *cmp = compare(suite_doc(two_cases, 2, 1, "fxaa", 20, 1, 1), suite_doc(other, 2, 1, "fxaa", 20, 1, 1), NULL,
			      false, &err);
	assert_null(cmp);
	assert_int_equal(err.code, AA_ERR_INVALID);
	assert_non_null(strstr(err.message, "missing from NEW: cutout-fence/default/64x36"));
	assert_non_null(strstr(err.message, "missing from BASE: hairball/default/64x36"));
	/* --allow-missing compares the one they share */
	cmp = compare(suite_doc(two_cases, 2, 1, "fxaa", 20, 1, 1), suite_doc(other, 2, 1, "fxaa", 20, 1, 1), NULL, true,
		      &err);
	assert_non_null(cmp);
	assert_int_equal(json_array_size(json_object_get(cmp, "cases")), 1);
	json_decref(cmp);
	/* documents that are not results.json: the error names the run and the field */
	static const struct {
		const char *doc, *path;
	} bad[] = {
		{"[1]", "NEW"},
		{"{\"cases\": 3}", "NEW cases"},
		{"{\"cases\": [{\"id\": \"a\", \"methods\": [{\"label\": \"x\", \"metrics\": {\"psnr\": {\"mean\": \"high\"}}}]}]}",
		 "NEW cases[0].methods[0].metrics.psnr.mean"},
		{"{\"cases\": [{\"id\": \"a\", \"methods\": [{\"name\": \"x\"}]}]}", "NEW cases[0].methods[0].label"},
		{"{\"cases\": [{\"methods\": []}]}", "NEW cases[0].id"},
		{"{\"cases\": [{\"id\": \"a\", \"methods\": [{\"label\": \"x\", \"timed_renders\": [{\"gpu_ms\": true}]}]}]}",
		 "NEW cases[0].methods[0].timed_renders[0].gpu_ms"},
		{"{\"methods\": []}", "NEW job"},
		{"{\"cases\": [{\"id\": \"a\", \"methods\": []}, {\"id\": \"a\", \"methods\": []}]}", "NEW cases[1]"},
	};
	for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
		cmp = compare(suite_doc(two_cases, 1, 1, "fxaa", 20, 1, 1), load(bad[i].doc), NULL, false, &err);
		if (cmp || err.code != AA_ERR_INVALID || strcmp(err.path, bad[i].path))
			fail_msg("%s: got path \"%s\" (%s), want \"%s\"", bad[i].doc, err.path, err.message, bad[i].path);
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_sha256),
		cmocka_unit_test(test_matrix),
		cmocka_unit_test(test_cases_and_hash),
		cmocka_unit_test(test_bad_suites),
		cmocka_unit_test(test_labels_and_baselines),
		cmocka_unit_test(test_gates),
		cmocka_unit_test(test_compare_self_and_noise),
		cmocka_unit_test(test_compare_slowdown),
		cmocka_unit_test(test_compare_interval),
		cmocka_unit_test(test_compare_pairing_and_quality),
		cmocka_unit_test(test_compare_refusals),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
