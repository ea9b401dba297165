/* SMAA on the real device: its parameters, what it needs and allocates, its passes, and its output.
 * Every preset and edge mode beats `none` on hard-edges; on flat 2D patterns with exact coverage it
 * leaves a pixel-aligned edge untouched (no shift, no darkening) and reduces the error of slanted edges.
 * The T2x, S2x and 4x modes: where each samples and which area texture slots go with each sample, and on
 * a still camera S2x beats 1x, T2x's second frame reaches S2x's 2-sample quality and 4x beats both; on a
 * moving camera the reprojected history keeps T2x near 1x and 4x above it. */
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
#include "methods/smaa.h"
#include "gpu/sample_positions.h"



static void test_parameters(void **state)
{
	(void)state;
	const struct aa_method *m;
	struct aa_method_params p;
	struct aa_error err = {0};
	assert_int_equal(aa_method_parse("smaa:preset=extreme", "methods[0]", &m, &p, &err), -1);
	assert_int_equal(err.code, AA_ERR_INVALID);
	if (!strstr(err.message, "low") || !strstr(err.message, "medium") || !strstr(err.message, "high") ||
	    !strstr(err.message, "ultra"))
		fail_msg("the message does not list the presets: %s", err.message);
	assert_int_equal(aa_method_parse("smaa:edge=normals", "methods[0]", &m, &p, &err), -1);
	assert_int_equal(aa_method_parse("smaa:threshold=0.9", "methods[0]", &m, &p, &err), -1);

	/* defaults: high preset, luma edges, no depth needed; depth edges ask the plan for depth */
	assert_int_equal(aa_method_parse("smaa", "methods[0]", &m, &p, &err), 0);
	char label[AA_LABEL_MAX];
	aa_method_label(m, &p, label, sizeof label);
	assert_string_equal(label, "smaa");
	assert_int_equal(m->needs_fn(&p) & AA_NEED_DEPTH, 0);
	assert_int_equal(aa_method_parse("smaa:edge=depth,preset=ultra", "methods[0]", &m, &p, &err), 0);
	assert_true(m->needs_fn(&p) & AA_NEED_DEPTH);
	aa_method_label(m, &p, label, sizeof label);
	assert_string_equal(label, "smaa:preset=ultra,edge=depth");
}

static const struct aa_memory_item *find_memory(const struct aa_method_result *m, const char *name)
{
	for (int i = 0; i < m->memory_count; i++)
		if (strcmp(m->memory[i].name, name) == 0)
			return &m->memory[i];
	return NULL;
}

/* Every preset and edge mode beats no AA on hard-edges, with its own passes timed and every image
 * (the look-up textures included) counted. */
static void test_hard_edges(void **state)
{
	(void)state;
	const char *methods[] = {"none", "smaa", "smaa:preset=low", "smaa:preset=medium", "smaa:preset=ultra",
				 "smaa:edge=color", "smaa:edge=depth"};
	const int n = (int)(sizeof methods / sizeof methods[0]);
	struct aa_job_spec spec;
	fixture_spec(&spec, "hard-edges", methods, n, 160, 90, 1, 32);
	struct aa_job_result *r = fixture_run(&spec, NULL, NULL, NULL);
	double none = r->methods[0].frames[0].metrics.psnr;
	printf("  hard-edges 160x90: none %.2f dB\n", none);
	for (int i = 1; i < n; i++) {
		const struct aa_method_result *m = &r->methods[i];
		const struct aa_frame_result *f = &m->frames[0];
		printf("  %-28s %.2f dB  %.2f ms  %.2f MB  (%s)\n", m->label, f->metrics.psnr, f->gpu_ms,
		       m->memory_bytes / 1048576.0, m->path_taken);
		assert_int_equal(f->nonfinite, 0);
		if (!(f->metrics.psnr > none))
			fail_msg("%s: %.2f dB does not beat none (%.2f dB)", m->label, f->metrics.psnr, none);
		/* the scene's shadow map (hard-edges has a shadow-casting light), then SMAA's own passes */
		const char *passes[] = {"shadow-map", "scene", "smaa-edges", "smaa-weights", "smaa-blend"};
		int first = f->pass_count == 5 ? 0 : 1;
		assert_int_equal(f->pass_count, 5 - first);
		for (int k = 0; k < f->pass_count; k++) {
			assert_string_equal(f->passes[k].name, passes[first + k]);
			assert_true(f->passes[k].gpu_ms > 0.0);
		}
		const struct aa_memory_item *area = find_memory(m, "area texture");
		const struct aa_memory_item *search = find_memory(m, "search texture");
		assert_non_null(area);
		assert_non_null(search);
		assert_true(area->bytes >= 160 * 560 * 2);
		assert_true(search->bytes >= 64 * 16);
		assert_non_null(find_memory(m, "edges"));
		assert_non_null(find_memory(m, "blend weights"));
		assert_non_null(find_memory(m, "edge queue"));
		assert_non_null(find_memory(m, "blend mask (depth)"));
		assert_true(m->memory_bytes > r->methods[0].memory_bytes + 160 * 90 * (2 + 4 + 8));
	}
	fixture_free(r);
}

/* The modes' labels, needs and alpha rules, and their sample tables: S2x's samples are the standard 2x
 * positions, T2x's jitter pair is the same two points on alternate frames, 4x moves both by an eighth of
 * a pixel, and each sample's orthogonal area slots are the ones whose offset is minus the sample's offset
 * (notes/smaa.md §3.9: a swapped jitter or a wrong slot fails here, and on the images below). */
static void test_mode_tables(void **state)
{
	(void)state;
	const struct aa_method *m;
	struct aa_method_params p;
	struct aa_error err = {0};
	assert_int_equal(aa_method_parse("smaa:mode=8x", "methods[0]", &m, &p, &err), -1);
	if (!strstr(err.message, "t2x") || !strstr(err.message, "s2x") || !strstr(err.message, "4x"))
		fail_msg("the message does not list the modes: %s", err.message);
	static const struct {
		const char *text, *label, *rule;
		unsigned needs;
	} modes[] = {
		{"smaa:mode=1x", "smaa", "per-pixel", 0},
		{"smaa:mode=t2x", "smaa:mode=t2x", "per-sample", AA_NEED_VELOCITY | AA_NEED_HISTORY},
		{"smaa:mode=s2x", "smaa:mode=s2x", "per-pixel", AA_NEED_MSAA},
		{"smaa:mode=4x,preset=ultra", "smaa:preset=ultra,mode=4x", "per-pixel",
		 AA_NEED_VELOCITY | AA_NEED_HISTORY | AA_NEED_MSAA},
	};
	for (size_t i = 0; i < sizeof modes / sizeof modes[0]; i++) {
		assert_int_equal(aa_method_parse(modes[i].text, "methods[0]", &m, &p, &err), 0);
		char label[AA_LABEL_MAX];
		aa_method_label(m, &p, label, sizeof label);
		assert_string_equal(label, modes[i].label);
		assert_int_equal(m->needs_fn(&p), modes[i].needs);
		assert_string_equal(aa_alpha_rule_name(aa_method_alpha_rule(m, &p)), modes[i].rule);
	}

	static const float ortho_offset[7] = {0.0f, -0.25f, 0.25f, -0.125f, 0.125f, -0.375f, 0.375f};
	const float (*two)[2] = aa_standard_sample_positions(2);
	for (int frame = 0; frame < 4; frame++) {
		int n;
		const struct aa_smaa_sample *x1 = aa_smaa_frame_samples(AA_SMAA_1X, frame, &n);
		assert_int_equal(n, 1);
		for (int k = 0; k < 4; k++)
			assert_int_equal(x1->indices[k], 0);
		const struct aa_smaa_sample *s2 = aa_smaa_frame_samples(AA_SMAA_S2X, frame, &n);
		assert_int_equal(n, 2);
		const struct aa_smaa_sample *t2 = aa_smaa_frame_samples(AA_SMAA_T2X, frame, &n);
		assert_int_equal(n, 1);
		const struct aa_smaa_sample *x4 = aa_smaa_frame_samples(AA_SMAA_4X, frame, &n);
		assert_int_equal(n, 2);
		/* T2x's frame parity f samples where S2x's sample f does, with its slots */
		assert_memory_equal(t2, &s2[frame & 1], sizeof *t2);
		float jitter = (frame & 1) ? -0.125f : 0.125f;
		for (int i = 0; i < 2; i++) {
			assert_true(s2[i].offset[0] == two[i][0] - 0.5f && s2[i].offset[1] == two[i][1] - 0.5f);
			assert_true(x4[i].offset[0] == s2[i].offset[0] + jitter);
			assert_true(x4[i].offset[1] == s2[i].offset[1] - jitter);
			const struct aa_smaa_sample *all[2] = {&s2[i], &x4[i]};
			for (int k = 0; k < 2; k++) {
				/* x: vertical lines, across them x; y: horizontal lines, across them y */
				if (ortho_offset[all[k]->indices[0]] != -all[k]->offset[0] ||
				    ortho_offset[all[k]->indices[1]] != -all[k]->offset[1])
					fail_msg("frame %d sample %d: slots (%d, %d) are not those of offset (%g, %g)",
						 frame, i, all[k]->indices[0], all[k]->indices[1],
						 (double)all[k]->offset[0], (double)all[k]->offset[1]);
			}
		}
		/* the published diagonal slots: T2x/S2x (1, 0) and (2, 0); 4x (1, 3), (2, 3) then (1, 4), (2, 4) */
		for (int i = 0; i < 2; i++) {
			assert_int_equal(s2[i].indices[2], i + 1);
			assert_int_equal(s2[i].indices[3], 0);
			assert_int_equal(x4[i].indices[2], i + 1);
			assert_int_equal(x4[i].indices[3], 3 + (frame & 1));
		}
	}
}

static double frame_psnr(const struct aa_job_result *r, int method, int frame)
{
	return r->methods[method].frames[frame].metrics.psnr;
}

/* A still camera, 2 frames. S2x beats 1x (sub-pixel wires: by far); T2x's second frame, the two jittered
 * frames blended, reaches S2x's quality (the same two samples) and beats 1x and 2x MSAA; 4x's second frame
 * beats S2x. A jitter of the wrong sign, slots swapped between the samples or a resolve that drops the
 * history each fail one of these (see the mutations in tests/integration/local.mk's notes). Each mode
 * times its own passes and counts its images. */
static void test_modes_still_camera(void **state)
{
	(void)state;
	const char *methods[] = {"smaa", "smaa:mode=t2x", "smaa:mode=s2x", "smaa:mode=4x", "msaa:2"};
	enum { X1, T2X, S2X, X4, MSAA2 };
	const char *scenes[] = {"thin-wires", "hard-edges"};
	for (int sc = 0; sc < 2; sc++) {
		struct aa_job_spec spec;
		fixture_spec(&spec, scenes[sc], methods, 5, 320, 180, 2, 32);
		snprintf(spec.path, sizeof spec.path, "static");
		struct aa_job_result *r = fixture_run(&spec, NULL, NULL, NULL);
		double x1 = frame_psnr(r, X1, 0), s2x = frame_psnr(r, S2X, 0), msaa2 = frame_psnr(r, MSAA2, 0);
		double t2x = frame_psnr(r, T2X, 1), x4 = frame_psnr(r, X4, 1);
		printf("  %s 320x180 static: 1x %.2f, t2x %.2f -> %.2f, s2x %.2f, 4x %.2f -> %.2f, msaa:2 %.2f dB\n",
		       scenes[sc], x1, frame_psnr(r, T2X, 0), t2x, s2x, frame_psnr(r, X4, 0), x4, msaa2);
		double margin = sc == 0 ? 3.0 : 1.0; /* sub-pixel wires gain most from a second sample */
		if (!(s2x > x1 + margin))
			fail_msg("%s: s2x %.2f dB does not beat 1x %.2f dB by %.1f dB", scenes[sc], s2x, x1, margin);
		if (!(t2x > x1 + margin) || !(t2x > msaa2))
			fail_msg("%s: t2x's second frame %.2f dB does not beat 1x %.2f dB by %.1f dB and msaa:2 %.2f dB",
				 scenes[sc], t2x, x1, margin, msaa2);
		if (!(fabs(t2x - s2x) < 1.0))
			fail_msg("%s: t2x's second frame %.2f dB is not within 1 dB of s2x %.2f dB", scenes[sc], t2x,
				 s2x);
		if (!(x4 > s2x + 0.2))
			fail_msg("%s: 4x's second frame %.2f dB does not beat s2x %.2f dB", scenes[sc], x4, s2x);
		for (int i = T2X; i <= X4; i++) {
			const struct aa_method_result *m = &r->methods[i];
			const struct aa_frame_result *f = &m->frames[1];
			assert_int_equal(f->nonfinite, 0);
			int chains = i == T2X ? 1 : 2;
			/* scenes, then edges/weights/blend per sample, then the resolve; maybe a shadow map first */
			int first = f->passes[0].name[0] == 's' && strcmp(f->passes[0].name, "shadow-map") == 0;
			assert_int_equal(f->pass_count, first + chains * 4 + 1);
			assert_string_equal(f->passes[f->pass_count - 1].name, "smaa-resolve");
			for (int k = 0; k < f->pass_count; k++)
				assert_true(f->passes[k].gpu_ms > 0.0);
			assert_non_null(find_memory(m, "resolved colour"));
			assert_non_null(find_memory(m, chains == 2 ? "blended sample 1" : "blended colour"));
			if (i != S2X)
				assert_non_null(find_memory(m, chains == 2 ? "previous sample 1" : "previous frame"));
			else
				assert_null(find_memory(m, "previous sample 1"));
		}
		fixture_free(r);
	}
}

/* A moving camera (hard-edges' sweep, 4 frames): the temporal modes read the previous frame at p - velocity.
 * Over frames 2-3, T2x stays within 0.5 dB of 1x and 4x beats 1x by 1 dB; history read at p + velocity
 * (a reprojection the wrong way) costs both about 1.7 dB and fails this. */
static void test_modes_moving_camera(void **state)
{
	(void)state;
	const char *methods[] = {"smaa", "smaa:mode=t2x", "smaa:mode=4x"};
	struct aa_job_spec spec;
	fixture_spec(&spec, "hard-edges", methods, 3, 320, 180, 4, 32);
	snprintf(spec.path, sizeof spec.path, "sweep");
	struct aa_job_result *r = fixture_run(&spec, NULL, NULL, NULL);
	double mean[3];
	for (int i = 0; i < 3; i++)
		mean[i] = 0.5 * (frame_psnr(r, i, 2) + frame_psnr(r, i, 3));
	printf("  hard-edges sweep 320x180, frames 2-3: 1x %.2f, t2x %.2f, 4x %.2f dB\n", mean[0], mean[1], mean[2]);
	if (!(mean[1] > mean[0] - 0.5))
		fail_msg("t2x %.2f dB is more than 0.5 dB below 1x %.2f dB on a moving camera", mean[1], mean[0]);
	if (!(mean[2] > mean[0] + 1.0))
		fail_msg("4x %.2f dB does not beat 1x %.2f dB by 1 dB on a moving camera", mean[2], mean[0]);
	fixture_free(r);
}

static struct fixture_coverage run_half_plane(double angle)
{
	return fixture_pattern_coverage(AA_PATTERN2D_HALF_PLANE, angle, "smaa", 64);
}

/* Slanted edges get closer to the exact coverage. At exactly 45 degrees the edge runs through pixel
 * centres, so `none` draws a perfect staircase whose revectorised line (through the step midpoints) lies
 * half a pixel off the true edge: SMAA cannot beat the tie there and is only required to stay close. */
static void test_slanted_edges(void **state)
{
	(void)state;
	const double angles[] = {3.0, 10.0, 20.0, 30.0, 40.0, 44.0, 45.0, 46.0, 50.0, 60.0, 70.0, 80.0, 87.0};
	const int n = (int)(sizeof angles / sizeof angles[0]);
	double sum[2] = {0, 0};
	for (int i = 0; i < n; i++) {
		struct fixture_coverage c = run_half_plane(angles[i]);
		sum[0] += c.error[0] / n;
		sum[1] += c.error[1] / n;
		printf("  half-plane %4.0f deg: none %.4f, smaa %.4f mean abs coverage error (x%.2f)\n", angles[i],
		       c.error[0], c.error[1], c.error[1] / c.error[0]);
		double limit = angles[i] == 45.0 ? 1.3 : fabs(angles[i] - 45.0) > 30.0 ? 0.6 : 1.0;
		if (!(c.error[1] < limit * c.error[0]))
			fail_msg("%g deg: smaa %.4f is not below %.1f x none (%.4f)", angles[i], c.error[1], limit,
				 c.error[0]);
	}
	printf("  mean over these angles: none %.4f, smaa %.4f\n", sum[0], sum[1]);
	assert_true(sum[1] < 0.6 * sum[0]);
}

/* An edge on pixel boundaries has nothing to revectorise: the output must equal the input exactly. */
static void test_aligned_edge_untouched(void **state)
{
	(void)state;
	struct fixture_coverage c = run_half_plane(0.0);
	printf("  half-plane 0 deg: none %.4f, smaa %.4f, largest change %.6f\n", c.error[0], c.error[1],
	       c.max_change);
	assert_true(c.max_change < 1e-6);
}

/* The blend pass runs only where the edge pass's mask lets it: the pixels with an edge of their own, and
 * those left of a vertical edge or above a horizontal one, whose blend reads their neighbour's weights.
 * A white half-plane on black: SMAA blends across the edge both ways, as many pixels get brighter (the
 * black side) as darker (the white side); a mask of the edge pixels alone, or one missing the right or
 * the bottom neighbour, leaves (part of) one side as it was, for a near-vertical or near-horizontal
 * edge. */
static void test_blend_reaches_both_sides(void **state)
{
	(void)state;
	const double angles[] = {10.0, 80.0};
	for (int i = 0; i < 2; i++) {
		struct fixture_coverage c = run_half_plane(angles[i]);
		printf("  half-plane %2.0f deg: %d pixels brighter, %d darker than none\n", angles[i], c.brighter,
		       c.darker);
		if (c.brighter < 8 || c.darker < 8 || c.brighter < 0.8 * c.darker || c.darker < 0.8 * c.brighter)
			fail_msg("%g deg: %d brighter and %d darker pixels: the blend skipped one side of the edge",
				 angles[i], c.brighter, c.darker);
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_parameters),
		cmocka_unit_test(test_hard_edges),
		cmocka_unit_test(test_mode_tables),
		cmocka_unit_test(test_modes_still_camera),
		cmocka_unit_test(test_modes_moving_camera),
		cmocka_unit_test(test_slanted_edges),
		cmocka_unit_test(test_aligned_edge_untouched),
		cmocka_unit_test(test_blend_reaches_both_sides),
	};
	return fixture_status(cmocka_run_group_tests(tests, fixture_setup, fixture_teardown));
}
