/* Metrics on hand-made images with known answers, SSIM against a direct 2D evaluation, the sRGB
 * transfer functions, and image file round trips through OpenImageIO. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include <png.h>

#include "image/image.h"
#include "image/png_io.h"
#include "metrics/metrics.h"

#define PSNR_ONE_LSB 48.130803608679102 /* 20 log10(255) */

static void alloc_rgba8(struct aa_image_rgba8 *img, int width, int height)
{
	assert_int_equal(aa_image_rgba8_alloc(img, width, height), 0);
}

static void fill_rgba8(struct aa_image_rgba8 *img, uint8_t r, uint8_t g, uint8_t b)
{
	for (size_t p = 0; p < (size_t)img->width * img->height; p++) {
		uint8_t *px = img->pixels + 4 * p;
		px[0] = r;
		px[1] = g;
		px[2] = b;
		px[3] = 255;
	}
}

/* Deterministic pseudo-random bytes (xorshift32), so failures reproduce. */
static uint32_t next_random(uint32_t *state)
{
	uint32_t x = *state;
	x ^= x << 13;
	x ^= x >> 17;
	x ^= x << 5;
	return *state = x;
}

static void fill_random(struct aa_image_rgba8 *img, uint32_t seed, int lo, int hi)
{
	for (size_t i = 0; i < (size_t)img->width * img->height * 4; i++)
		img->pixels[i] = (i % 4 == 3) ? 255 : (uint8_t)(lo + next_random(&seed) % (uint32_t)(hi - lo + 1));
}

static void test_off_by_one_everywhere(void **state)
{
	(void)state;
	struct aa_image_rgba8 ref, test;
	alloc_rgba8(&ref, 17, 9);
	alloc_rgba8(&test, 17, 9);
	fill_random(&ref, 7, 1, 254);
	for (size_t i = 0; i < 17 * 9 * 4; i++)
		test.pixels[i] = (i % 4 == 3) ? 255 : (uint8_t)(ref.pixels[i] + ((i / 3) % 2 ? 1 : -1));
	struct aa_metrics m;
	struct aa_error err = { 0 };
	assert_int_equal(aa_metrics_compare(&ref, &test, &m, &err), 0);
	assert_true(m.mse == 1.0);
	assert_true(m.rmsd == 1.0);
	assert_true(fabs(m.psnr - PSNR_ONE_LSB) < 1e-9);
	assert_true(fabs(m.psnr - 48.1308) < 1e-4);
	assert_false(m.identical);
	assert_true(m.max_abs == 1.0);
	assert_true(m.ssim < 1.0 && m.ssim > 0.9);
	aa_image_rgba8_free(&ref);
	aa_image_rgba8_free(&test);
}

static void test_one_pixel_off_by_255(void **state)
{
	(void)state;
	struct aa_image_rgba8 ref, test;
	alloc_rgba8(&ref, 10, 10);
	alloc_rgba8(&test, 10, 10);
	fill_rgba8(&ref, 0, 0, 0);
	fill_rgba8(&test, 0, 0, 0);
	test.pixels[4 * (3 * 10 + 7) + 1] = 255;
	struct aa_metrics m;
	assert_int_equal(aa_metrics_compare(&ref, &test, &m, NULL), 0);
	assert_true(fabs(m.mse - 255.0 * 255.0 / 300.0) < 1e-12);
	assert_true(fabs(m.psnr - 10.0 * log10(300.0)) < 1e-9); /* 24.7712 dB */
	assert_true(m.max_abs == 255.0);
	assert_true(isnan(m.snr)); /* a black reference has no signal */
	/* The pixel's luminance error is 0.7152: it exceeds thresholds 0..0.71 and no higher one. */
	assert_true(fabs(m.exceed[0] - 0.01) < 1e-15);
	assert_true(fabs(m.exceed[71] - 0.01) < 1e-15);
	assert_true(m.exceed[72] == 0.0);
	aa_image_rgba8_free(&ref);
	aa_image_rgba8_free(&test);
}

static void test_identical_images(void **state)
{
	(void)state;
	struct aa_image_rgba8 ref, test;
	alloc_rgba8(&ref, 40, 30);
	alloc_rgba8(&test, 40, 30);
	fill_random(&ref, 99, 0, 255);
	memcpy(test.pixels, ref.pixels, 40 * 30 * 4);
	test.pixels[3] = 0; /* alpha is ignored */
	struct aa_metrics m;
	assert_int_equal(aa_metrics_compare(&ref, &test, &m, NULL), 0);
	assert_true(m.identical);
	assert_true(m.mse == 0.0 && m.rmsd == 0.0 && m.max_abs == 0.0);
	assert_true(isnan(m.psnr));
	assert_true(isnan(m.snr));
	assert_true(m.ssim == 1.0);
	for (int i = 0; i < AA_THRESHOLD_COUNT; i++)
		assert_true(m.exceed[i] == 0.0);
	aa_image_rgba8_free(&ref);
	aa_image_rgba8_free(&test);
}

static void test_constant_images(void **state)
{
	(void)state;
	struct aa_image_rgba8 ref, test;
	alloc_rgba8(&ref, 24, 16);
	alloc_rgba8(&test, 24, 16);
	fill_rgba8(&ref, 100, 100, 100);
	fill_rgba8(&test, 110, 110, 110);
	struct aa_metrics m;
	assert_int_equal(aa_metrics_compare(&ref, &test, &m, NULL), 0);
	assert_true(m.mse == 100.0);
	assert_true(fabs(m.psnr - 10.0 * log10(650.25)) < 1e-9);
	assert_true(fabs(m.snr - 20.0) < 1e-9); /* mean ref^2 = 10000 over mse 100 */
	/* No variance anywhere: SSIM reduces to the luminance term. */
	double c1 = (0.01 * 255) * (0.01 * 255);
	double expected = (2.0 * 100 * 110 + c1) / (100.0 * 100 + 110.0 * 110 + c1);
	assert_true(fabs(m.ssim - expected) < 1e-12);
	/* Both constant and equal: SSIM 1, no NaN from 0/0. */
	fill_rgba8(&test, 100, 100, 100);
	assert_int_equal(aa_metrics_compare(&ref, &test, &m, NULL), 0);
	assert_true(m.ssim == 1.0 && m.identical);
	aa_image_rgba8_free(&ref);
	aa_image_rgba8_free(&test);
}

static void test_exceedance_curve(void **state)
{
	(void)state;
	struct aa_image_rgba8 ref, test;
	alloc_rgba8(&ref, 2, 2);
	alloc_rgba8(&test, 2, 2);
	fill_rgba8(&ref, 0, 0, 0);
	fill_rgba8(&test, 0, 0, 0);
	/* Grey errors of 128/255 = 0.502 and 64/255 = 0.251, and a pure red error of 0.2126. */
	memset(test.pixels + 0, 128, 3);
	memset(test.pixels + 4, 64, 3);
	test.pixels[8] = 255;
	struct aa_metrics m;
	assert_int_equal(aa_metrics_compare(&ref, &test, &m, NULL), 0);
	for (int i = 0; i < AA_THRESHOLD_COUNT; i++) {
		double expected = i <= 21 ? 0.75 : i <= 25 ? 0.5 : i <= 50 ? 0.25 : 0.0;
		assert_true(m.exceed[i] == expected);
	}
	aa_image_rgba8_free(&ref);
	aa_image_rgba8_free(&test);
}

/* The curve on 65,536 pixels of many colours against the definition evaluated per pixel and threshold
 * (luma of each as written, err > i/100): the counts must be the same exactly, whatever tables or
 * shortcuts the metric uses. */
static void test_exceedance_curve_by_definition(void **state)
{
	(void)state;
	struct aa_image_rgba8 ref, test;
	alloc_rgba8(&ref, 256, 256);
	alloc_rgba8(&test, 256, 256);
	size_t over[AA_THRESHOLD_COUNT] = { 0 };
	for (int y = 0; y < 256; y++)
		for (int x = 0; x < 256; x++) {
			uint8_t *r = ref.pixels + 4 * (y * 256 + x), *t = test.pixels + 4 * (y * 256 + x);
			r[0] = (uint8_t)x, r[1] = (uint8_t)y, r[2] = (uint8_t)(x ^ y);
			t[0] = (uint8_t)y, t[1] = (uint8_t)(x + 3 * y), t[2] = (uint8_t)(255 - x);
			const double y_ref = (0.2126 * r[0] + 0.7152 * r[1] + 0.0722 * r[2]) / 255.0;
			const double y_test = (0.2126 * t[0] + 0.7152 * t[1] + 0.0722 * t[2]) / 255.0;
			for (int i = 0; i < AA_THRESHOLD_COUNT; i++)
				over[i] += fabs(y_test - y_ref) > i / 100.0;
		}
	struct aa_metrics m;
	assert_int_equal(aa_metrics_compare_pixels(&ref, &test, &m, NULL), 0);
	for (int i = 0; i < AA_THRESHOLD_COUNT; i++)
		if (m.exceed[i] != (double)over[i] / 65536.0)
			fail_msg("threshold %d: %.17g, by definition %.17g", i, m.exceed[i], (double)over[i] / 65536.0);
	aa_image_rgba8_free(&ref);
	aa_image_rgba8_free(&test);
}

/* Direct 2D evaluation of one channel's SSIM map mean: 11x11 Gaussian (sigma 1.5) built as an outer
 * product, window border cropped; independent of the separable, blocked, threaded implementation. */
static double ssim_direct(const struct aa_image_rgba8 *a, const struct aa_image_rgba8 *b, int channel)
{
	double g[11], total = 0.0;
	for (int k = 0; k < 11; k++)
		total += g[k] = exp(-(k - 5) * (k - 5) / (2.0 * 1.5 * 1.5));
	double c1 = 6.5025, c2 = 58.5225, sum = 0.0;
	int w = a->width, h = a->height;
	for (int y = 5; y < h - 5; y++) {
		for (int x = 5; x < w - 5; x++) {
			double ux = 0, uy = 0, uxx = 0, uyy = 0, uxy = 0;
			for (int dy = -5; dy <= 5; dy++) {
				for (int dx = -5; dx <= 5; dx++) {
					double wt = g[dy + 5] * g[dx + 5] / (total * total);
					size_t i = ((size_t)(y + dy) * w + (x + dx)) * 4 + channel;
					double p = a->pixels[i], q = b->pixels[i];
					ux += wt * p;
					uy += wt * q;
					uxx += wt * p * p;
					uyy += wt * q * q;
					uxy += wt * p * q;
				}
			}
			double vx = uxx - ux * ux, vy = uyy - uy * uy, vxy = uxy - ux * uy;
			sum += (2 * ux * uy + c1) * (2 * vxy + c2) / ((ux * ux + uy * uy + c1) * (vx + vy + c2));
		}
	}
	return sum / ((double)(w - 10) * (h - 10));
}

static void test_ssim_matches_direct_evaluation(void **state)
{
	(void)state;
	/* Large enough to be split over threads; odd sizes exercise partial blocks. */
	int w = 403, h = 331;
	struct aa_image_rgba8 ref, test;
	alloc_rgba8(&ref, w, h);
	alloc_rgba8(&test, w, h);
	uint32_t seed = 12345;
	for (int y = 0; y < h; y++) {
		for (int x = 0; x < w; x++) {
			uint8_t *r = ref.pixels + 4 * ((size_t)y * w + x), *t = test.pixels + 4 * ((size_t)y * w + x);
			r[0] = (uint8_t)(x * 255 / w);
			r[1] = (uint8_t)((x / 16 + y / 16) % 2 ? 220 : 30);
			r[2] = (uint8_t)(next_random(&seed) % 256);
			for (int c = 0; c < 3; c++)
				t[c] = (uint8_t)(r[c] / 2 + next_random(&seed) % 128);
			r[3] = t[3] = 255;
		}
	}
	double expected = (ssim_direct(&ref, &test, 0) + ssim_direct(&ref, &test, 1) + ssim_direct(&ref, &test, 2)) / 3;
	double ours = aa_ssim_rgba8(&ref, &test);
	assert_true(fabs(ours - expected) < 1e-10);
	assert_true(fabs(aa_ssim_rgba8(&test, &ref) - ours) < 1e-12); /* symmetric */
	assert_true(aa_ssim_rgba8(&ref, &ref) == 1.0);
	aa_image_rgba8_free(&ref);
	aa_image_rgba8_free(&test);
}

static void test_ssim_channel_matches_rgb(void **state)
{
	(void)state;
	int w = 31, h = 19;
	struct aa_image_rgba8 ref, test;
	alloc_rgba8(&ref, w, h);
	alloc_rgba8(&test, w, h);
	double *ref_d = malloc(sizeof(double) * w * h), *test_d = malloc(sizeof(double) * w * h);
	assert_non_null(ref_d);
	assert_non_null(test_d);
	uint32_t seed = 5;
	for (int i = 0; i < w * h; i++) {
		uint8_t a = (uint8_t)next_random(&seed), b = (uint8_t)(a / 3 + next_random(&seed) % 64);
		memset(ref.pixels + 4 * i, a, 3);
		memset(test.pixels + 4 * i, b, 3);
		ref_d[i] = a;
		test_d[i] = b;
	}
	double grey = aa_ssim_channel(ref_d, test_d, w, h, 255.0);
	assert_true(fabs(grey - aa_ssim_rgba8(&ref, &test)) < 1e-12);
	assert_true(fabs(grey - ssim_direct(&ref, &test, 0)) < 1e-10);
	/* The data range scales the constants: data on [0,1] with L = 1 gives the same value. */
	for (int i = 0; i < w * h; i++) {
		ref_d[i] /= 255.0;
		test_d[i] /= 255.0;
	}
	assert_true(fabs(aa_ssim_channel(ref_d, test_d, w, h, 1.0) - grey) < 1e-9);
	assert_true(isnan(aa_ssim_channel(ref_d, test_d, w, h, 0.0)));
	free(ref_d);
	free(test_d);
	aa_image_rgba8_free(&ref);
	aa_image_rgba8_free(&test);
}

/* SSIM to the last bit on two fixed pairs (gradients, stripes and noise; one of the job's sizes): values
 * computed by the plain scalar kernels. The vectorised kernels must keep every operation and its order,
 * so an FMA, a reassociated sum or a changed filter order shows here, where the 1e-12 checks above and
 * scikit-image's 1e-4 would let it through. */
static void make_ssim_pair(struct aa_image_rgba8 *a, struct aa_image_rgba8 *b, int w, int h)
{
	uint32_t x = 2463534242u;
	for (int y = 0; y < h; y++)
		for (int i = 0; i < w; i++) {
			uint8_t *p = a->pixels + 4 * ((size_t)y * w + i), *q = b->pixels + 4 * ((size_t)y * w + i);
			for (int c = 0; c < 3; c++) {
				x ^= x << 13; x ^= x >> 17; x ^= x << 5;
				int v = (i * 255 / w + y * (c + 1)) % 256;
				if ((i / 7 + y / 5) % 2) v = 255 - v;
				p[c] = (uint8_t)v;
				int n = (int)(x % 41) - 20;
				int t = v + n;
				q[c] = (uint8_t)(t < 0 ? 0 : t > 255 ? 255 : t);
			}
			p[3] = q[3] = 255;
		}
}

static void test_ssim_pinned_bits(void **state)
{
	(void)state;
	const struct { int w, h; double ssim; } pinned[2] = {
		{ 97, 61, 0x1.d57bf5daa75ddp-1 },
		{ 640, 360, 0x1.d3d508d828105p-1 },
	};
	for (int k = 0; k < 2; k++) {
		struct aa_image_rgba8 a, b;
		assert_int_equal(aa_image_rgba8_alloc(&a, pinned[k].w, pinned[k].h), 0);
		assert_int_equal(aa_image_rgba8_alloc(&b, pinned[k].w, pinned[k].h), 0);
		make_ssim_pair(&a, &b, pinned[k].w, pinned[k].h);
		const double v = aa_ssim_rgba8(&a, &b);
		if (v != pinned[k].ssim)
			fail_msg("SSIM of the %dx%d pair %a, pinned %a", pinned[k].w, pinned[k].h, v, pinned[k].ssim);
		aa_image_rgba8_free(&a);
		aa_image_rgba8_free(&b);
	}
}

static void test_ssim_small_images(void **state)
{
	(void)state;
	/* Smaller than the 11x11 window: defined (whole image, reflected borders), finite, 1 when equal. */
	int sizes[][2] = { { 1, 1 }, { 5, 3 }, { 10, 12 }, { 11, 11 } };
	for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++) {
		struct aa_image_rgba8 ref, test;
		alloc_rgba8(&ref, sizes[s][0], sizes[s][1]);
		alloc_rgba8(&test, sizes[s][0], sizes[s][1]);
		fill_random(&ref, 3 + (uint32_t)s, 0, 255);
		fill_random(&test, 300 + (uint32_t)s, 0, 255);
		double v = aa_ssim_rgba8(&ref, &test);
		assert_true(isfinite(v) && v <= 1.0 && v >= -1.0);
		assert_true(fabs(aa_ssim_rgba8(&ref, &ref) - 1.0) < 1e-15);
		aa_image_rgba8_free(&ref);
		aa_image_rgba8_free(&test);
	}
}

static void test_size_mismatch(void **state)
{
	(void)state;
	struct aa_image_rgba8 ref, test;
	alloc_rgba8(&ref, 8, 8);
	alloc_rgba8(&test, 8, 9);
	struct aa_metrics m;
	struct aa_error err = { 0 };
	assert_int_equal(aa_metrics_compare(&ref, &test, &m, &err), -1);
	assert_int_equal(err.code, AA_ERR_INVALID);
	assert_non_null(strstr(err.message, "8x9"));
	assert_non_null(strstr(err.message, "8x8"));
	assert_true(isnan(aa_ssim_rgba8(&ref, &test)));
	aa_image_rgba8_free(&ref);
	aa_image_rgba8_free(&test);
}

static void test_linear_psnr(void **state)
{
	(void)state;
	struct aa_image_rgbaf ref, test;
	assert_int_equal(aa_image_rgbaf_alloc(&ref, 4, 3), 0);
	assert_int_equal(aa_image_rgbaf_alloc(&test, 4, 3), 0);
	for (int i = 0; i < 4 * 3 * 4; i++) {
		ref.pixels[i] = 0.5f;
		test.pixels[i] = (i % 4 == 3) ? 0.0f : 0.75f; /* alpha differs but is ignored */
	}
	double mse, psnr;
	bool identical;
	struct aa_error err = { 0 };
	assert_int_equal(aa_metrics_psnr_linear(&ref, &test, &mse, &psnr, &identical, &err), 0);
	assert_true(mse == 0.0625);
	assert_true(fabs(psnr - 10.0 * log10(16.0)) < 1e-12);
	assert_false(identical);
	/* Not clamped: an HDR error of 2 gives a negative PSNR against peak 1. */
	for (int i = 0; i < 4 * 3 * 4; i++)
		test.pixels[i] = 2.5f;
	assert_int_equal(aa_metrics_psnr_linear(&ref, &test, &mse, &psnr, &identical, &err), 0);
	assert_true(mse == 4.0);
	assert_true(fabs(psnr + 10.0 * log10(4.0)) < 1e-12);
	assert_int_equal(aa_metrics_psnr_linear(&ref, &ref, &mse, &psnr, &identical, &err), 0);
	assert_true(identical && mse == 0.0 && isnan(psnr));
	test.pixels[4 * 5 + 1] = NAN;
	assert_int_equal(aa_metrics_psnr_linear(&ref, &test, &mse, &psnr, &identical, &err), -1);
	assert_int_equal(err.code, AA_ERR_INVALID);
	assert_non_null(strstr(err.message, "(1, 1)"));
	aa_image_rgbaf_free(&ref);
	aa_image_rgbaf_free(&test);
}

static void test_psnr_from_mse(void **state)
{
	(void)state;
	assert_true(fabs(aa_psnr_from_mse(1.0, 255.0) - PSNR_ONE_LSB) < 1e-12);
	assert_true(fabs(aa_psnr_from_mse(0.01, 1.0) - 20.0) < 1e-12);
	assert_true(isnan(aa_psnr_from_mse(0.0, 255.0)));
	assert_true(isnan(aa_psnr_from_mse(NAN, 255.0)));
}

static void test_srgb_round_trip(void **state)
{
	(void)state;
	assert_true(aa_srgb_to_linear(0.0f) == 0.0f);
	assert_true(fabsf(aa_srgb_to_linear(1.0f) - 1.0f) < 1e-7f);
	assert_true(fabsf(aa_linear_to_srgb(0.5f) - 0.735357f) < 1e-5f);
	struct aa_image_rgbaf lin;
	struct aa_image_rgba8 enc;
	assert_int_equal(aa_image_rgbaf_alloc(&lin, 256, 1), 0);
	alloc_rgba8(&enc, 256, 1);
	for (int v = 0; v < 256; v++) {
		float linear = aa_srgb_to_linear(v / 255.0f);
		for (int c = 0; c < 3; c++)
			lin.pixels[4 * v + c] = linear;
		lin.pixels[4 * v + 3] = v / 255.0f;
	}
	aa_image_encode_srgb8(&lin, &enc);
	for (int v = 0; v < 256; v++)
		for (int c = 0; c < 4; c++)
			assert_int_equal(enc.pixels[4 * v + c], v);
	/* NaN and negatives go to 0, overshoots clamp to 255; alpha is linear. */
	float odd[][4] = { { NAN, -1.0f, -INFINITY, NAN }, { 2.0f, INFINITY, 1.0f, 0.5f }, { 0.5f, 0, 0, 7.0f } };
	uint8_t expect[][4] = { { 0, 0, 0, 0 }, { 255, 255, 255, 128 }, { 188, 0, 0, 255 } };
	memcpy(lin.pixels, odd, sizeof odd);
	aa_image_encode_srgb8(&lin, &enc);
	assert_memory_equal(enc.pixels, expect, sizeof expect);
	aa_image_rgbaf_free(&lin);
	aa_image_rgba8_free(&enc);
}

static void test_alloc_limits(void **state)
{
	(void)state;
	struct aa_image_rgba8 img;
	assert_int_equal(aa_image_rgba8_alloc(&img, 0, 5), -1);
	assert_null(img.pixels);
	assert_int_equal(aa_image_rgba8_alloc(&img, -3, 5), -1);
	assert_int_equal(aa_image_rgba8_alloc(&img, 1 << 20, 1 << 20), -1);
	aa_image_rgba8_free(&img); /* freeing a failed allocation is safe */
}

/* A private directory under $TMPDIR for the file tests. */
static int make_temp_dir(char *dir, size_t size)
{
	const char *tmp = getenv("TMPDIR");
	snprintf(dir, size, "%s/aalab-test-image-XXXXXX", tmp && *tmp ? tmp : "/tmp");
	return mkdtemp(dir) ? 0 : -1;
}

static void test_png_round_trip(void **state)
{
	(void)state;
	char dir[512], path[600];
	assert_int_equal(make_temp_dir(dir, sizeof dir), 0);
	struct aa_error err = { 0 };
	struct aa_image_rgba8 img, back;
	alloc_rgba8(&img, 13, 7);
	fill_random(&img, 42, 0, 255);
	/* Opaque: stored as RGB, read back with alpha 255. */
	snprintf(path, sizeof path, "%s/opaque.png", dir);
	assert_int_equal(aa_image_write_png(path, &img, &err), 0);
	assert_int_equal(aa_image_read_rgba8(path, &back, &err), 0);
	assert_int_equal(back.width, 13);
	assert_int_equal(back.height, 7);
	assert_memory_equal(back.pixels, img.pixels, 13 * 7 * 4);
	aa_image_rgba8_free(&back);
	/* With transparency: stored as RGBA. */
	img.pixels[3] = 10;
	snprintf(path, sizeof path, "%s/alpha.png", dir);
	assert_int_equal(aa_image_write_png(path, &img, &err), 0);
	int channels = 0;
	struct aa_image_rgbaf backf;
	assert_int_equal(aa_image_read_rgbaf(path, &backf, &channels, &err), 0);
	assert_int_equal(channels, 4);
	assert_true(fabsf(backf.pixels[3] - 10 / 255.0f) < 1e-6f);
	aa_image_rgbaf_free(&backf);
	unlink(path);
	snprintf(path, sizeof path, "%s/opaque.png", dir);
	unlink(path);
	/* In memory: a PNG signature, decodable to the same pixels. */
	uint8_t *png = NULL;
	size_t size = 0;
	assert_int_equal(aa_image_encode_png(&img, &png, &size, &err), 0);
	assert_true(size > 8);
	assert_memory_equal(png, "\x89PNG\r\n\x1a\n", 8);
	snprintf(path, sizeof path, "%s/memory.png", dir);
	FILE *f = fopen(path, "wb");
	assert_non_null(f);
	assert_int_equal(fwrite(png, 1, size, f), size);
	fclose(f);
	free(png);
	assert_int_equal(aa_image_read_rgba8(path, &back, &err), 0);
	assert_memory_equal(back.pixels, img.pixels, 13 * 7 * 4);
	aa_image_rgba8_free(&back);
	unlink(path);
	aa_image_rgba8_free(&img);
	rmdir(dir);
}

/* A 16-bit PNG (written here with libpng, as other tools write them) read as 8 bits: each sample is the
 * nearest 8-bit value, v * 255 / 65535 rounded (129 is 0.502: 1; 128 is 0.498: 0); as float, v / 65535. */
static void test_png_16bit_samples(void **state)
{
	(void)state;
	static const uint16_t grey[] = {0, 128, 129, 257, 32767, 32896, 65406, 65535};
	static const uint8_t nearest[] = {0, 0, 1, 1, 127, 128, 254, 255};
	enum { N = sizeof grey / sizeof grey[0] };
	char dir[512], path[600];
	assert_int_equal(make_temp_dir(dir, sizeof dir), 0);
	snprintf(path, sizeof path, "%s/grey16.png", dir);
	FILE *f = fopen(path, "wb");
	assert_non_null(f);
	png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
	png_infop info = png_create_info_struct(png);
	assert_true(png && info && !setjmp(png_jmpbuf(png)));
	png_init_io(png, f);
	png_set_IHDR(png, info, N, 1, 16, PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
		     PNG_FILTER_TYPE_DEFAULT);
	png_write_info(png, info);
	uint8_t row[2 * N];
	for (int i = 0; i < N; i++) { /* big-endian, as PNG stores them */
		row[2 * i] = (uint8_t)(grey[i] >> 8);
		row[2 * i + 1] = (uint8_t)(grey[i] & 0xff);
	}
	png_write_row(png, row);
	png_write_end(png, NULL);
	png_destroy_write_struct(&png, &info);
	fclose(f);
	struct aa_error err = {0};
	struct aa_file_pixels px;
	assert_int_equal(aa_png_read(path, false, &px, &err), 0);
	assert_int_equal(px.width, N);
	assert_int_equal(px.height, 1);
	assert_int_equal(px.channels, 1);
	for (int i = 0; i < N; i++)
		if (((const uint8_t *)px.data)[i] != nearest[i])
			fail_msg("16-bit %u read as %u, expected %u", grey[i], ((const uint8_t *)px.data)[i], nearest[i]);
	free(px.data);
	assert_int_equal(aa_png_read(path, true, &px, &err), 0);
	for (int i = 0; i < N; i++)
		assert_float_equal(((const float *)px.data)[i], grey[i] / 65535.0f, 1e-7f);
	free(px.data);
	unlink(path);
	rmdir(dir);
}

static void test_float_round_trip_and_errors(void **state)
{
	(void)state;
	char dir[512], path[600];
	assert_int_equal(make_temp_dir(dir, sizeof dir), 0);
	struct aa_error err = { 0 };
	struct aa_image_rgbaf img, back;
	assert_int_equal(aa_image_rgbaf_alloc(&img, 5, 4), 0);
	for (int i = 0; i < 5 * 4 * 4; i++)
		img.pixels[i] = (float)i * 0.37f - 3.0f; /* negatives and HDR values survive EXR */
	snprintf(path, sizeof path, "%s/linear.exr", dir);
	assert_int_equal(aa_image_write_rgbaf(path, &img, &err), 0);
	int channels = 0;
	assert_int_equal(aa_image_read_rgbaf(path, &back, &channels, &err), 0);
	assert_int_equal(channels, 4);
	assert_memory_equal(back.pixels, img.pixels, sizeof(float) * 5 * 4 * 4);
	aa_image_rgbaf_free(&back);
	unlink(path);
	aa_image_rgbaf_free(&img);

	/* Errors name the file. */
	struct aa_image_rgba8 img8;
	snprintf(path, sizeof path, "%s/missing.png", dir);
	assert_int_equal(aa_image_read_rgba8(path, &img8, &err), -1);
	assert_int_equal(err.code, AA_ERR_NOT_FOUND);
	assert_non_null(strstr(err.message, "missing.png"));
	snprintf(path, sizeof path, "%s/garbage.png", dir);
	FILE *f = fopen(path, "wb");
	assert_non_null(f);
	fputs("this is not an image", f);
	fclose(f);
	assert_int_equal(aa_image_read_rgba8(path, &img8, &err), -1);
	assert_int_equal(err.code, AA_ERR_IO);
	assert_non_null(strstr(err.message, "garbage.png"));
	assert_null(img8.pixels);
	unlink(path);
	alloc_rgba8(&img8, 2, 2);
	snprintf(path, sizeof path, "%s/no/such/dir/out.png", dir);
	assert_int_equal(aa_image_write_png(path, &img8, &err), -1);
	assert_int_equal(err.code, AA_ERR_IO);
	assert_non_null(strstr(err.message, "out.png"));
	aa_image_rgba8_free(&img8);
	rmdir(dir);
}

/* The table behind aa_image_encode_srgb8 gives the codes of the definition (a pow per value): on every
 * 61st float of [0, 1] and one ulp either side of every code boundary, and on the special values. (All
 * 1.07e9 floats of [0, 1] were checked once, 2026-12-01: no difference.) */
static void test_srgb8_table(void **state)
{
	(void)state;
	for (uint32_t bits = 0; bits <= 0x3f800000u; bits += 61) {
		float v;
		memcpy(&v, &bits, sizeof v);
		if (aa_srgb8_encode(v) != aa_srgb8_encode_exact(v))
			fail_msg("code of %a: table %d, definition %d", (double)v, aa_srgb8_encode(v),
				 aa_srgb8_encode_exact(v));
	}
	for (int k = 1; k < 256; k++) {
		float lo = 0.0f, hi = 1.0f; /* the boundary of code k, by bisection on values */
		for (int i = 0; i < 60; i++) {
			float mid = 0.5f * (lo + hi);
			if (aa_srgb8_encode_exact(mid) >= k)
				hi = mid;
			else
				lo = mid;
		}
		float around[3] = {nextafterf(hi, 0.0f), hi, nextafterf(hi, 2.0f)};
		for (int i = 0; i < 3; i++)
			assert_int_equal(aa_srgb8_encode(around[i]), aa_srgb8_encode_exact(around[i]));
	}
	const float special[] = {-0.0f, -1.0f, 1.0f, 1.5f, 1e30f, INFINITY, -INFINITY, NAN, 1e-45f};
	for (size_t i = 0; i < sizeof special / sizeof special[0]; i++)
		assert_int_equal(aa_srgb8_encode(special[i]), aa_srgb8_encode_exact(special[i]));
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_srgb8_table),
		cmocka_unit_test(test_off_by_one_everywhere),
		cmocka_unit_test(test_one_pixel_off_by_255),
		cmocka_unit_test(test_identical_images),
		cmocka_unit_test(test_constant_images),
		cmocka_unit_test(test_exceedance_curve),
		cmocka_unit_test(test_exceedance_curve_by_definition),
		cmocka_unit_test(test_ssim_matches_direct_evaluation),
		cmocka_unit_test(test_ssim_channel_matches_rgb),
		cmocka_unit_test(test_ssim_small_images),
		cmocka_unit_test(test_ssim_pinned_bits),
		cmocka_unit_test(test_size_mismatch),
		cmocka_unit_test(test_linear_psnr),
		cmocka_unit_test(test_psnr_from_mse),
		cmocka_unit_test(test_srgb_round_trip),
		cmocka_unit_test(test_alloc_limits),
		cmocka_unit_test(test_png_round_trip),
		cmocka_unit_test(test_png_16bit_samples),
		cmocka_unit_test(test_float_round_trip_and_errors),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
