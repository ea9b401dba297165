/* Values with a known, exact answer, checked without a GPU: Halton and Sobol' points (worked out by hand),
 * the reference's scrambled nets, the jitter sequences of the temporal methods, Vulkan's standard sample locations, FXAA 3.11's and SMAA 2.8's
 * published presets and defaults, and the boolean reading of environment flags. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "run/engine.h"
#include "gpu/sample_positions.h"
#include "methods/fxaa.h"
#include "types/method.h"
#include "methods/smaa.h"
#include "reference/owen_sobol.h"
#include "reference/reference.h"
#include "types/job.h"
#include "methods/jitter.h"
#include "methods/methods.h"
#include "util/halton.h"

/* Radical inverses written out by hand: index in base b, digits mirrored about the point. */
static void test_halton_points(void **state)
{
	(void)state;
	static const struct { unsigned index, base; double value; } known[] = {
		{0, 2, 0.0}, {1, 2, 1.0 / 2}, {2, 2, 1.0 / 4}, {3, 2, 3.0 / 4}, {4, 2, 1.0 / 8}, {5, 2, 5.0 / 8},
		{6, 2, 3.0 / 8}, {7, 2, 7.0 / 8}, {8, 2, 1.0 / 16}, {11, 2, 13.0 / 16}, /* 1011 -> .1101 */
		{0, 3, 0.0}, {1, 3, 1.0 / 3}, {2, 3, 2.0 / 3}, {3, 3, 1.0 / 9}, {4, 3, 4.0 / 9}, {5, 3, 7.0 / 9},
		{8, 3, 8.0 / 9}, {9, 3, 1.0 / 27}, {16, 3, 16.0 / 27}, /* 121 -> .121 */
		{26, 3, 26.0 / 27}, /* 222 -> .222 */
		{3, 5, 3.0 / 5}, {7, 5, 11.0 / 25}, /* 12 -> .21 */
	};
	for (size_t i = 0; i < sizeof known / sizeof known[0]; i++)
		/* exact in base 2; thirds and fifths to the last bit or two of a double */
		if (fabs(aa_halton(known[i].index, known[i].base) - known[i].value) > (known[i].base == 2 ? 0 : 1e-15))
			fail_msg("halton(%u, %u) = %.17g, expected %.17g", known[i].index, known[i].base,
				 aa_halton(known[i].index, known[i].base), known[i].value);
}

/* The unscrambled Sobol' points worked out by hand: x is the van der Corput sequence (index's bits mirrored
 * about the point); y xors the direction numbers 1/2, 3/4, 5/8, 15/16 of the index's set bits. */
static void test_sobol_points(void **state)
{
	(void)state;
	static const double expected[8][2] = {{0, 0}, {0.5, 0.5}, {0.25, 0.75}, {0.75, 0.25},
					      {0.125, 0.625}, {0.625, 0.125}, {0.375, 0.375}, {0.875, 0.875}};
	for (uint32_t i = 0; i < 8; i++) {
		uint32_t p[2];
		aa_sobol_2d(i, p);
		for (int k = 0; k < 2; k++)
			if (p[k] / 4294967296.0 != expected[i][k])
				fail_msg("sobol %u.%c = %.9g, expected %.9g", i, "xy"[k], p[k] / 4294967296.0, expected[i][k]);
	}
	uint32_t p[2];
	aa_sobol_2d(15, p); /* 1111: .1000 ^ .1100 ^ .1010 ^ .1111 = .0001 */
	assert_true(p[1] == 0x10000000u && p[0] == 0xf0000000u);
}

/* Owen's scramble is nested: two fractions that agree in their first k bits still agree in them after it,
 * and it permutes the 2^k intervals of each level (a bijection of the first k bits). */
static void test_owen_scramble_nested(void **state)
{
	(void)state;
	for (int k = 1; k <= 10; k++) {
		static unsigned char seen[1 << 10];
		memset(seen, 0, sizeof seen);
		for (uint32_t top = 0; top < (1u << k); top++) {
			uint32_t a = top << (32 - k), b = a | (0x9e3779b9u >> k); /* same first k bits */
			uint32_t sa = aa_owen_scramble(a, 12345u), sb = aa_owen_scramble(b, 12345u);
			if ((sa ^ sb) >> (32 - k))
				fail_msg("level %d: 0x%08x and 0x%08x scramble to 0x%08x and 0x%08x", k, a, b, sa, sb);
			seen[sa >> (32 - k)]++;
		}
		for (uint32_t t = 0; t < (1u << k); t++)
			assert_int_equal(seen[t], 1);
	}
	/* it does scramble: not the identity, and other seeds give other trees */
	assert_true(aa_owen_scramble(0x80000000u, 1u) != 0x80000000u || aa_owen_scramble(0x40000000u, 1u) != 0x40000000u);
	assert_true(aa_owen_scramble(0x12345678u, 1u) != aa_owen_scramble(0x12345678u, 2u));
}

/* The reference's offsets: Owen-scrambled Sobol' points in [-0.5, 0.5)^2, nested, and at every power of two
 * up to the largest reference a (0,k,2)-net: each of the 2^k boxes of every dyadic shape 2^-m x 2^-(k-m)
 * holds exactly one of the first 2^k points. */
static void test_reference_offsets(void **state)
{
	(void)state;
	static float off[AA_MAX_REFERENCE_SAMPLES][2];
	aa_reference_offsets(AA_MAX_REFERENCE_SAMPLES, off);
	float few[8][2];
	aa_reference_offsets(8, few);
	for (int i = 0; i < 8; i++)
		assert_true(few[i][0] == off[i][0] && few[i][1] == off[i][1]);
	for (int i = 0; i < AA_MAX_REFERENCE_SAMPLES; i++)
		for (int k = 0; k < 2; k++)
			if (!(off[i][k] >= -0.5f && off[i][k] < 0.5f))
				fail_msg("reference offset %d.%c = %.9g, outside the pixel", i, "xy"[k], off[i][k]);
	static int count[AA_MAX_REFERENCE_SAMPLES];
	for (int k = 0; (1 << k) <= AA_MAX_REFERENCE_SAMPLES; k++)
		for (int m = 0; m <= k; m++) {
			int n = 1 << k, cols = 1 << m, rows = 1 << (k - m);
			memset(count, 0, sizeof count);
			for (int i = 0; i < n; i++) {
				int cx = (int)((off[i][0] + 0.5f) * (float)cols), cy = (int)((off[i][1] + 0.5f) * (float)rows);
				count[cy * cols + cx]++;
			}
			for (int b = 0; b < n; b++)
				if (count[b] != 1)
					fail_msg("first %d reference points, %dx%d boxes: box %d holds %d", n, cols, rows, b,
						 count[b]);
		}
}

/* TAA's jitter: Halton points 1..length, repeating; ASAA's quadrant centres; T2MSAA's alternation. */
static void test_jitter_sequences(void **state)
{
	(void)state;
	float j[2];
	aa_jitter_halton(0, 16, j);
	assert_true(j[0] == 0.0f && fabsf(j[1] - (float)(1.0 / 3 - 0.5)) < 1e-7f);
	aa_jitter_halton(2, 16, j);
	assert_true(j[0] == 0.25f && fabsf(j[1] - (float)(1.0 / 9 - 0.5)) < 1e-7f);
	aa_jitter_halton(15, 16, j); /* index 16 */
	assert_true(j[0] == (float)(1.0 / 32 - 0.5) && fabsf(j[1] - (float)(16.0 / 27 - 0.5)) < 1e-7f);
	float a[2], b[2];
	for (int len = 8; len <= 16; len += 8)
		for (int f = 0; f < 3 * len; f++) {
			aa_jitter_halton(f, len, a);
			aa_jitter_halton(f % len, len, b);
			assert_true(a[0] == b[0] && a[1] == b[1]);
		}

	static const float quadrant[4][2] = {{-0.25f, -0.25f}, {0.25f, 0.25f}, {0.25f, -0.25f}, {-0.25f, 0.25f}};
	for (int f = 0; f < 12; f++) {
		aa_jitter_quadrant(f, j);
		assert_true(j[0] == quadrant[f % 4][0] && j[1] == quadrant[f % 4][1]);
	}
	for (int f = 0; f < 6; f++) {
		aa_jitter_alternate(f, 0.125f, j);
		float s = f % 2 ? -0.125f : 0.125f;
		assert_true(j[0] == s && j[1] == s);
	}
}

/* Vulkan's "standard sample locations" table (the Vulkan specification, multisampling chapter). */
static void test_standard_sample_positions(void **state)
{
	(void)state;
	static const float p1[][2] = {{0.5f, 0.5f}};
	static const float p2[][2] = {{0.75f, 0.75f}, {0.25f, 0.25f}};
	static const float p4[][2] = {{0.375f, 0.125f}, {0.875f, 0.375f}, {0.125f, 0.625f}, {0.625f, 0.875f}};
	static const float p8[][2] = {{0.5625f, 0.3125f}, {0.4375f, 0.6875f}, {0.8125f, 0.5625f},
				      {0.3125f, 0.1875f}, {0.1875f, 0.8125f}, {0.0625f, 0.4375f},
				      {0.6875f, 0.9375f}, {0.9375f, 0.0625f}};
	static const float p16[][2] = {{0.5625f, 0.5625f}, {0.4375f, 0.3125f}, {0.3125f, 0.625f}, {0.75f, 0.4375f},
				       {0.1875f, 0.375f}, {0.625f, 0.8125f}, {0.8125f, 0.6875f}, {0.6875f, 0.1875f},
				       {0.375f, 0.875f}, {0.5f, 0.0625f}, {0.25f, 0.125f}, {0.125f, 0.75f},
				       {0.0f, 0.5f}, {0.9375f, 0.25f}, {0.875f, 0.9375f}, {0.0625f, 0.0f}};
	const struct { int n; const float (*p)[2]; } tables[] = {{1, p1}, {2, p2}, {4, p4}, {8, p8}, {16, p16}};
	for (size_t t = 0; t < sizeof tables / sizeof tables[0]; t++) {
		const float (*got)[2] = aa_standard_sample_positions(tables[t].n);
		assert_non_null(got);
		for (int i = 0; i < tables[t].n; i++)
			if (got[i][0] != tables[t].p[i][0] || got[i][1] != tables[t].p[i][1])
				fail_msg("%dx sample %d: (%g, %g), expected (%g, %g)", tables[t].n, i, got[i][0], got[i][1],
					 tables[t].p[i][0], tables[t].p[i][1]);
	}
	assert_null(aa_standard_sample_positions(3));
}

static void parse_ok(const char *text, const struct aa_method **m, struct aa_method_params *p)
{
	struct aa_error err = {0};
	if (aa_method_parse(text, "m", m, p, &err))
		fail_msg("%s: %s", text, err.message);
}

/* FXAA 3.11's quality presets (FXAA_QUALITY__PS and __P0..__P11 of the public source) and its default
 * knobs (subpix 0.75, edge threshold 0.166, edge threshold min 0.0833; preset 12). */
static void test_fxaa_presets(void **state)
{
	(void)state;
	static const struct { int preset, count; float steps[12]; } published[] = {
		{10, 3, {1.5f, 3.0f, 12.0f}},
		{11, 4, {1.0f, 1.5f, 3.0f, 12.0f}},
		{12, 5, {1.0f, 1.5f, 2.0f, 4.0f, 12.0f}},
		{13, 6, {1.0f, 1.5f, 2.0f, 2.0f, 4.0f, 12.0f}},
		{14, 7, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 4.0f, 12.0f}},
		{15, 8, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 12.0f}},
		{20, 3, {1.5f, 2.0f, 8.0f}},
		{21, 4, {1.0f, 1.5f, 2.0f, 8.0f}},
		{22, 5, {1.0f, 1.5f, 2.0f, 2.0f, 8.0f}},
		{23, 6, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 8.0f}},
		{24, 7, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 3.0f, 8.0f}},
		{25, 8, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}},
		{26, 9, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}},
		{27, 10, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}},
		{28, 11, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}},
		{29, 12, {1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}},
		{39, 12, {1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.5f, 2.0f, 2.0f, 2.0f, 2.0f, 4.0f, 8.0f}},
	};
	const char *const variants[] = {"fxaa", "fxaa-cs"};
	for (int v = 0; v < 2; v++)
		for (size_t i = 0; i < sizeof published / sizeof published[0]; i++) {
			char text[64];
			snprintf(text, sizeof text, "%s:preset=%d", variants[v], published[i].preset);
			const struct aa_method *m;
			struct aa_method_params p;
			parse_ok(text, &m, &p);
			for (int horizontal = 0; horizontal < 2; horizontal++) {
				struct aa_fxaa_spec spec;
				aa_fxaa_spec_init(&spec, &p, horizontal);
				if (spec.data.step_count != published[i].count)
					fail_msg("%s: %d steps, published %d", text, spec.data.step_count, published[i].count);
				for (int k = 0; k < AA_FXAA_MAX_STEPS; k++)
					if (spec.data.steps[k] != published[i].steps[k])
						fail_msg("%s: step %d is %g, published %g", text, k, spec.data.steps[k],
							 published[i].steps[k]);
				assert_int_equal(spec.data.horizontal, horizontal);
				/* the specialization map hands the shader exactly these bytes */
				assert_ptr_equal(spec.info.pData, &spec.data);
				assert_int_equal(spec.info.mapEntryCount, AA_FXAA_MAX_STEPS + 2);
				for (uint32_t e = 0; e < spec.info.mapEntryCount; e++)
					assert_int_equal(spec.entries[e].constantID, e);
				assert_int_equal(spec.entries[4].offset, offsetof(struct aa_fxaa_spec_data, steps) + 3 * 4);
			}
		}
	for (int v = 0; v < 2; v++) {
		const struct aa_method *m;
		struct aa_method_params p;
		parse_ok(variants[v], &m, &p);
		struct aa_fxaa_spec spec;
		aa_fxaa_spec_init(&spec, &p, true);
		assert_int_equal(spec.data.step_count, 5); /* preset 12 */
		struct aa_fxaa_push push;
		aa_fxaa_push_init(&push, &p);
		assert_true(push.subpix == 0.75f && push.edge_threshold == 0.166f && push.edge_threshold_min == 0.0833f);
		parse_ok(v ? "fxaa-cs:subpix=0.25,edge_threshold=0.125,edge_threshold_min=0.0625"
			   : "fxaa:subpix=0.25,edge_threshold=0.125,edge_threshold_min=0.0625", &m, &p);
		aa_fxaa_push_init(&push, &p);
		assert_true(push.subpix == 0.25f && push.edge_threshold == 0.125f && push.edge_threshold_min == 0.0625f);
	}
}

/* SMAA 2.8's presets (SMAA.hlsl: THRESHOLD, MAX_SEARCH_STEPS, MAX_SEARCH_STEPS_DIAG, CORNER_ROUNDING;
 * LOW and MEDIUM detect no diagonals or corners), SMAA_DEPTH_THRESHOLD = 0.1 x THRESHOLD and the local
 * contrast adaptation factor 2.0; preset HIGH on luma by default. */
static void test_smaa_presets(void **state)
{
	(void)state;
	static const struct { const char *text; float threshold; int search, diag; float corner_keep; } published[] = {
		{"smaa:preset=low", 0.15f, 4, 0, -1.0f},
		{"smaa:preset=medium", 0.10f, 8, 0, -1.0f},
		{"smaa:preset=high", 0.10f, 16, 8, 0.75f},
		{"smaa:preset=ultra", 0.05f, 32, 16, 0.75f},
		{"smaa", 0.10f, 16, 8, 0.75f},
		{"smaa:edge=color", 0.10f, 16, 8, 0.75f},
		{"smaa:preset=ultra,edge=depth", 0.005f, 32, 16, 0.75f},
		{"smaa:edge=depth", 0.01f, 16, 8, 0.75f},
		{"smaa:preset=low,threshold=0.3", 0.3f, 4, 0, -1.0f},
		{"smaa:threshold=0.2,edge=depth", 0.02f, 16, 8, 0.75f},
	};
	for (size_t i = 0; i < sizeof published / sizeof published[0]; i++) {
		const struct aa_method *m;
		struct aa_method_params p;
		parse_ok(published[i].text, &m, &p);
		struct aa_smaa_settings s;
		aa_smaa_settings(&p, &s);
		if (fabsf(s.threshold - published[i].threshold) > 1e-7f || s.search_steps != published[i].search ||
		    s.diag_steps != published[i].diag || fabsf(s.corner_keep - published[i].corner_keep) > 1e-7f ||
		    s.contrast_factor != 2.0f)
			fail_msg("%s: threshold %g, steps %d, diagonal %d, corner %g, contrast %g; published %g, %d, %d, "
				 "%g, 2", published[i].text, s.threshold, s.search_steps, s.diag_steps, s.corner_keep,
				 s.contrast_factor, published[i].threshold, published[i].search, published[i].diag,
				 published[i].corner_keep);
	}
}

static void test_env_flag(void **state)
{
	(void)state;
	const char *off[] = {NULL, "", "0", "false", "FALSE", "no", "No", "off", "OFF"};
	const char *on[] = {"1", "true", "TRUE", "yes", "on", "On", "2", "enabled"};
	for (size_t i = 0; i < sizeof off / sizeof off[0]; i++)
		if (aa_env_flag_value(off[i]))
			fail_msg("'%s' reads as on", off[i] ? off[i] : "(unset)");
	for (size_t i = 0; i < sizeof on / sizeof on[0]; i++)
		if (!aa_env_flag_value(on[i]))
			fail_msg("'%s' reads as off", on[i]);
	setenv("AALAB_TEST_FLAG", "0", 1);
	assert_false(aa_env_flag("AALAB_TEST_FLAG"));
	setenv("AALAB_TEST_FLAG", "yes", 1);
	assert_true(aa_env_flag("AALAB_TEST_FLAG"));
	unsetenv("AALAB_TEST_FLAG");
	assert_false(aa_env_flag("AALAB_TEST_FLAG"));
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_halton_points),
		cmocka_unit_test(test_sobol_points),
		cmocka_unit_test(test_owen_scramble_nested),
		cmocka_unit_test(test_reference_offsets),
		cmocka_unit_test(test_jitter_sequences),
		cmocka_unit_test(test_standard_sample_positions),
		cmocka_unit_test(test_fxaa_presets),
		cmocka_unit_test(test_smaa_presets),
		cmocka_unit_test(test_env_flag),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
