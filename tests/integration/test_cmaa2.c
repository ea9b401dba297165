/* CMAA2 on the real device: its parameters, passes and memory; on hard-edges every preset beats `none`;
 * on flat 2D patterns with exact coverage it leaves a pixel-aligned edge untouched (conservative: a
 * straight edge has no step to revectorise) and reduces the error of slanted edges; on a textured scene
 * it leaves texture detail alone where FXAA blurs it. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "run/engine.h"
#include "fixture.h"
#include "reference/exact_coverage.h"
#include "methods/methods.h"

static void test_parameters(void **state)
{
	(void)state;
	const struct aa_method *m;
	struct aa_method_params p;
	struct aa_error err = {0};
	assert_int_equal(aa_method_parse("cmaa2:preset=extreme", "methods[0]", &m, &p, &err), -1);
	assert_int_equal(err.code, AA_ERR_INVALID);
	if (!strstr(err.message, "low") || !strstr(err.message, "ultra"))
		fail_msg("the message does not list the presets: %s", err.message);
	assert_int_equal(aa_method_parse("cmaa2:max_line=1", "methods[0]", &m, &p, &err), -1);
	assert_int_equal(aa_method_parse("cmaa2", "methods[0]", &m, &p, &err), 0);
	char label[AA_LABEL_MAX];
	aa_method_label(m, &p, label, sizeof label);
	assert_string_equal(label, "cmaa2");
	assert_string_equal(aa_alpha_rule_name(aa_method_alpha_rule(m, &p)), "per-pixel");
}

static void test_hard_edges(void **state)
{
	(void)state;
	const char *methods[] = {"none", "cmaa2", "cmaa2:preset=low", "cmaa2:preset=medium", "cmaa2:preset=ultra"};
	const int n = (int)(sizeof methods / sizeof methods[0]);
	struct aa_job_spec spec;
	fixture_spec(&spec, "hard-edges", methods, n, 320, 180, 1, 32);
	struct aa_job_result *r = fixture_run(&spec, NULL, NULL, NULL);
	double none = r->methods[0].frames[0].metrics.psnr;
	for (int i = 1; i < n; i++) {
		const struct aa_method_result *m = &r->methods[i];
		const struct aa_frame_result *f = &m->frames[0];
		printf("  %-22s %.2f dB (none %.2f)  %.2f MB  (%s)\n", m->label, f->metrics.psnr, none,
		       m->memory_bytes / 1048576.0, m->path_taken);
		assert_int_equal(f->nonfinite, 0);
		if (!(f->metrics.psnr > none + 1.0))
			fail_msg("%s: %.2f dB does not beat none (%.2f dB) by 1 dB", m->label, f->metrics.psnr, none);
		const char *passes[] = {"shadow-map", "scene", "cmaa2-edges", "cmaa2-shapes", "cmaa2-apply"};
		int first = f->pass_count == 5 ? 0 : 1;
		assert_int_equal(f->pass_count, 5 - first);
		for (int k = 0; k < f->pass_count; k++) {
			assert_string_equal(f->passes[k].name, passes[first + k]);
			assert_true(f->passes[k].gpu_ms > 0.0);
		}
		const char *images[] = {"edges", "blended colour", "deferred blends"};
		for (int k = 0; k < 3; k++) {
			int found = 0;
			for (int j = 0; j < m->memory_count; j++)
				found |= strcmp(m->memory[j].name, images[k]) == 0;
			if (!found)
				fail_msg("%s: no memory item '%s'", m->label, images[k]);
		}
		assert_true(m->memory_bytes >= r->methods[0].memory_bytes + 320 * 180 * (1 + 8 + 16));
	}
	fixture_free(r);
}

/* Conservative: on moving-sphere's textured sphere and floor (still camera), where revectorising every
 * corner and bump blurs texture detail (FXAA loses to none there), CMAA2 gains on none and beats FXAA. */
static void test_textures_kept(void **state)
{
	(void)state;
	const char *methods[] = {"none", "cmaa2", "fxaa"};
	struct aa_job_spec spec;
	fixture_spec(&spec, "moving-sphere", methods, 3, 320, 180, 1, 32);
	snprintf(spec.path, sizeof spec.path, "static");
	struct aa_job_result *r = fixture_run(&spec, NULL, NULL, NULL);
	double none = r->methods[0].frames[0].metrics.psnr, cmaa2 = r->methods[1].frames[0].metrics.psnr;
	double fxaa = r->methods[2].frames[0].metrics.psnr;
	printf("  moving-sphere 320x180 static: none %.2f, cmaa2 %.2f, fxaa %.2f dB\n", none, cmaa2, fxaa);
	if (!(cmaa2 > none + 0.2) || !(cmaa2 > fxaa))
		fail_msg("cmaa2 %.2f dB does not beat none %.2f dB by 0.2 dB and fxaa %.2f dB", cmaa2, none, fxaa);
	fixture_free(r);
}

static struct fixture_coverage run_pattern(enum aa_pattern2d_kind pattern, double angle)
{
	return fixture_pattern_coverage(pattern, angle, "cmaa2", 64);
}

/* Slanted edges get closer to the exact coverage, on both axes and both slopes. */
static void test_slanted_edges(void **state)
{
	(void)state;
	const double angles[] = {3.0, 10.0, 20.0, 30.0, 60.0, 70.0, 80.0, 87.0, 100.0, 120.0, 160.0, 177.0};
	const int n = (int)(sizeof angles / sizeof angles[0]);
	double sum[2] = {0, 0};
	for (int i = 0; i < n; i++) {
		struct fixture_coverage c = run_pattern(AA_PATTERN2D_HALF_PLANE, angles[i]);
		sum[0] += c.error[0] / n;
		sum[1] += c.error[1] / n;
		printf("  half-plane %4.0f deg: none %.4f, cmaa2 %.4f mean abs coverage error (x%.2f)\n", angles[i],
		       c.error[0], c.error[1], c.error[1] / c.error[0]);
		if (!(c.error[1] < 0.8 * c.error[0]))
			fail_msg("%g deg: cmaa2 %.4f is not below 0.8 x none (%.4f)", angles[i], c.error[1], c.error[0]);
	}
	printf("  mean over these angles: none %.4f, cmaa2 %.4f\n", sum[0], sum[1]);
	assert_true(sum[1] < 0.6 * sum[0]);
}

/* An edge on pixel boundaries has no step: the output equals the input exactly. */
static void test_aligned_edge_untouched(void **state)
{
	(void)state;
	struct fixture_coverage c = run_pattern(AA_PATTERN2D_HALF_PLANE, 0.0);
	printf("  half-plane 0 deg: largest change %.6f\n", c.max_change);
	assert_true(c.max_change < 1e-6);
	c = run_pattern(AA_PATTERN2D_HALF_PLANE, 90.0);
	printf("  half-plane 90 deg: largest change %.6f\n", c.max_change);
	assert_true(c.max_change < 1e-6);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_parameters),
		cmocka_unit_test(test_hard_edges),
		cmocka_unit_test(test_textures_kept),
		cmocka_unit_test(test_slanted_edges),
		cmocka_unit_test(test_aligned_edge_untouched),
	};
	return fixture_status(cmocka_run_group_tests(tests, fixture_setup, fixture_teardown));
}
