/* SMAA 1x on the real device: its parameters, what it needs and allocates, its passes, and its output.
 * Every preset and edge mode beats `none` on hard-edges; on flat 2D patterns with exact coverage it
 * leaves a pixel-aligned edge untouched (no shift, no darkening) and reduces the error of slanted edges. */
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

struct capture {
	const double *coverage;
	int size;
	double error[2]; /* mean abs coverage error of none and smaa */
	double max_change;  /* largest |smaa - none| over the image */
	int brighter, darker; /* pixels smaa made brighter / darker than none by more than 1e-3 */
	float *none;
};

static int on_frame(const struct aa_event *ev, void *user)
{
	struct capture *c = user;
	if (ev->type != AA_EVENT_METHOD_FRAME || ev->method_index > 1)
		return 0;
	const struct aa_image_rgbaf *img = ev->linear;
	int n = c->size * c->size;
	double sum = 0;
	for (int i = 0; i < n; i++)
		sum += fabs(img->pixels[i * 4] - c->coverage[i]);
	c->error[ev->method_index] = sum / n;
	if (ev->method_index == 0)
		for (int i = 0; i < n; i++)
			c->none[i] = img->pixels[i * 4];
	else
		for (int i = 0; i < n; i++) {
			double d = fabs(img->pixels[i * 4] - c->none[i]);
			c->max_change = d > c->max_change ? d : c->max_change;
			c->brighter += img->pixels[i * 4] > c->none[i] + 1e-3;
			c->darker += img->pixels[i * 4] < c->none[i] - 1e-3;
		}
	return 0;
}

static struct capture run_half_plane(double angle)
{
	enum { SIZE = 64 };
	static double coverage[SIZE * SIZE];
	static float none[SIZE * SIZE];
	struct aa_polygon2d polys[16];
	int n = aa_pattern2d_make(AA_PATTERN2D_HALF_PLANE, angle, 0, 0, SIZE, SIZE, polys);
	aa_exact_coverage(polys, n, SIZE, SIZE, coverage);
	struct aa_scene *scene;
	struct aa_error err = {0};
	float fg[3] = {1, 1, 1}, bg[3] = {0, 0, 0};
	assert_int_equal(aa_scene_from_polygons(polys, n, SIZE, SIZE, fg, bg, &scene, &err), 0);
	const char *methods[] = {"none", "smaa"};
	struct aa_job_spec spec;
	fixture_spec(&spec, "half-plane", methods, 2, SIZE, SIZE, 1, 2);
	struct capture c = {.coverage = coverage, .size = SIZE, .none = none};
	fixture_free(fixture_run(&spec, scene, on_frame, &c));
	aa_scene_free(scene);
	return c;
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
		struct capture c = run_half_plane(angles[i]);
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
	struct capture c = run_half_plane(0.0);
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
		struct capture c = run_half_plane(angles[i]);
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
		cmocka_unit_test(test_slanted_edges),
		cmocka_unit_test(test_aligned_edge_untouched),
		cmocka_unit_test(test_blend_reaches_both_sides),
	};
	return fixture_status(cmocka_run_group_tests(tests, fixture_setup, fixture_teardown));
}
