/* The arithmetic of `aalab compare` against answers worked out by hand: every number the comparison
 * prints (BASE -> NEW, the raw change and its percent against BASE, the judged change over the machine
 * factor, its interval, each gate's verdict) for one case of two methods (no machine factor), three
 * methods (a factor), times spread over five renders (an interval with known bounds), gates exactly at
 * their threshold; and the refusals: a case twice in one run, cases missing from one run, methods that
 * pair ambiguously, and runs where nothing pairs or no gate judges (exit 2, never "held"). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "compare/compare.h"

/* A method: label, PSNR, memory in bytes, and its timed renders' GPU ms (CPU ms the same). */
static json_t *method(const char *label, double psnr, double memory, const double *ms, int n)
{
	json_t *timed = json_array();
	for (int i = 0; i < n; i++)
		json_array_append_new(timed, json_pack("{s:f, s:f}", "gpu_ms", ms[i], "cpu_ms", ms[i]));
	return json_pack("{s:s, s:f, s:{s:{s:f, s:b}, s:{s:f}, s:{s:f}, s:{s:n}}, s:o}", "label", label, "memory_bytes",
			 memory, "metrics", "psnr", "mean", psnr, "identical", 0, "ssim", "mean", 0.9, "flip", "mean",
			 0.05, "flicker", "mean", "timed_renders", timed);
}

/* A job's results.json of one case, scene/default/64x36, with these methods (taken). */
static json_t *job(const char *scene, json_t *methods)
{
	return json_pack("{s:{s:s, s:s, s:s, s:i}, s:i, s:o, s:{s:s}}", "job", "scene", scene, "path", "default", "size",
			 "64x36", "first_frame", 0, "frames", 1, "methods", methods, "verdict", "headline",
			 "front: a and b");
}

static json_t *compare(json_t *base, json_t *new_run, const char *const *gates, struct aa_error *err)
{
	struct aa_compare_options o = {.base_source = "BASEDIR", .new_source = "NEWDIR"};
	for (int i = 0; gates && gates[i]; i++)
		assert_int_equal(aa_gate_parse(gates[i], &o.gates[o.gate_count++], "--fail-if", NULL), 0);
	*err = (struct aa_error){0};
	json_t *c = aa_compare_results(base, new_run, &o, err);
	json_decref(base);
	json_decref(new_run);
	return c;
}

static json_t *pair_of(json_t *cmp, int method)
{
	return json_array_get(json_object_get(json_array_get(json_object_get(cmp, "cases"), 0), "methods"), (size_t)method);
}

static double num_at(json_t *o, const char *a, const char *b)
{
	json_t *v = json_object_get(b ? json_object_get(o, a) : o, b ? b : a);
	if (!json_is_number(v))
		fail_msg("%s.%s is not a number", a, b ? b : "");
	return json_number_value(v);
}

/* The result of the gate named text on a method of the comparison. */
static const char *gate_result(json_t *pair, const char *text)
{
	size_t i;
	json_t *g;
	json_array_foreach(json_object_get(pair, "gates"), i, g)
		if (!strcmp(json_string_value(json_object_get(g, "gate")), text))
			return json_string_value(json_object_get(g, "result"));
	fail_msg("no gate %s", text);
	return NULL;
}

static char *table_of(json_t *cmp)
{
	char *buf = NULL;
	size_t size = 0;
	FILE *o = open_memstream(&buf, &size);
	aa_compare_print_table(cmp, o);
	fclose(o);
	return buf;
}

static void assert_has(const char *text, const char *want)
{
	if (!strstr(text, want))
		fail_msg("missing \"%s\" in:\n%s", want, text);
}

static const double ms10[5] = {10, 10, 10, 10, 10}, ms15[5] = {15, 15, 15, 15, 15}, ms20[5] = {20, 20, 20, 20, 20};

/* One case, two timed methods: too few for a machine factor, so a doubled method is judged +100%,
 * and every percent is of BASE: +100% from 10 to 20 ms (not +50%, which is of NEW), memory 100 -> 150
 * bytes +50% (not +33%), PSNR 30 -> 29.5 -1.667% (not -1.695%). */
static void test_two_methods(void **state)
{
	(void)state;
	struct aa_error err;
	json_t *cmp = compare(job("s", json_pack("[o, o]", method("a", 30, 100, ms10, 5), method("b", 40, 100, ms10, 5))),
			      job("s", json_pack("[o, o]", method("a", 29.5, 150, ms20, 5), method("b", 40, 100, ms10, 5))),
			      (const char *const[]){"gpu_ms > +50%", "memory > +40%", "psnr < -0.1", "psnr < -1.68%", NULL}, &err);
	assert_non_null(cmp);
	json_t *a = pair_of(cmp, 0), *b = pair_of(cmp, 1);
	json_t *gpu = json_object_get(json_object_get(a, "metrics"), "gpu_ms");
	assert_float_equal(num_at(gpu, "base", "median"), 10, 1e-12);
	assert_float_equal(num_at(gpu, "new", "median"), 20, 1e-12);
	assert_float_equal(num_at(gpu, "change_median_pct", NULL), 100, 1e-9);
	assert_float_equal(num_at(gpu, "change", NULL), 10, 1e-12);       /* p10: 10 -> 20 ms */
	assert_float_equal(num_at(gpu, "change_pct", NULL), 100, 1e-9);
	assert_float_equal(num_at(gpu, "machine_factor", NULL), 1, 0);   /* two methods: no factor */
	assert_float_equal(num_at(gpu, "judged_pct", NULL), 100, 1e-9);
	assert_float_equal(json_number_value(json_array_get(json_object_get(gpu, "interval_pct"), 0)), 100, 1e-9);
	assert_float_equal(json_number_value(json_array_get(json_object_get(gpu, "interval_pct"), 1)), 100, 1e-9);
	json_t *mem = json_object_get(json_object_get(a, "metrics"), "memory_bytes");
	assert_float_equal(num_at(mem, "change_pct", NULL), 50, 1e-9);
	json_t *psnr = json_object_get(json_object_get(a, "metrics"), "psnr");
	assert_float_equal(num_at(psnr, "change", NULL), -0.5, 1e-12);
	assert_float_equal(num_at(psnr, "change_pct", NULL), -100.0 * 0.5 / 30, 1e-9);
	assert_string_equal(gate_result(a, "gpu_ms > +50%"), "tripped");
	assert_string_equal(gate_result(a, "memory > +40%"), "tripped");
	assert_string_equal(gate_result(a, "psnr < -0.1"), "tripped");
	assert_string_equal(gate_result(a, "psnr < -1.68%"), "held"); /* -1.667% of BASE (of NEW: -1.695%) */
	assert_string_equal(gate_result(b, "gpu_ms > +50%"), "held");
	assert_float_equal(num_at(json_object_get(json_object_get(b, "metrics"), "gpu_ms"), "judged_pct", NULL), 0, 1e-12);
	assert_int_equal(aa_compare_tripped(cmp), 1);

	/* what the table prints of it */
	char *t = table_of(cmp);
	assert_has(t, "verdict BASE: front: a and b");
	assert_has(t, "  a         30.00 -> 29.50 -0.50     0.9000 -> 0.9000 +0.0000");
	assert_has(t, "0.0 -> 0.0 +0.0    TRIPPED memory > +40%, psnr < -0.1");
	assert_has(t, "  a         10.00 -> 20.00       +100.0%     +100.0% [+100.0%, +100.0%]         TRIPPED gpu_ms > +50%");
	assert_has(t, "  b         10.00 -> 10.00       +0.0%       +0.0% [+0.0%, +0.0%]               held");
	assert_has(t, "machine factor x1.00 (none: fewer than 3 methods");
	assert_has(t, "TRIPPED: 8 gates checked, 5 held, 3 tripped, 0 not judged");
	assert_has(t, "tripped gpu_ms > +50% in s/default/64x36, a: gpu_ms p10 10 -> 20 ms (+100.0% as measured); judged "
		      "over the machine factor x1.00: +100.0%, 90% interval +100.0% to +100.0%: the whole interval is past "
		      "the gate gpu_ms > +50%");
	free(t);
	json_decref(cmp);
}

/* Three timed methods: the machine factor is the median of NEW/BASE p10 ratios, 11/10, 22/20, 88/40 ->
 * 1.1; the third is judged 88 / 1.1 - 40 = +40 ms, +100%, though its raw change is +120%. */
static void test_machine_factor(void **state)
{
	(void)state;
	struct aa_error err;
	const double b1[5] = {10, 10, 10, 10, 10}, b2[5] = {20, 20, 20, 20, 20}, b3[5] = {40, 40, 40, 40, 40};
	const double n1[5] = {11, 11, 11, 11, 11}, n2[5] = {22, 22, 22, 22, 22}, n3[5] = {88, 88, 88, 88, 88};
	json_t *cmp = compare(job("s", json_pack("[o, o, o]", method("a", 30, 1, b1, 5), method("b", 30, 1, b2, 5),
						    method("c", 30, 1, b3, 5))),
			      job("s", json_pack("[o, o, o]", method("a", 30, 1, n1, 5), method("b", 30, 1, n2, 5),
						    method("c", 30, 1, n3, 5))),
			      (const char *const[]){"gpu_ms > +50%", NULL}, &err);
	assert_non_null(cmp);
	json_t *c = json_object_get(json_object_get(pair_of(cmp, 2), "metrics"), "gpu_ms");
	assert_float_equal(num_at(c, "machine_factor", NULL), 1.1, 1e-12);
	assert_float_equal(num_at(c, "change_median_pct", NULL), 120, 1e-9);
	assert_float_equal(num_at(c, "judged", NULL), 40, 1e-9);
	assert_float_equal(num_at(c, "judged_pct", NULL), 100, 1e-9);
	for (int m = 0; m < 2; m++)
		assert_float_equal(num_at(json_object_get(json_object_get(pair_of(cmp, m), "metrics"), "gpu_ms"), "judged_pct",
					  NULL), 0, 1e-9);
	assert_string_equal(gate_result(pair_of(cmp, 2), "gpu_ms > +50%"), "tripped");
	assert_string_equal(gate_result(pair_of(cmp, 0), "gpu_ms > +50%"), "held");
	char *t = table_of(cmp);
	assert_has(t, "  c         40.00 -> 88.00       +120.0%     +100.0% [+100.0%, +100.0%]         TRIPPED gpu_ms > +50%");
	assert_has(t, "machine factor x1.10: NEW ran this case 10% slower than BASE");
	assert_has(t, "tripped gpu_ms > +50% in s/default/64x36, c: gpu_ms p10 40 -> 88 ms (+120.0% as measured); judged "
		      "over the machine factor x1.10: +100.0%, 90% interval +100.0% to +100.0%");
	free(t);
	json_decref(cmp);
}

/* Spread times: BASE 10..14 (p10 10.4, median 12), NEW 20..28 (p10 20.8, median 24): +100% both ways;
 * a resample's p10 lies between its run's extremes, so the interval lies within 20/14 - 1 = +42.9% and
 * 28/10 - 1 = +180%. */
static void test_interval(void **state)
{
	(void)state;
	struct aa_error err;
	const double b[5] = {14, 10, 12, 11, 13}, n[5] = {24, 28, 20, 22, 26};
	json_t *cmp = compare(job("s", json_pack("[o, o]", method("a", 30, 1, b, 5), method("z", 30, 1, ms10, 5))),
			      job("s", json_pack("[o, o]", method("a", 30, 1, n, 5), method("z", 30, 1, ms10, 5))),
			      (const char *const[]){"gpu_ms > +40%", "gpu_ms > +190%", NULL}, &err);
	assert_non_null(cmp);
	json_t *gpu = json_object_get(json_object_get(pair_of(cmp, 0), "metrics"), "gpu_ms");
	assert_float_equal(num_at(gpu, "base", "p10"), 10.4, 1e-9);
	assert_float_equal(num_at(gpu, "new", "p10"), 20.8, 1e-9);
	assert_float_equal(num_at(gpu, "base", "median"), 12, 1e-12);
	assert_float_equal(num_at(gpu, "new", "median"), 24, 1e-12);
	assert_float_equal(num_at(gpu, "change", NULL), 10.4, 1e-9);
	assert_float_equal(num_at(gpu, "change_pct", NULL), 100, 1e-9);
	assert_float_equal(num_at(gpu, "judged_pct", NULL), 100, 1e-9);
	const double lo = json_number_value(json_array_get(json_object_get(gpu, "interval_pct"), 0));
	const double hi = json_number_value(json_array_get(json_object_get(gpu, "interval_pct"), 1));
	if (!(lo >= 100.0 * (20.0 / 14 - 1) - 1e-9 && lo <= 100 && hi >= 100 && hi <= 180 + 1e-9))
		fail_msg("interval [%g, %g] outside [+42.9%%, +180%%] or not around +100%%", lo, hi);
	assert_string_equal(gate_result(pair_of(cmp, 0), "gpu_ms > +40%"), "tripped");
	assert_string_equal(gate_result(pair_of(cmp, 0), "gpu_ms > +190%"), "held");
	json_decref(cmp);
}

/* Exactly at the threshold: a strict gate holds, its "or equal" form trips. 30.5 -> 30.25 dB is -0.25
 * exactly; 10 -> 15 ms is +50% exactly, the whole (degenerate) interval at +50%. */
static void test_at_threshold(void **state)
{
	(void)state;
	struct aa_error err;
	json_t *cmp = compare(job("s", json_pack("[o, o]", method("a", 30.5, 1, ms10, 5), method("z", 30, 1, ms10, 5))),
			      job("s", json_pack("[o, o]", method("a", 30.25, 1, ms15, 5), method("z", 30, 1, ms10, 5))),
			      (const char *const[]){"psnr < -0.25", "psnr <= -0.25", "gpu_ms > +50%", "gpu_ms >= +50%", NULL},
			      &err);
	assert_non_null(cmp);
	json_t *a = pair_of(cmp, 0);
	assert_string_equal(gate_result(a, "psnr < -0.25"), "held");
	assert_string_equal(gate_result(a, "psnr <= -0.25"), "tripped");
	assert_string_equal(gate_result(a, "gpu_ms > +50%"), "held");
	assert_string_equal(gate_result(a, "gpu_ms >= +50%"), "tripped");
	json_decref(cmp);
}

/* A gate on a run with fewer than 5 timed renders is not judged; when nothing at all is judged the
 * comparison is refused, never "held". */
static void test_nothing_judged(void **state)
{
	(void)state;
	struct aa_error err;
	const double one[1] = {10};
	json_t *cmp = compare(job("s", json_pack("[o]", method("a", 30, 1, one, 1))),
			      job("s", json_pack("[o]", method("a", 30, 1, one, 1))),
			      (const char *const[]){"gpu_ms > +50%", NULL}, &err);
	assert_null(cmp);
	assert_int_equal(err.code, AA_ERR_INVALID);
	assert_non_null(strstr(err.message, "nothing was judged"));
	assert_non_null(strstr(err.message, "fewer than 5 timed renders"));
	/* with a gate it can judge, the same runs hold */
	cmp = compare(job("s", json_pack("[o]", method("a", 30, 1, one, 1))), job("s", json_pack("[o]", method("a", 30, 1, one, 1))),
		      (const char *const[]){"gpu_ms > +50%", "psnr < -0.1", NULL}, &err);
	assert_non_null(cmp);
	json_t *counts = json_object_get(cmp, "counts");
	assert_int_equal(json_integer_value(json_object_get(counts, "held")), 1);
	assert_int_equal(json_integer_value(json_object_get(counts, "unknown")), 1);
	assert_int_equal(aa_compare_tripped(cmp), 0);
	json_decref(cmp);
}

/* No method pairs: refused, naming each run's methods. */
static void test_nothing_pairs(void **state)
{
	(void)state;
	struct aa_error err;
	json_t *cmp = compare(job("s", json_pack("[o]", method("fxaa", 30, 1, ms10, 5))),
			      job("s", json_pack("[o]", method("smaa", 30, 1, ms10, 5))), NULL, &err);
	assert_null(cmp);
	assert_int_equal(err.code, AA_ERR_INVALID);
	assert_non_null(strstr(err.message, "no method pairs"));
	assert_non_null(strstr(err.message, "case s/default/64x36: BASE has fxaa; NEW has smaa"));
}

/* Pairing: a label in one run only pairs with the one method of its name in the other; two of that name
 * are ambiguous and pair with nothing, and are listed as not compared. */
static void test_ambiguous_pairing(void **state)
{
	(void)state;
	struct aa_error err;
	json_t *cmp = compare(job("s", json_pack("[o, o]", method("none", 20, 1, ms10, 5), method("fxaa", 30, 1, ms10, 5))),
			      job("s", json_pack("[o, o, o]", method("none", 20, 1, ms10, 5),
						    method("fxaa:preset=10", 31, 1, ms10, 5), method("fxaa:preset=39", 32, 1, ms10, 5))),
			      NULL, &err);
	assert_non_null(cmp);
	json_t *c = json_array_get(json_object_get(cmp, "cases"), 0);
	assert_int_equal(json_array_size(json_object_get(c, "methods")), 1);
	assert_string_equal(json_string_value(json_array_get(json_object_get(json_object_get(c, "unpaired"), "base"), 0)),
			    "fxaa");
	assert_int_equal(json_array_size(json_object_get(json_object_get(c, "unpaired"), "new")), 2);
	json_decref(cmp);
	/* with one of them, they pair by name */
	cmp = compare(job("s", json_pack("[o]", method("fxaa", 30, 1, ms10, 5))),
		      job("s", json_pack("[o]", method("fxaa:preset=10", 31, 1, ms10, 5))), NULL, &err);
	assert_non_null(cmp);
	assert_string_equal(json_string_value(json_object_get(pair_of(cmp, 0), "paired_by")), "name");
	json_decref(cmp);
}

/* A suite of these cases (each a job's document with its id). */
static json_t *suite(const char *const *ids, int n)
{
	json_t *cases = json_array();
	for (int i = 0; i < n; i++) {
		json_t *c = job("s", json_pack("[o]", method("a", 30, 1, ms10, 5)));
		json_object_set_new(c, "id", json_string(ids[i]));
		json_array_append_new(cases, c);
	}
	return json_pack("{s:o}", "cases", cases);
}

/* A case twice in one run is refused, not paired as if it were there once; cases missing from a run are
 * named. */
static void test_duplicate_and_missing_cases(void **state)
{
	(void)state;
	struct aa_error err;
	static const char *const twice[] = {"s/default/64x36", "t/default/64x36", "s/default/64x36"};
	static const char *const both[] = {"s/default/64x36", "t/default/64x36"};
	json_t *cmp = compare(suite(both, 2), suite(twice, 3), NULL, &err);
	assert_null(cmp);
	assert_int_equal(err.code, AA_ERR_INVALID);
	assert_string_equal(err.path, "NEW cases[2]");
	assert_non_null(strstr(err.message, "has the id of an earlier case (s/default/64x36)"));
	cmp = compare(suite(twice, 3), suite(both, 2), NULL, &err);
	assert_null(cmp);
	assert_string_equal(err.path, "BASE cases[2]");
	cmp = compare(suite(both, 2), suite(both, 1), NULL, &err);
	assert_null(cmp);
	assert_non_null(strstr(err.message, "missing from NEW: t/default/64x36"));
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_two_methods),
		cmocka_unit_test(test_machine_factor),
		cmocka_unit_test(test_interval),
		cmocka_unit_test(test_at_threshold),
		cmocka_unit_test(test_nothing_judged),
		cmocka_unit_test(test_nothing_pairs),
		cmocka_unit_test(test_ambiguous_pairing),
		cmocka_unit_test(test_duplicate_and_missing_cases),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
