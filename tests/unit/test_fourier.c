/* Fourier-band error: the FFT against a direct DFT, Parseval's identity (the bands add up to the spatial
 * sum of squares, so to the MSE), band edges, and sinusoids landing in the band of their frequency. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "metrics/fourier.h"
#include "metrics/metrics.h"

static uint32_t next_random(uint32_t *state)
{
	uint32_t x = *state;
	x ^= x << 13;
	x ^= x >> 17;
	x ^= x << 5;
	return *state = x;
}

static double uniform(uint32_t *state)
{
	return (double)next_random(state) / 4294967296.0 - 0.5;
}

/* Lengths covering every path: radix 4, 2, 3, 5, the generic 7/11/13 butterfly, Bluestein for primes
 * above 13 (17, 97, 1021) and mixed products. */
static void test_fft_matches_dft(void **state)
{
	(void)state;
	const int lengths[] = { 1, 2, 3, 4, 5, 6, 7, 8, 11, 12, 13, 16, 17, 30, 49, 64, 97, 143, 360, 1021 };
	uint32_t rng = 12345;
	for (size_t t = 0; t < sizeof lengths / sizeof lengths[0]; t++) {
		const int n = lengths[t];
		double *x = malloc(2 * (size_t)n * sizeof *x), *orig = malloc(2 * (size_t)n * sizeof *orig);
		for (int i = 0; i < 2 * n; i++)
			x[i] = orig[i] = uniform(&rng);
		assert_int_equal(aa_fft(x, n, NULL), 0);
		double worst = 0, scale = 0;
		for (int k = 0; k < n; k++) {
			long double re = 0, im = 0;
			for (int j = 0; j < n; j++) {
				long double a = -2.0L * 3.141592653589793238462643383279L * (long double)((long long)j * k % n) / n;
				re += orig[2 * j] * cosl(a) - orig[2 * j + 1] * sinl(a);
				im += orig[2 * j] * sinl(a) + orig[2 * j + 1] * cosl(a);
			}
			double e = hypot(x[2 * k] - (double)re, x[2 * k + 1] - (double)im);
			worst = e > worst ? e : worst;
			scale += (double)(re * re + im * im);
		}
		if (worst > 1e-12 * sqrt(scale / n + 1.0))
			fail_msg("FFT of length %d is off by %g", n, worst);
		free(x);
		free(orig);
	}
	struct aa_error err = { 0 };
	double one[2] = { 1, 0 };
	assert_int_equal(aa_fft(one, 0, &err), -1);
}

/* Parseval: sum over bands of |F|^2 / N equals sum of f^2, at sizes with every kind of factor. */
static void test_parseval(void **state)
{
	(void)state;
	const int sizes[][2] = { { 64, 48 }, { 37, 23 }, { 30, 45 }, { 1, 1 }, { 1, 17 }, { 160, 90 }, { 211, 7 } };
	uint32_t rng = 99;
	for (size_t t = 0; t < sizeof sizes / sizeof sizes[0]; t++) {
		const int w = sizes[t][0], h = sizes[t][1];
		const size_t n = (size_t)w * h;
		double *f[3], sum_sq = 0;
		for (int c = 0; c < 3; c++) {
			f[c] = malloc(n * sizeof(double));
			for (size_t i = 0; i < n; i++) {
				f[c][i] = 255.0 * uniform(&rng) + (c == 1 ? 40.0 : 0.0); /* one field with a DC offset */
				sum_sq += f[c][i] * f[c][i];
			}
		}
		for (int threads = 1; threads <= 2; threads++) {
			double energy[AA_FOURIER_BANDS];
			assert_int_equal(aa_fourier_band_energy((const double *const *)f, 3, w, h, threads, energy, NULL), 0);
			double total = energy[0] + energy[1] + energy[2];
			if (fabs(total - sum_sq) > 1e-10 * sum_sq)
				fail_msg("%dx%d: bands sum to %.17g, squares to %.17g", w, h, total, sum_sq);
			for (int b = 0; b < AA_FOURIER_BANDS; b++)
				assert_true(energy[b] >= 0.0);
		}
		for (int c = 0; c < 3; c++)
			free(f[c]);
	}
}

static void test_band_edges(void **state)
{
	(void)state;
	assert_int_equal(aa_fourier_band_of(0, 0, 64, 64), AA_FOURIER_LOW);
	assert_int_equal(aa_fourier_band_of(3, 0, 64, 64), AA_FOURIER_LOW);  /* 3/64 < 1/16 */
	assert_int_equal(aa_fourier_band_of(4, 0, 64, 64), AA_FOURIER_MID);  /* exactly 1/16 */
	assert_int_equal(aa_fourier_band_of(60, 0, 64, 64), AA_FOURIER_MID); /* -4/64 */
	assert_int_equal(aa_fourier_band_of(15, 0, 64, 64), AA_FOURIER_MID);
	assert_int_equal(aa_fourier_band_of(16, 0, 64, 64), AA_FOURIER_HIGH); /* exactly 1/4 */
	assert_int_equal(aa_fourier_band_of(12, 12, 64, 64), AA_FOURIER_HIGH); /* sqrt(2) * 12/64 > 1/4 */
	assert_int_equal(aa_fourier_band_of(32, 32, 64, 64), AA_FOURIER_HIGH);
	assert_string_equal(aa_fourier_band_names[AA_FOURIER_MID], "mid");
}

/* A cosine of frequency k/W along x puts all its energy in the band of k/W. */
static void test_sinusoids(void **state)
{
	(void)state;
	const int w = 128, h = 32;
	const int k[] = { 0, 2, 12, 40, 64 }; /* 0, 1/64 (low), 3/32 (mid), 5/16 (high), Nyquist (high) */
	const int band[] = { AA_FOURIER_LOW, AA_FOURIER_LOW, AA_FOURIER_MID, AA_FOURIER_HIGH, AA_FOURIER_HIGH };
	double *f = malloc((size_t)w * h * sizeof *f);
	for (int t = 0; t < 5; t++) {
		double sum_sq = 0;
		for (int y = 0; y < h; y++)
			for (int x = 0; x < w; x++) {
				double v = 10.0 * cos(2.0 * M_PI * k[t] * x / w + 0.3);
				f[y * w + x] = v;
				sum_sq += v * v;
			}
		double energy[AA_FOURIER_BANDS];
		const double *fields[1] = { f };
		assert_int_equal(aa_fourier_band_energy(fields, 1, w, h, 0, energy, NULL), 0);
		for (int b = 0; b < AA_FOURIER_BANDS; b++)
			assert_float_equal(energy[b], b == band[t] ? sum_sq : 0.0, 1e-8 * sum_sq);
	}
	free(f);
}

/* On images, the three bands are the MSE that aa_metrics_compare reports, split by frequency. */
static void test_bands_sum_to_mse(void **state)
{
	(void)state;
	struct aa_image_rgba8 ref, test;
	assert_int_equal(aa_image_rgba8_alloc(&ref, 90, 61), 0);
	assert_int_equal(aa_image_rgba8_alloc(&test, 90, 61), 0);
	uint32_t rng = 5;
	for (int i = 0; i < 90 * 61; i++)
		for (int c = 0; c < 4; c++) {
			ref.pixels[4 * i + c] = (uint8_t)(c == 3 ? 255 : (i % 90) * 2 + c * 10);
			int v = ref.pixels[4 * i + c] + (c == 3 ? 0 : (int)(next_random(&rng) % 21) - 10);
			test.pixels[4 * i + c] = (uint8_t)(v < 0 ? 0 : v > 255 ? 255 : v);
		}
	struct aa_metrics m;
	assert_int_equal(aa_metrics_compare(&ref, &test, &m, NULL), 0);
	double bands[AA_FOURIER_BANDS];
	assert_int_equal(aa_fourier_bands_rgba8(&ref, &test, bands, NULL), 0);
	assert_float_equal(bands[0] + bands[1] + bands[2], m.mse, 1e-10 * m.mse);
	/* white noise spreads over the spectrum: most of its power is at high frequencies */
	assert_true(bands[AA_FOURIER_HIGH] > bands[AA_FOURIER_MID] && bands[AA_FOURIER_MID] > bands[AA_FOURIER_LOW]);
	/* identical images: every band is exactly 0 */
	assert_int_equal(aa_fourier_bands_rgba8(&ref, &ref, bands, NULL), 0);
	for (int b = 0; b < AA_FOURIER_BANDS; b++)
		assert_true(bands[b] == 0.0);
	struct aa_image_rgba8 other;
	assert_int_equal(aa_image_rgba8_alloc(&other, 91, 61), 0);
	struct aa_error err = { 0 };
	assert_int_equal(aa_fourier_bands_rgba8(&ref, &other, bands, &err), -1);
	assert_non_null(strstr(err.message, "91x61"));
	aa_image_rgba8_free(&ref);
	aa_image_rgba8_free(&test);
	aa_image_rgba8_free(&other);
}

/* The bands to the last bit on two fixed pairs (97x61: Bluestein on both axes; 640x360: mixed radix),
 * values from the straightforward per-bin sums: a change to how the FFT or the band sums round (an FMA,
 * a reordered sum) shows here, where the 1e-8 to 1e-12 checks above let it through. */
static void make_pair(struct aa_image_rgba8 *a, struct aa_image_rgba8 *b, int w, int h)
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

static void test_bands_pinned_bits(void **state)
{
	(void)state;
	const struct { int w, h; double bands[AA_FOURIER_BANDS]; } pinned[2] = {
		{ 97, 61, { 0x1.d4372fd09ae48p+0, 0x1.9e8a5aaeeed91p+4, 0x1.a4655f5eb5a25p+6 } },
		{ 640, 360, { 0x1.aaaf8fbd17549p+0, 0x1.9016a886b4e2ep+4, 0x1.aec898618cae7p+6 } },
	};
	for (int k = 0; k < 2; k++) {
		struct aa_image_rgba8 a, b;
		assert_int_equal(aa_image_rgba8_alloc(&a, pinned[k].w, pinned[k].h), 0);
		assert_int_equal(aa_image_rgba8_alloc(&b, pinned[k].w, pinned[k].h), 0);
		make_pair(&a, &b, pinned[k].w, pinned[k].h);
		double bands[AA_FOURIER_BANDS];
		struct aa_error err = { 0 };
		assert_int_equal(aa_fourier_bands_rgba8(&a, &b, bands, &err), 0);
		for (int i = 0; i < AA_FOURIER_BANDS; i++)
			if (bands[i] != pinned[k].bands[i])
				fail_msg("%dx%d band %d: %a, pinned %a", pinned[k].w, pinned[k].h, i, bands[i],
					 pinned[k].bands[i]);
		aa_image_rgba8_free(&a);
		aa_image_rgba8_free(&b);
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_fft_matches_dft),
		cmocka_unit_test(test_parseval),
		cmocka_unit_test(test_band_edges),
		cmocka_unit_test(test_sinusoids),
		cmocka_unit_test(test_bands_sum_to_mse),
		cmocka_unit_test(test_bands_pinned_bits),
	};
	return cmocka_run_group_tests_name("fourier", tests, NULL, NULL);
}
