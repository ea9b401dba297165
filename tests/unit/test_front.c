/* The cost-quality front (engine/results/front.c) on hand-made entries whose answers are worked out by
 * hand: which are on the front, what beats each other entry and by how much, ties in cost exactly at the
 * spreads' edges, entries with too few timed renders left unranked, identical images, the headline, and the
 * front of each method family. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "results/front.h"

static struct aa_front_entry entry(const char *label, double p10, double median, double p90, int n, double psnr,
				   double flip)
{
	return (struct aa_front_entry){.label = label, .psnr = psnr, .flip = flip,
				       .cost = {.median = median, .p10 = p10, .p90 = p90, .min = p10, .mean = median, .n = n}};
}

static void test_cost_order(void **state)
{
	(void)state;
	struct aa_timing_stats a = {.median = 1.1, .p10 = 1.0, .p90 = 1.2, .n = 5};
	struct aa_timing_stats b = {.median = 1.5, .p10 = 1.3, .p90 = 1.6, .n = 5};
	assert_int_equal(aa_cost_order(&a, &b), AA_COST_LOWER);
	assert_int_equal(aa_cost_order(&b, &a), AA_COST_HIGHER);
	b.p10 = 1.2; /* touching spreads overlap: the same cost */
	assert_int_equal(aa_cost_order(&a, &b), AA_COST_SAME);
	assert_int_equal(aa_cost_order(&b, &a), AA_COST_SAME);
	b.p10 = 1.2000001;
	assert_int_equal(aa_cost_order(&a, &b), AA_COST_LOWER);
	b.n = 4; /* too few renders on either side: not comparable */
	assert_int_equal(aa_cost_order(&a, &b), AA_COST_UNKNOWN);
	assert_int_equal(aa_cost_order(&b, &a), AA_COST_UNKNOWN);
	b.n = 5;
	b.p90 = NAN;
	assert_int_equal(aa_cost_order(&a, &b), AA_COST_UNKNOWN);
}

/* cheap (1.0-1.2 ms, 30 dB, FLIP 0.05); good (2.0-2.4, 35 dB, 0.03); close (2.1-2.6, overlaps good, 34 dB,
 * 0.04): good beats close at the same cost, by 1 dB and 0.01 FLIP; sharp (5.0-5.5, 34.5 dB, 0.02) costs
 * more than good and has less PSNR but less FLIP: on the front; slow (3.0-3.2, 29 dB, 0.06) is beaten by
 * cheap (lower cost), and by good; one (n 1) is not ranked. */
static void test_front(void **state)
{
	(void)state;
	struct aa_front_entry e[] = {
		entry("cheap", 1.0, 1.1, 1.2, 5, 30, 0.05), entry("good", 2.0, 2.2, 2.4, 5, 35, 0.03),
		entry("close", 2.1, 2.3, 2.6, 5, 34, 0.04), entry("sharp", 5.0, 5.2, 5.5, 5, 34.5, 0.02),
		entry("slow", 3.0, 3.1, 3.2, 5, 29, 0.06),  entry("one", 0.5, 0.5, 0.5, 1, 40, 0.001),
	};
	struct aa_front_place p[6];
	assert_int_equal(aa_front_compute(e, 6, p), 5);
	assert_int_equal(p[0].kind, AA_PLACE_FRONT);
	assert_int_equal(p[1].kind, AA_PLACE_FRONT);
	assert_int_equal(p[2].kind, AA_PLACE_DOMINATED);
	assert_int_equal(p[2].beaten_by, 1);
	assert_int_equal(p[2].beater_cost, AA_COST_SAME);
	assert_int_equal(p[3].kind, AA_PLACE_FRONT);
	assert_int_equal(p[4].kind, AA_PLACE_DOMINATED);
	assert_int_equal(p[4].beaten_by, 0); /* of its beaters on the front (cheap, good) the cheapest */
	assert_int_equal(p[4].beater_cost, AA_COST_LOWER);
	assert_int_equal(p[5].kind, AA_PLACE_NOT_RANKED); /* one timed render ranks nothing, however good */

	json_t *v = aa_front_json(e, 6);
	assert_non_null(v);
	assert_string_equal(json_string_value(json_object_get(v, "headline")),
			    "front: cheap, good and sharp; ties in cost: good with close; not ranked (n=1): one");
	assert_false(json_is_true(json_object_get(v, "ranked")));
	json_t *ties = json_object_get(v, "ties");
	assert_int_equal(json_array_size(ties), 1);
	assert_string_equal(json_string_value(json_array_get(json_array_get(ties, 0), 0)), "good");
	assert_string_equal(json_string_value(json_array_get(json_array_get(ties, 0), 1)), "close");
	json_t *close = json_array_get(json_object_get(v, "methods"), 2), *by = json_object_get(close, "beaten_by");
	assert_string_equal(json_string_value(json_object_get(close, "place")), "beaten");
	assert_string_equal(json_string_value(json_object_get(by, "method")), "good");
	assert_string_equal(json_string_value(json_object_get(by, "cost")), "same");
	assert_float_equal(json_real_value(json_object_get(by, "psnr_db")), 1.0, 1e-12);
	assert_float_equal(json_real_value(json_object_get(by, "flip")), 0.01, 1e-12);
	assert_float_equal(json_real_value(json_object_get(by, "time_ratio")), 2.3 / 2.2, 1e-12);
	json_t *slow = json_object_get(json_array_get(json_object_get(v, "methods"), 4), "beaten_by");
	assert_string_equal(json_string_value(json_object_get(slow, "cost")), "lower");
	assert_float_equal(json_real_value(json_object_get(slow, "time_ratio")), 3.1 / 1.1, 1e-12);
	json_t *lines = json_object_get(v, "lines");
	assert_int_equal(json_array_size(lines), 2);
	assert_string_equal(json_string_value(json_array_get(lines, 0)),
			    "close: 1.00 dB less PSNR and 0.0100 more FLIP than good, at a cost the timings cannot tell "
			    "apart (p10-p90 overlap)");
	assert_string_equal(json_string_value(json_array_get(lines, 1)),
			    "slow: 1.00 dB less PSNR and 0.0100 more FLIP than cheap, for 2.82x its time");
	assert_string_equal(json_string_value(json_array_get(json_object_get(v, "not_ranked"), 0)), "one");
	json_decref(v);
}

/* Equal quality decides nothing: only the lower cost beats; equal quality at the same cost is a tie on the
 * front. An identical image (infinite PSNR) beats any PSNR; a missing FLIP leaves PSNR alone to decide. */
static void test_equal_and_identical(void **state)
{
	(void)state;
	struct aa_front_entry e[] = {
		entry("a", 1.0, 1.1, 1.2, 8, 33, 0.02), entry("b", 1.1, 1.2, 1.3, 8, 33, 0.02),
		entry("c", 2.0, 2.1, 2.2, 8, 33, 0.02),
	};
	struct aa_front_place p[3];
	aa_front_compute(e, 3, p);
	assert_int_equal(p[0].kind, AA_PLACE_FRONT);
	assert_int_equal(p[1].kind, AA_PLACE_FRONT); /* the same cost and quality as a: nothing beats it */
	assert_int_equal(p[2].kind, AA_PLACE_DOMINATED);
	json_t *v = aa_front_json(e, 3);
	assert_string_equal(json_string_value(json_object_get(v, "headline")), "front: a and b; ties in cost: a with b");
	assert_string_equal(json_string_value(json_array_get(json_object_get(v, "lines"), 0)),
			    "c: the same PSNR and FLIP as a, for 1.91x its time");
	json_decref(v);

	struct aa_front_entry f[] = {
		entry("ssaa", 9.0, 9.5, 10.0, 5, INFINITY, NAN), entry("none", 1.0, 1.1, 1.2, 5, 25, NAN),
		entry("worse", 9.2, 9.6, 9.9, 5, 60, NAN),
	};
	aa_front_compute(f, 3, p);
	assert_int_equal(p[0].kind, AA_PLACE_FRONT);
	assert_int_equal(p[1].kind, AA_PLACE_FRONT);
	assert_int_equal(p[2].kind, AA_PLACE_DOMINATED);
	v = aa_front_json(f, 3);
	json_t *m = json_array_get(json_object_get(v, "methods"), 0);
	assert_true(json_is_true(json_object_get(m, "psnr_identical")));
	assert_true(json_is_null(json_object_get(m, "psnr")));
	assert_string_equal(json_string_value(json_array_get(json_object_get(v, "lines"), 0)),
			    "worse: not identical to the reference where ssaa is, at a cost the timings cannot tell apart "
			    "(p10-p90 overlap)");
	json_decref(v);
}

/* Overlapping spreads are not transitive (a~b, b~c, a<c): every entry still gets a place, the front is
 * never empty, and each beaten entry names something that beats it. */
static void test_chains(void **state)
{
	(void)state;
	struct aa_front_entry e[] = {
		entry("a", 1.0, 1.2, 1.5, 5, 30, 0.03), entry("b", 1.4, 1.7, 2.1, 5, 31, 0.025),
		entry("c", 2.0, 2.2, 2.5, 5, 32, 0.02), entry("d", 2.4, 2.6, 3.0, 5, 31.5, 0.021),
	};
	struct aa_front_place p[4];
	assert_int_equal(aa_front_compute(e, 4, p), 4);
	int front = 0;
	for (int i = 0; i < 4; i++) {
		front += p[i].kind == AA_PLACE_FRONT;
		if (p[i].kind == AA_PLACE_DOMINATED)
			assert_true(p[i].beaten_by >= 0 && p[i].beaten_by != i);
	}
	assert_true(front >= 1);
	assert_int_equal(p[3].kind, AA_PLACE_DOMINATED); /* c: same cost, better in both */
	assert_int_equal(p[3].beaten_by, 2);
}

/* Nothing ranked: the headline says why, and no method is placed on a front of one render each. */
static void test_not_ranked(void **state)
{
	(void)state;
	struct aa_front_entry e[] = {entry("none", 9, 9, 9, 1, 20, 0.1), entry("smaa", 2, 2, 2, 1, 30, 0.05)};
	json_t *v = aa_front_json(e, 2);
	assert_string_equal(json_string_value(json_object_get(v, "headline")),
			    "not ranked: n=1 timed render per method, 5 needed to rank costs");
	assert_int_equal(json_array_size(json_object_get(v, "front")), 0);
	assert_int_equal(json_array_size(json_object_get(v, "lines")), 0);
	json_decref(v);
	e[0].cost.n = 2;
	e[1].cost.n = 4;
	v = aa_front_json(e, 2);
	assert_string_equal(json_string_value(json_object_get(v, "headline")),
			    "not ranked: n=2-4 timed renders per method, 5 needed to rank costs");
	json_decref(v);
}

/* The labels of a JSON array, space-separated. */
static const char *joined(const json_t *list)
{
	static char out[1024];
	size_t i;
	json_t *x;
	out[0] = '\0';
	json_array_foreach(list, i, x)
		snprintf(out + strlen(out), sizeof out - strlen(out), "%s%s", i ? " " : "", json_string_value(x));
	return out;
}

/* Per-family fronts: each family of two or more configurations (the label before ':'; fxaa-cs, first
 * here, is not fxaa) in the order of its first method (msaa:4 comes before fxaa:preset=10), its labels by median cost, and its own front. fxaa:preset=20
 * is beaten by smaa overall but by nothing of its family; fxaa:preset=39 is beaten by fxaa:preset=20 (cheaper,
 * better in both); msaa:8 by msaa:4 (cheaper, better PSNR, FLIP 0.031 > 0.03); msaa:2 and msaa:2x tie in
 * cost with equal quality, both on the front; the ssaa pair is not ranked: on no front. */
static void test_families(void **state)
{
	(void)state;
	struct aa_front_entry e[] = {
		entry("none", 1.0, 1.1, 1.2, 5, 20, 0.1),          entry("fxaa-cs:preset=10", 2.5, 2.6, 2.7, 5, 25, 0.05),
		entry("msaa:4", 6.0, 6.1, 6.3, 5, 30, 0.03),       entry("fxaa:preset=10", 2.0, 2.1, 2.2, 5, 25, 0.05),
		entry("smaa", 2.4, 2.5, 2.6, 5, 28, 0.035),        entry("msaa:2", 5.0, 5.15, 5.2, 5, 27, 0.04),
		entry("fxaa:preset=20", 3.0, 3.1, 3.2, 5, 26, 0.045), entry("msaa:8", 9.0, 9.2, 9.5, 5, 29, 0.031),
		entry("ssaa:16", 20, 21, 22, 1, 40, 0.01),         entry("fxaa:preset=39", 4.0, 4.2, 4.4, 5, 25.5, 0.05),
		entry("ssaa:4", 8, 8.5, 9, 1, 35, 0.02),           entry("msaa:2x", 5.05, 5.1, 5.3, 5, 27, 0.04),
	};
	const int n = (int)(sizeof e / sizeof e[0]);
	json_t *f = aa_front_families_json(e, n);
	assert_non_null(f);
	assert_int_equal(json_array_size(f), 3);
	json_t *msaa = json_array_get(f, 0), *fxaa = json_array_get(f, 1), *ssaa = json_array_get(f, 2);
	assert_int_equal(json_object_size(fxaa), 3); /* the shape is exactly family, methods, front */
	assert_string_equal(json_string_value(json_object_get(fxaa, "family")), "fxaa");
	assert_string_equal(joined(json_object_get(fxaa, "methods")), "fxaa:preset=10 fxaa:preset=20 fxaa:preset=39");
	assert_string_equal(joined(json_object_get(fxaa, "front")), "fxaa:preset=10 fxaa:preset=20");
	assert_string_equal(json_string_value(json_object_get(msaa, "family")), "msaa");
	assert_string_equal(joined(json_object_get(msaa, "methods")), "msaa:2x msaa:2 msaa:4 msaa:8");
	assert_string_equal(joined(json_object_get(msaa, "front")), "msaa:2x msaa:2 msaa:4");
	assert_string_equal(json_string_value(json_object_get(ssaa, "family")), "ssaa");
	assert_string_equal(joined(json_object_get(ssaa, "methods")), "ssaa:4 ssaa:16");
	assert_int_equal(json_array_size(json_object_get(ssaa, "front")), 0);
	json_decref(f);

	/* the overall front is another matter: fxaa:preset=20 is beaten there */
	struct aa_front_place p[12];
	aa_front_compute(e, n, p);
	assert_int_equal(p[6].kind, AA_PLACE_DOMINATED);
	assert_int_equal(p[6].beaten_by, 4);

	/* no family with two configurations: an empty array */
	f = aa_front_families_json(e, 3);
	assert_int_equal(json_array_size(f), 0);
	json_decref(f);
	/* equal medians keep job order; a missing median goes last */
	struct aa_front_entry g[] = {entry("taa:a", 1, 2, 3, 5, 30, 0.03), entry("taa:b", 1, 2, 3, 5, 31, 0.02),
				     entry("taa:c", NAN, NAN, NAN, 0, 33, 0.01), entry("taa:d", 0.2, 0.5, 0.8, 5, 29, 0.03)};
	f = aa_front_families_json(g, 4);
	assert_string_equal(joined(json_object_get(json_array_get(f, 0), "methods")), "taa:d taa:a taa:b taa:c");
	assert_string_equal(joined(json_object_get(json_array_get(f, 0), "front")), "taa:d taa:b");
	json_decref(f);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_cost_order),
		cmocka_unit_test(test_front),
		cmocka_unit_test(test_equal_and_identical),
		cmocka_unit_test(test_chains),
		cmocka_unit_test(test_not_ranked),
		cmocka_unit_test(test_families),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
