/* Exact coverage: known areas of rectangles, half-planes, bars, stars and random polygons. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>

#include "reference/exact_coverage.h"

#define PI 3.14159265358979323846

static double *coverage_of(const struct aa_polygon2d *polys, int count, int width, int height)
{
	double *coverage = malloc(sizeof(double) * width * height);
	assert_non_null(coverage);
	aa_exact_coverage(polys, count, width, height, coverage);
	return coverage;
}

static double total_of(const double *coverage, int width, int height)
{
	double total = 0.0;
	for (int i = 0; i < width * height; i++)
		total += coverage[i];
	return total;
}

static void assert_all_in_unit_range(const double *coverage, int width, int height)
{
	for (int i = 0; i < width * height; i++)
		assert_true(coverage[i] >= 0.0 && coverage[i] <= 1.0);
}

static struct aa_polygon2d rectangle(double x0, double y0, double x1, double y1)
{
	return (struct aa_polygon2d){ .count = 4, .xy = { { x0, y0 }, { x1, y0 }, { x1, y1 }, { x0, y1 } } };
}

static double shoelace(const struct aa_polygon2d *p)
{
	double twice = 0.0;
	for (int i = 0; i < p->count; i++) {
		int j = (i + 1) % p->count;
		twice += p->xy[i][0] * p->xy[j][1] - p->xy[j][0] * p->xy[i][1];
	}
	return fabs(twice) / 2;
}

static void test_vertical_edge_at_quarter_pixel(void **state)
{
	(void)state;
	int w = 20, h = 6;
	struct aa_polygon2d left = rectangle(0, 0, 10.25, h);
	double *c = coverage_of(&left, 1, w, h);
	for (int y = 0; y < h; y++) {
		assert_true(c[y * w + 9] == 1.0);
		assert_true(fabs(c[y * w + 10] - 0.25) < 1e-12);
		assert_true(c[y * w + 11] == 0.0);
	}
	assert_true(fabs(total_of(c, w, h) - 10.25 * h) < 1e-9);
	free(c);
}

static void test_half_plane_side_and_centre(void **state)
{
	(void)state;
	/* 90 degrees on an odd width: the line runs down the middle of column 10, the left is covered. */
	int w = 21, h = 8;
	struct aa_polygon2d polys[16];
	assert_int_equal(aa_pattern2d_make(AA_PATTERN2D_HALF_PLANE, 90, 0, 0, w, h, polys), 1);
	double *c = coverage_of(polys, 1, w, h);
	for (int y = 0; y < h; y++) {
		assert_true(fabs(c[y * w + 0] - 1.0) < 1e-12);
		assert_true(fabs(c[y * w + 10] - 0.5) < 1e-12);
		assert_true(fabs(c[y * w + 20]) < 1e-12);
	}
	free(c);
	/* 0 degrees: the top half is covered. */
	assert_int_equal(aa_pattern2d_make(AA_PATTERN2D_HALF_PLANE, 0, 0, 0, w, h, polys), 1);
	c = coverage_of(polys, 1, w, h);
	assert_true(fabs(c[0] - 1.0) < 1e-12 && fabs(c[(h - 1) * w]) < 1e-12);
	free(c);
}

static void test_half_plane_area_is_half_the_image(void **state)
{
	(void)state;
	/* Any line through the centre halves the rectangle (point symmetry). */
	const double angles[] = { 45, 0, 17, 90, 133.7, 270, -30 };
	int w = 64, h = 48;
	for (size_t a = 0; a < sizeof angles / sizeof angles[0]; a++) {
		struct aa_polygon2d polys[16];
		assert_int_equal(aa_pattern2d_make(AA_PATTERN2D_HALF_PLANE, angles[a], 0, 0, w, h, polys), 1);
		double *c = coverage_of(polys, 1, w, h);
		assert_true(fabs(total_of(c, w, h) - w * h / 2.0) < 1e-9);
		assert_all_in_unit_range(c, w, h);
		free(c);
	}
}

static void test_bar_area(void **state)
{
	(void)state;
	struct aa_polygon2d polys[16];
	/* Horizontal: thickness times the image width. */
	int w = 64, h = 48;
	assert_int_equal(aa_pattern2d_make(AA_PATTERN2D_BAR, 0, 3, 0, w, h, polys), 1);
	double *c = coverage_of(polys, 1, w, h);
	assert_true(fabs(total_of(c, w, h) - 3.0 * w) < 1e-9);
	assert_all_in_unit_range(c, w, h);
	free(c);
	/* 30 degrees in a wide image: both ends are cut by the top and bottom edges, making a
	 * parallelogram of thickness 2.5 and centre-line length h / sin 30 = 100. */
	w = 200;
	h = 50;
	assert_int_equal(aa_pattern2d_make(AA_PATTERN2D_BAR, 30, 2.5, 0, w, h, polys), 1);
	c = coverage_of(polys, 1, w, h);
	assert_true(fabs(total_of(c, w, h) - 2.5 * 100.0) < 1e-9);
	assert_all_in_unit_range(c, w, h);
	free(c);
	/* Zero thickness is nothing. */
	assert_int_equal(aa_pattern2d_make(AA_PATTERN2D_BAR, 30, 0, 0, w, h, polys), 0);
}

static void test_star_is_symmetric(void **state)
{
	(void)state;
	int w = 64, h = 64;
	struct aa_polygon2d polys[16];
	/* Four spokes repeat every 90 degrees: rotating the square image by 90 degrees about its centre,
	 * which sends pixel (i, j) to (j, w-1-i), leaves the coverage unchanged. */
	int n = aa_pattern2d_make(AA_PATTERN2D_STAR, 10, 0, 4, w, h, polys);
	assert_int_equal(n, 4);
	double *c = coverage_of(polys, n, w, h);
	for (int j = 0; j < h; j++)
		for (int i = 0; i < w; i++)
			assert_true(fabs(c[j * w + i] - c[(w - 1 - i) * w + j]) < 1e-9);
	free(c);
	/* Sixteen spokes, an even count: a half turn maps wedges onto wedges. */
	n = aa_pattern2d_make(AA_PATTERN2D_STAR, 3, 0, 16, w, h, polys);
	assert_int_equal(n, 16);
	c = coverage_of(polys, n, w, h);
	assert_all_in_unit_range(c, w, h);
	for (int j = 0; j < h; j++)
		for (int i = 0; i < w; i++)
			assert_true(fabs(c[j * w + i] - c[(h - 1 - j) * w + (w - 1 - i)]) < 1e-9);
	free(c);
	n = aa_pattern2d_make(AA_PATTERN2D_STAR, 25, 0, 5, w, h, polys);
	assert_int_equal(n, 5);
	c = coverage_of(polys, n, w, h);
	/* An odd spoke count maps each wedge onto a gap under a half turn: opposite pixels sum to 1. */
	for (int j = 0; j < h; j++)
		for (int i = 0; i < w; i++)
			assert_true(fabs(c[j * w + i] + c[(h - 1 - j) * w + (w - 1 - i)] - 1.0) < 1e-9);
	free(c);
	assert_int_equal(aa_pattern2d_make(AA_PATTERN2D_STAR, 0, 0, 0, w, h, polys), 0);
	assert_int_equal(aa_pattern2d_make(AA_PATTERN2D_STAR, 0, 0, 17, w, h, polys), 0);
}

/* Deterministic pseudo-random numbers in [0, 1). */
static double next_uniform(uint32_t *state)
{
	uint32_t x = *state;
	x ^= x << 13;
	x ^= x >> 17;
	x ^= x << 5;
	*state = x;
	return x / 4294967296.0;
}

static void test_polygons_inside_keep_their_area(void **state)
{
	(void)state;
	int w = 50, h = 40;
	uint32_t seed = 2024;
	for (int trial = 0; trial < 200; trial++) {
		/* Regular n-gon at a random place, size and rotation, fully inside the image. */
		struct aa_polygon2d p = { .count = 3 + trial % 14 };
		double r = 0.3 + 12.0 * next_uniform(&seed);
		double cx = r + (w - 2 * r) * next_uniform(&seed), cy = r + (h - 2 * r) * next_uniform(&seed);
		double phase = 2 * PI * next_uniform(&seed);
		for (int i = 0; i < p.count; i++) {
			double a = phase + 2 * PI * i / p.count;
			p.xy[i][0] = cx + r * cos(a);
			p.xy[i][1] = cy + r * sin(a);
		}
		double *c = coverage_of(&p, 1, w, h);
		assert_true(fabs(total_of(c, w, h) - shoelace(&p)) < 1e-9);
		assert_all_in_unit_range(c, w, h);
		free(c);
	}
}

static void test_edge_cases(void **state)
{
	(void)state;
	int w = 10, h = 10;
	/* Partly outside: only the part inside counts. */
	struct aa_polygon2d corner = rectangle(-5, -5, 2.5, 3);
	double *c = coverage_of(&corner, 1, w, h);
	assert_true(fabs(total_of(c, w, h) - 2.5 * 3) < 1e-12);
	assert_true(fabs(c[2] - 0.5) < 1e-12);
	free(c);
	/* Past the right and bottom borders too: the last column and row are covered in full. */
	struct aa_polygon2d far_corner = rectangle(7.5, 6, 15, 20);
	c = coverage_of(&far_corner, 1, w, h);
	assert_true(fabs(total_of(c, w, h) - 2.5 * 4) < 1e-12);
	for (int y = 6; y < h; y++) {
		assert_true(c[y * w + 7] == 0.5);
		assert_true(c[y * w + 8] == 1.0 && c[y * w + 9] == 1.0);
	}
	free(c);
	/* Entirely outside, degenerate, non-finite and absurdly large polygons add nothing. */
	struct aa_polygon2d nothing[4] = { rectangle(20, 20, 30, 30), { .count = 2 }, rectangle(1, 1, NAN, 4),
					   rectangle(-1e20, -1e20, 1e20, 1e20) };
	c = coverage_of(nothing, 4, w, h);
	assert_true(total_of(c, w, h) == 0.0);
	free(c);
	/* Winding direction does not matter; two polygons sharing an edge fill every pixel exactly once. */
	struct aa_polygon2d halves[2] = {
		{ .count = 3, .xy = { { 0, 0 }, { 10, 0 }, { 0, 10 } } },
		{ .count = 3, .xy = { { 10, 0 }, { 0, 10 }, { 10, 10 } } },
	};
	c = coverage_of(halves, 2, w, h);
	for (int i = 0; i < w * h; i++)
		assert_true(fabs(c[i] - 1.0) < 1e-12);
	free(c);
	/* A concave L-shape still gets its exact area. */
	struct aa_polygon2d ell = { .count = 6, .xy = { { 1, 1 }, { 8, 1 }, { 8, 3.5 }, { 3.5, 3.5 }, { 3.5, 9 }, { 1, 9 } } };
	c = coverage_of(&ell, 1, w, h);
	assert_true(fabs(total_of(c, w, h) - shoelace(&ell)) < 1e-9);
	free(c);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_vertical_edge_at_quarter_pixel),
		cmocka_unit_test(test_half_plane_side_and_centre),
		cmocka_unit_test(test_half_plane_area_is_half_the_image),
		cmocka_unit_test(test_bar_area),
		cmocka_unit_test(test_star_is_symmetric),
		cmocka_unit_test(test_polygons_inside_keep_their_area),
		cmocka_unit_test(test_edge_cases),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
