/* FLIP against its published specification: filter taps, colour transforms and constants
 * at their published float32 values, the map against a direct, unoptimised evaluation of the published formulas
 * (bit for bit, at several sizes, strip widths, ppd values and thread counts), known answers, pooling,
 * the colour map and HDR-FLIP's exposure loop. The reference test images are not available here, so the
 * published means (LDR 0.159691, HDR 0.283478) are not checked. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "metrics/flip.h"

#include "flip_images.h"

/* ------------------------------------------------------------------------ a direct evaluation of the notes */

static int clampi(int v, int lo, int hi)
{
	return v < lo ? lo : v > hi ? hi : v;
}

/* Separable filtering on whole planes with clamped indices; sums start at 0 and add taps i = -r..r. */
static void naive_flip(const struct aa_image_rgba8 *ref, const struct aa_image_rgba8 *test, float ppd, float *map)
{
	struct aa_flip_filters f;
	assert_int_equal(aa_flip_filters_init(ppd, &f), 0);
	const int w = ref->width, h = ref->height, r = f.csf_radius, R = f.feature_radius;
	const size_t n = (size_t)w * h;
	enum { Y, CX, CZ, YN, HY, HCX, HCZ1, HCZ2, HDX, HDDX, HG, FY, FCX, FCZ, DX, DDX, DY, DDY, PLANES };
	float *p[2][PLANES];
	for (int im = 0; im < 2; im++) {
		const struct aa_image_rgba8 *src = im == 0 ? ref : test;
		for (int k = 0; k < PLANES; k++)
			p[im][k] = malloc(n * sizeof(float));
		for (size_t i = 0; i < n; i++) {
			float rgb[3], xyz[3], ycc[3];
			for (int c = 0; c < 3; c++)
				rgb[c] = aa_flip_srgb_to_linear(src->pixels[4 * i + c] / 255.0f);
			aa_flip_linear_to_xyz(rgb, xyz);
			aa_flip_xyz_to_ycxcz(xyz, ycc);
			p[im][Y][i] = ycc[0];
			p[im][CX][i] = ycc[1];
			p[im][CZ][i] = ycc[2];
			p[im][YN][i] = ycc[0] * (1.0f / 116.0f) + (16.0f / 116.0f);
		}
		for (int y = 0; y < h; y++)
			for (int x = 0; x < w; x++) {
				float s[7] = { 0 };
				for (int i = -r; i <= r; i++) {
					size_t j = (size_t)y * w + clampi(x + i, 0, w - 1);
					s[0] += f.csf_y[i + r] * p[im][Y][j];
					s[1] += f.csf_cx[i + r] * p[im][CX][j];
					s[2] += f.csf_cz1[i + r] * p[im][CZ][j];
					s[3] += f.csf_cz2[i + r] * p[im][CZ][j];
				}
				for (int i = -R; i <= R; i++) {
					size_t j = (size_t)y * w + clampi(x + i, 0, w - 1);
					s[4] += f.dg[i + R] * p[im][YN][j];
					s[5] += f.ddg[i + R] * p[im][YN][j];
					s[6] += f.g[i + R] * p[im][YN][j];
				}
				for (int k = 0; k < 7; k++)
					p[im][HY + k][(size_t)y * w + x] = s[k];
			}
		for (int y = 0; y < h; y++)
			for (int x = 0; x < w; x++) {
				float yf = 0, cxf = 0, cz1 = 0, cz2 = 0, dx = 0, ddx = 0, dy = 0, ddy = 0;
				for (int i = -r; i <= r; i++) {
					size_t j = (size_t)clampi(y + i, 0, h - 1) * w + x;
					yf += f.csf_y[i + r] * p[im][HY][j];
					cxf += f.csf_cx[i + r] * p[im][HCX][j];
					cz1 += f.csf_cz1[i + r] * p[im][HCZ1][j];
					cz2 += f.csf_cz2[i + r] * p[im][HCZ2][j];
				}
				for (int i = -R; i <= R; i++) {
					size_t j = (size_t)clampi(y + i, 0, h - 1) * w + x;
					dx += f.g[i + R] * p[im][HDX][j];
					ddx += f.g[i + R] * p[im][HDDX][j];
					dy += f.dg[i + R] * p[im][HG][j];
					ddy += f.ddg[i + R] * p[im][HG][j];
				}
				size_t o = (size_t)y * w + x;
				p[im][FY][o] = yf;
				p[im][FCX][o] = cxf;
				p[im][FCZ][o] = cz1 + cz2;
				p[im][DX][o] = dx;
				p[im][DDX][o] = ddx;
				p[im][DY][o] = dy;
				p[im][DDY][o] = ddy;
			}
	}
	for (size_t i = 0; i < n; i++) {
		float a[3] = { p[0][FY][i], p[0][FCX][i], p[0][FCZ][i] }, b[3] = { p[1][FY][i], p[1][FCX][i], p[1][FCZ][i] };
		float cdiff = aa_flip_color_error(a, b);
		float edge[2], point[2];
		for (int im = 0; im < 2; im++) {
			edge[im] = sqrtf(p[im][DX][i] * p[im][DX][i] + p[im][DY][i] * p[im][DY][i]);
			point[im] = sqrtf(p[im][DDX][i] * p[im][DDX][i] + p[im][DDY][i] * p[im][DDY][i]);
		}
		float fdiff = aa_flip_feature_error(edge[0], edge[1], point[0], point[1]);
		map[i] = powf(cdiff, 1.0f - fdiff);
	}
	for (int im = 0; im < 2; im++)
		for (int k = 0; k < PLANES; k++)
			free(p[im][k]);
}

/* ------------------------------------------------------------------------ tests */

static void test_ppd(void **state)
{
	(void)state;
	assert_true(aa_flip_ppd(0.7f, 0.7f, 3840.0f) == AA_FLIP_DEFAULT_PPD);
	assert_true(AA_FLIP_DEFAULT_PPD == 0x1.0c1524p+6f);
	assert_float_equal(aa_flip_ppd(0.5f, 0.6f, 1920.0f), 27.925f, 1e-3);
}

static void test_csf_taps(void **state)
{
	(void)state;
	struct aa_flip_filters f;
	assert_int_equal(aa_flip_filters_init(AA_FLIP_DEFAULT_PPD, &f), 0);
	assert_int_equal(f.csf_radius, 10);
	const int c = 10;
	/* centre tap, tap +1 and -1 (the filters are symmetric), end taps +-10: exact float32 values */
	assert_true(f.csf_y[c] == 0.385760248f);
	assert_true(f.csf_y[c + 1] == 0.241703719f && f.csf_y[c - 1] == 0.241703719f);
	assert_float_equal(f.csf_y[c + 10], 1.918e-21f, 1e-24);
	assert_true(f.csf_cx[c] == 0.363269061f);
	assert_true(f.csf_cx[c + 1] == 0.239982337f);
	assert_float_equal(f.csf_cx[c - 10], 3.592e-19f, 1e-22);
	assert_true(f.csf_cz1[c] == 0.115442052f);
	assert_true(f.csf_cz1[c + 1] == 0.109271646f);
	assert_true(f.csf_cz1[c + 10] == 0.000475021166f && f.csf_cz1[c - 10] == 0.000475021166f);
	assert_true(f.csf_cz2[c] == 0.0816927925f);
	assert_true(f.csf_cz2[c + 1] == 0.0748192519f);
	assert_true(f.csf_cz2[c + 10] == 1.24492281e-05f);
	/* Y and Cx sum to 1; the Cz pair is normalised jointly: (sum cz1)^2 + (sum cz2)^2 = 1 */
	double sy = 0, s1 = 0, s2 = 0;
	for (int k = 0; k <= 20; k++) {
		sy += f.csf_y[k];
		s1 += f.csf_cz1[k];
		s2 += f.csf_cz2[k];
	}
	assert_float_equal(sy, 1.0, 1e-6);
	assert_float_equal(s1 * s1 + s2 * s2, 1.0, 1e-6);

	const float ppd[] = { 10, 30, 42, 100 };
	const int radius[] = { 2, 5, 6, 14 };
	for (int i = 0; i < 4; i++) {
		assert_int_equal(aa_flip_filters_init(ppd[i], &f), 0);
		assert_int_equal(f.csf_radius, radius[i]);
	}
	assert_int_equal(aa_flip_filters_init(0.0f, &f), -1);
	assert_int_equal(aa_flip_filters_init(NAN, &f), -1);
	assert_int_equal(aa_flip_filters_init(AA_FLIP_MAX_PPD * 2, &f), -1);
	assert_int_equal(aa_flip_filters_init(AA_FLIP_MAX_PPD, &f), 0);
	assert_true(f.csf_radius <= AA_FLIP_MAX_RADIUS && f.feature_radius <= AA_FLIP_MAX_RADIUS);
}

static void test_feature_taps(void **state)
{
	(void)state;
	struct aa_flip_filters f;
	assert_int_equal(aa_flip_filters_init(AA_FLIP_DEFAULT_PPD, &f), 0);
	assert_true(f.feature_sigma == 2.7478466f);
	assert_int_equal(f.feature_radius, 9);
	const int c = 9;
	assert_true(f.g[c] == 0.145257458f);
	assert_true(f.dg[c - 1] == 0.125649005f);
	assert_true(f.ddg[c] == -0.298901498f);
	assert_true(f.ddg[c + 9] == 0.0138061726f && f.ddg[c - 9] == 0.0138061726f);
	/* float summation makes the derivative slightly asymmetric, as in the reference */
	assert_true(f.dg[c - 2] == 0.206021681f);
	assert_true(f.dg[c + 2] == -0.206021667f);
	/* positive taps sum to +1 and negative ones to -1 */
	double pos = 0, neg = 0, pos2 = 0, neg2 = 0;
	for (int k = 0; k <= 18; k++) {
		*(f.dg[k] > 0 ? &pos : &neg) += f.dg[k];
		*(f.ddg[k] > 0 ? &pos2 : &neg2) += f.ddg[k];
	}
	assert_float_equal(pos, 1.0, 1e-6);
	assert_float_equal(neg, -1.0, 1e-6);
	assert_float_equal(pos2, 1.0, 1e-6);
	assert_float_equal(neg2, -1.0, 1e-6);
}

static void test_colour(void **state)
{
	(void)state;
	const float white[3] = { 1, 1, 1 }, green[3] = { 0, 1, 0 }, blue[3] = { 0, 0, 1 };
	float xyz[3], lab[3], ycc[3], back[3];
	aa_flip_linear_to_xyz(white, xyz);
	aa_flip_xyz_to_lab(xyz, lab);
	aa_flip_xyz_to_ycxcz(xyz, ycc);
	assert_true(lab[0] == 100.0f && lab[1] == 0.0f && lab[2] == 0.0f);
	assert_true(ycc[0] == 100.0f && ycc[1] == 0.0f);
	assert_float_equal(ycc[2], 1.19e-5f, 1e-7);
	aa_flip_ycxcz_to_xyz(ycc, back);
	aa_flip_xyz_to_linear(back, back);
	for (int c = 0; c < 3; c++)
		assert_float_equal(back[c], 1.0f, 1e-5);
	aa_flip_linear_to_xyz(green, xyz);
	aa_flip_xyz_to_lab(xyz, lab);
	assert_true(lab[0] == 87.7362137f && lab[1] == -86.1787186f && lab[2] == 83.1825714f);
	aa_flip_linear_to_xyz(blue, xyz);
	aa_flip_xyz_to_lab(xyz, lab);
	assert_true(lab[0] == 32.298172f && lab[1] == 79.1935883f && lab[2] == -107.858635f);
	assert_true(aa_flip_max_color_distance() == 41.2760963f);
	assert_true(aa_flip_srgb_to_linear(0.0f) == 0.0f && aa_flip_srgb_to_linear(1.0f) == 1.0f);
	assert_float_equal(aa_flip_srgb_to_linear(0.5f), 0.21404114f, 1e-7);
}

static void test_known_errors(void **state)
{
	(void)state;
	struct aa_image_rgba8 black, white;
	assert_int_equal(aa_image_rgba8_alloc(&black, 40, 30), 0);
	assert_int_equal(aa_image_rgba8_alloc(&white, 40, 30), 0);
	memset(white.pixels, 255, 40 * 30 * 4);
	for (int i = 0; i < 40 * 30; i++)
		black.pixels[4 * i + 3] = 255;
	float map[40 * 30];
	struct aa_flip_stats st;
	/* Identical images: no error anywhere. */
	assert_int_equal(aa_flip_ldr_rgba8(&white, &white, NULL, map, NULL), 0);
	for (int i = 0; i < 40 * 30; i++)
		assert_true(map[i] == 0.0f);
	assert_int_equal(aa_flip_pool(map, 40 * 30, &st), 0);
	assert_true(st.mean == 0 && st.max == 0 && st.min == 0 && st.weighted_median == 0);
	/* Flat black against flat white: no features, so the error is the colour error of L 0 vs 100:
	 * d = 100^0.7 is above pc*cmax, on the second, shallow segment. */
	assert_int_equal(aa_flip_ldr_rgba8(&black, &white, NULL, map, NULL), 0);
	const float cmax = 41.2760963f, pccmax = 0.4f * cmax, d = powf(100.0f, 0.7f);
	const float expected = 0.95f + ((d - pccmax) / (cmax - pccmax)) * 0.05f;
	assert_float_equal(expected, 0.967381, 1e-5);
	for (int i = 0; i < 40 * 30; i++)
		assert_float_equal(map[i], expected, 1e-5);
	aa_image_rgba8_free(&black);
	aa_image_rgba8_free(&white);
}

/* The optimised map (strips, ring of rows, SIMD kernels, threads) equals the direct evaluation exactly. */
static void check_against_naive(int w, int h, float ppd, int threads)
{
	struct aa_image_rgba8 ref, test;
	make_image(&ref, w, h, 7u + (uint32_t)w, 0);
	make_image(&test, w, h, 11u + (uint32_t)h, 12);
	float *fast = malloc((size_t)w * h * sizeof(float)), *slow = malloc((size_t)w * h * sizeof(float));
	struct aa_flip_options opt = { .ppd = ppd, .threads = threads };
	struct aa_error err = { 0 };
	assert_int_equal(aa_flip_ldr_rgba8(&ref, &test, &opt, fast, &err), 0);
	naive_flip(&ref, &test, ppd, slow);
	size_t differ = 0;
	for (size_t i = 0; i < (size_t)w * h; i++)
		differ += memcmp(&fast[i], &slow[i], sizeof(float)) != 0;
	if (differ)
		fail_msg("%zu of %dx%d pixels differ (ppd %g, %d threads)", differ, w, h, (double)ppd, threads);
	free(fast);
	free(slow);
	aa_image_rgba8_free(&ref);
	aa_image_rgba8_free(&test);
}

static void test_map_matches_direct_evaluation(void **state)
{
	(void)state;
	check_against_naive(37, 23, AA_FLIP_DEFAULT_PPD, 1);
	check_against_naive(37, 23, AA_FLIP_DEFAULT_PPD, 2);
	check_against_naive(1, 1, AA_FLIP_DEFAULT_PPD, 0);
	check_against_naive(3, 50, AA_FLIP_DEFAULT_PPD, 3);
	check_against_naive(1100, 9, AA_FLIP_DEFAULT_PPD, 2); /* more than one strip of columns */
	check_against_naive(64, 40, 10.0f, 2);
	check_against_naive(70, 33, 150.0f, 2);
}

static void test_threads_agree(void **state)
{
	(void)state;
	struct aa_image_rgba8 ref, test;
	make_image(&ref, 300, 200, 1, 0);
	make_image(&test, 300, 200, 2, 30);
	float *a = malloc(300 * 200 * sizeof(float)), *b = malloc(300 * 200 * sizeof(float));
	struct aa_flip_options one = { .threads = 1 }, many = { .threads = 5 };
	assert_int_equal(aa_flip_ldr_rgba8(&ref, &test, &one, a, NULL), 0);
	assert_int_equal(aa_flip_ldr_rgba8(&ref, &test, &many, b, NULL), 0);
	assert_memory_equal(a, b, 300 * 200 * sizeof(float));
	struct aa_flip_stats st;
	assert_int_equal(aa_flip_pool(a, 300 * 200, &st), 0);
	assert_true(st.mean > 0.0 && st.mean < 1.0);
	/* the mean alone (what a job reports) is the pooled mean to the bit */
	assert_true(aa_flip_mean(a, 300 * 200) == st.mean);
	assert_true(aa_flip_mean(a, 0) == 0.0);
	assert_true(st.min <= st.weighted_q1 && st.weighted_q1 <= st.weighted_median);
	assert_true(st.weighted_median <= st.weighted_q3 && st.weighted_q3 <= st.max);
	free(a);
	free(b);
	aa_image_rgba8_free(&ref);
	aa_image_rgba8_free(&test);
}

static void test_errors(void **state)
{
	(void)state;
	struct aa_image_rgba8 a, b;
	assert_int_equal(aa_image_rgba8_alloc(&a, 8, 8), 0);
	assert_int_equal(aa_image_rgba8_alloc(&b, 8, 9), 0);
	float map[8 * 9];
	struct aa_error err = { 0 };
	assert_int_equal(aa_flip_ldr_rgba8(&a, &b, NULL, map, &err), -1);
	assert_non_null(strstr(err.message, "8x9"));
	struct aa_flip_options bad = { .ppd = -3 };
	assert_int_equal(aa_flip_ldr_rgba8(&a, &a, &bad, map, &err), -1);
	assert_string_equal(err.path, "ppd");
	aa_image_rgba8_free(&a);
	aa_image_rgba8_free(&b);
}

static void test_pool(void **state)
{
	(void)state;
	/* Weighted by their own values: running sums 0.1, 0.3, 0.6, 1.0 over a total of 1.0. */
	const float map[] = { 0.3f, 0.1f, 0.4f, 0.2f };
	struct aa_flip_stats st;
	assert_int_equal(aa_flip_pool(map, 4, &st), 0);
	assert_float_equal(st.mean, 0.25, 1e-7);
	assert_true((float)st.weighted_q1 == 0.2f);
	assert_true((float)st.weighted_median == 0.3f);
	assert_true((float)st.weighted_q3 == 0.4f);
	assert_true((float)st.min == 0.1f && (float)st.max == 0.4f);
	/* One large error dominates the weighted median even though most pixels are small. */
	float skewed[100];
	for (int i = 0; i < 100; i++)
		skewed[i] = i == 50 ? 0.9f : 0.001f;
	assert_int_equal(aa_flip_pool(skewed, 100, &st), 0);
	assert_true((float)st.weighted_median == 0.9f);
	assert_true((float)st.weighted_q1 == 0.9f);
	assert_int_equal(aa_flip_pool(skewed, 0, &st), 0);
	assert_true(st.mean == 0.0);
	/* the sort underneath, with negatives, zeros of both signs and repeated values */
	const float v[] = { 3.0f, -1.0f, 0.0f, -0.0f, 2.5f, -1e-30f, 3.0f, 1e30f };
	float s[8];
	assert_int_equal(aa_flip_sort_floats(v, 8, s), 0);
	for (int i = 1; i < 8; i++)
		assert_true(s[i - 1] <= s[i]);
	assert_true(s[0] == -1.0f && s[7] == 1e30f);
}

static void test_colorize(void **state)
{
	(void)state;
	struct aa_image_rgba8 out;
	assert_int_equal(aa_image_rgba8_alloc(&out, 4, 1), 0);
	const float map[4] = { 0.0f, 1.0f, 0.5f, NAN };
	aa_flip_colorize(map, true, &out);
	const uint8_t expected[16] = { 0, 0, 4, 255, 252, 253, 191, 255, 183, 55, 121, 255, 0, 0, 4, 255 };
	assert_memory_equal(out.pixels, expected, 16);
	aa_flip_colorize(map, false, &out);
	assert_int_equal(out.pixels[0], 0);
	assert_int_equal(out.pixels[4], 255);
	assert_int_equal(out.pixels[8], 128);
	aa_image_rgba8_free(&out);
}

static void test_tone_mapping(void **state)
{
	(void)state;
	assert_true(aa_flip_tone_xmax(AA_FLIP_ACES) == 2.11887312f);
	assert_true(aa_flip_tone_xmax(AA_FLIP_HABLE) == 3.12774992f);
	assert_true(aa_flip_tone_xmax(AA_FLIP_REINHARD) == 5.66666794f);
	for (int tm = AA_FLIP_ACES; tm <= AA_FLIP_HABLE; tm++) {
		float x = aa_flip_tone_xmax((enum aa_flip_tone_mapper)tm), in[3] = { x, x, x }, out[3];
		aa_flip_tone_map((enum aa_flip_tone_mapper)tm, in, out);
		assert_float_equal(out[0], 0.85f, 1e-5);
	}
	float in[3] = { 1.0f, 1.0f, 1.0f }, out[3];
	aa_flip_tone_map(AA_FLIP_REINHARD, in, out);
	assert_float_equal(out[1], 0.5f, 1e-6);
	assert_int_equal(aa_flip_tone_mapper_parse("ACES"), AA_FLIP_ACES);
	assert_int_equal(aa_flip_tone_mapper_parse("hable"), AA_FLIP_HABLE);
	assert_int_equal(aa_flip_tone_mapper_parse("Reinhard"), AA_FLIP_REINHARD);
	assert_int_equal(aa_flip_tone_mapper_parse("filmic"), -1);
}

static void make_hdr(struct aa_image_rgbaf *img, int w, int h, uint32_t seed)
{
	assert_int_equal(aa_image_rgbaf_alloc(img, w, h), 0);
	uint32_t state = seed;
	for (int i = 0; i < w * h; i++) {
		float v = (i % w < w / 2) ? 0.05f : 8.0f; /* a dim half and a bright half */
		for (int c = 0; c < 3; c++)
			img->pixels[4 * i + c] = v * (1.0f + (float)(next_random(&state) % 100) / 400.0f);
		img->pixels[4 * i + 3] = 1.0f;
	}
}

/* HDR-FLIP is the per-pixel maximum of LDR-FLIP over tone-mapped exposures start..stop. */
static void test_hdr(void **state)
{
	(void)state;
	const int w = 48, h = 20;
	struct aa_image_rgbaf ref, test, ref_e, test_e;
	make_hdr(&ref, w, h, 3);
	make_hdr(&test, w, h, 4);
	float start, stop;
	assert_int_equal(aa_flip_exposure_range(&ref, AA_FLIP_ACES, &start, &stop, NULL), 0);
	float ymax = 0, lum[48 * 20];
	for (int i = 0; i < w * h; i++) {
		const float *p = ref.pixels + 4 * i;
		lum[i] = 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
		ymax = lum[i] > ymax ? lum[i] : ymax;
	}
	float sorted[48 * 20];
	assert_int_equal(aa_flip_sort_floats(lum, (size_t)w * h, sorted), 0);
	assert_true(start == log2f(2.11887312f / ymax));
	assert_true(stop == log2f(2.11887312f / sorted[w * h / 2]));

	float *map = malloc((size_t)w * h * sizeof(float)), *expected = calloc((size_t)w * h, sizeof(float));
	float *one = malloc((size_t)w * h * sizeof(float));
	struct aa_flip_hdr_info info;
	assert_int_equal(aa_flip_hdr(&ref, &test, NULL, map, &info, NULL), 0);
	assert_true(info.start_exposure == start && info.stop_exposure == stop);
	int count = (int)ceilf(stop - start);
	assert_int_equal(info.exposures, count < 2 ? 2 : count);
	assert_int_equal(aa_image_rgbaf_alloc(&ref_e, w, h), 0);
	assert_int_equal(aa_image_rgbaf_alloc(&test_e, w, h), 0);
	const float step = (stop - start) / (float)(info.exposures - 1);
	for (int e = 0; e < info.exposures; e++) {
		const float scale = powf(2.0f, start + (float)e * step);
		for (int i = 0; i < w * h; i++) {
			float a[3], b[3];
			for (int c = 0; c < 3; c++) {
				a[c] = ref.pixels[4 * i + c] * scale;
				b[c] = test.pixels[4 * i + c] * scale;
			}
			aa_flip_tone_map(AA_FLIP_ACES, a, ref_e.pixels + 4 * i);
			aa_flip_tone_map(AA_FLIP_ACES, b, test_e.pixels + 4 * i);
		}
		assert_int_equal(aa_flip_ldr_linear(&ref_e, &test_e, NULL, one, NULL), 0);
		for (int i = 0; i < w * h; i++)
			expected[i] = one[i] > expected[i] ? one[i] : expected[i];
	}
	assert_memory_equal(map, expected, (size_t)w * h * sizeof(float));

	/* user-given range and count; start above stop is refused */
	struct aa_flip_options opt = { .have_start = true, .start_exposure = -2.0f, .have_stop = true,
				       .stop_exposure = 1.0f, .exposures = 4, .tone_mapper = AA_FLIP_HABLE };
	assert_int_equal(aa_flip_hdr(&ref, &test, &opt, map, &info, NULL), 0);
	assert_int_equal(info.exposures, 4);
	opt.start_exposure = 2.0f;
	struct aa_error err = { 0 };
	assert_int_equal(aa_flip_hdr(&ref, &test, &opt, map, &info, &err), -1);
	assert_non_null(strstr(err.message, "start exposure"));
	/* a black reference has no exposure range of its own */
	memset(ref.pixels, 0, (size_t)w * h * 4 * sizeof(float));
	assert_int_equal(aa_flip_hdr(&ref, &test, NULL, map, &info, &err), -1);
	free(map);
	free(expected);
	free(one);
	aa_image_rgbaf_free(&ref);
	aa_image_rgbaf_free(&test);
	aa_image_rgbaf_free(&ref_e);
	aa_image_rgbaf_free(&test_e);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_ppd),
		cmocka_unit_test(test_csf_taps),
		cmocka_unit_test(test_feature_taps),
		cmocka_unit_test(test_colour),
		cmocka_unit_test(test_known_errors),
		cmocka_unit_test(test_map_matches_direct_evaluation),
		cmocka_unit_test(test_threads_agree),
		cmocka_unit_test(test_errors),
		cmocka_unit_test(test_pool),
		cmocka_unit_test(test_colorize),
		cmocka_unit_test(test_tone_mapping),
		cmocka_unit_test(test_hdr),
	};
	return cmocka_run_group_tests_name("flip", tests, NULL, NULL);
}
