/* Per-pixel error metrics (MSE, PSNR, SNR, max error, luminance-error curve) in one pass over the pixels. */
#include "metrics/metrics.h"

#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

/* Rec. 709 luma weights, applied to sRGB-encoded values as the curve's definition says. */
#define LUMA_R 0.2126
#define LUMA_G 0.7152
#define LUMA_B 0.0722

double aa_psnr_from_mse(double mse, double peak)
{
	/* Identical images have no finite PSNR; NaN means "report null" to the caller. */
	if (!(mse > 0.0) || !isfinite(mse))
		return NAN;
	return 10.0 * log10(peak * peak / mse);
}

static int check_same_size(int rw, int rh, int tw, int th, struct aa_error *err)
{
	if (rw != tw || rh != th)
		return aa_error_set(err, AA_ERR_INVALID, "",
				    "cannot compare a %dx%d image against a %dx%d reference", tw, th, rw, rh);
	if (rw <= 0 || rh <= 0)
		return aa_error_set(err, AA_ERR_INVALID, "", "cannot compare empty images");
	return 0;
}

static bool have_pixels(const void *ref, const void *test, struct aa_error *err)
{
	if (ref && test)
		return true;
	aa_error_set(err, AA_ERR_INVALID, "", "cannot compare images without pixels");
	return false;
}

/* Per-pixel constants as tables, each entry the value the expression gives, so that every sum and
 * comparison is the same: the thresholds i/100 (two or three compared for every pixel, without their
 * divisions) and each luma weight times each 8-bit value. */
static double threshold_of[AA_THRESHOLD_COUNT];
static double luma_r[256], luma_g[256], luma_b[256];
static pthread_once_t tables_once = PTHREAD_ONCE_INIT;

static void tables_init(void)
{
	for (int i = 0; i < AA_THRESHOLD_COUNT; i++)
		threshold_of[i] = i / 100.0;
	for (int v = 0; v < 256; v++) {
		luma_r[v] = LUMA_R * v;
		luma_g[v] = LUMA_G * v;
		luma_b[v] = LUMA_B * v;
	}
}

/* Index of the last threshold i/100 that err exceeds (strictly), or -1 when err exceeds none.
 * The estimate from err*100 is corrected with the exact comparisons the curve is defined by. */
static int last_threshold_exceeded(double err)
{
	int i = (int)(err * 100.0);
	if (i > AA_THRESHOLD_COUNT - 1)
		i = AA_THRESHOLD_COUNT - 1;
	while (i >= 0 && !(err > threshold_of[i]))
		i--;
	while (i + 1 < AA_THRESHOLD_COUNT && err > threshold_of[i + 1])
		i++;
	return i;
}

int aa_metrics_compare(const struct aa_image_rgba8 *ref, const struct aa_image_rgba8 *test,
		       struct aa_metrics *out, struct aa_error *err)
{
	if (aa_metrics_compare_pixels(ref, test, out, err))
		return -1;
	out->ssim = aa_ssim_rgba8(ref, test);
	return 0;
}

int aa_metrics_compare_pixels(const struct aa_image_rgba8 *ref, const struct aa_image_rgba8 *test,
			      struct aa_metrics *out, struct aa_error *err)
{
	memset(out, 0, sizeof *out);
	if (check_same_size(ref->width, ref->height, test->width, test->height, err) != 0 ||
	    !have_pixels(ref->pixels, test->pixels, err))
		return -1;

	pthread_once(&tables_once, tables_init);
	/* 8-bit sums fit easily in 64-bit integers (255^2 * 3 * 32768^2 < 2^63), so they are exact. */
	size_t n = (size_t)ref->width * ref->height;
	uint64_t sum_sq_err = 0, sum_sq_ref = 0;
	int max_abs = 0;
	size_t last_exceeded_count[AA_THRESHOLD_COUNT] = { 0 };
	for (size_t p = 0; p < n; p++) {
		const uint8_t *r = ref->pixels + 4 * p, *t = test->pixels + 4 * p;
		for (int c = 0; c < 3; c++) {
			int d = (int)t[c] - (int)r[c];
			int a = d < 0 ? -d : d;
			sum_sq_err += (uint64_t)(d * d);
			sum_sq_ref += (uint64_t)r[c] * r[c];
			if (a > max_abs)
				max_abs = a;
		}
		double y_ref = (luma_r[r[0]] + luma_g[r[1]] + luma_b[r[2]]) / 255.0;
		double y_test = (luma_r[t[0]] + luma_g[t[1]] + luma_b[t[2]]) / 255.0;
		int last = last_threshold_exceeded(fabs(y_test - y_ref));
		if (last >= 0)
			last_exceeded_count[last]++;
	}

	double samples = 3.0 * (double)n;
	out->mse = (double)sum_sq_err / samples;
	out->rmsd = sqrt(out->mse);
	out->identical = sum_sq_err == 0;
	out->psnr = aa_psnr_from_mse(out->mse, 255.0);
	double signal = (double)sum_sq_ref / samples;
	out->snr = (out->identical || signal == 0.0) ? NAN : 10.0 * log10(signal / out->mse);
	out->max_abs = max_abs;
	/* A pixel exceeding threshold i exceeds all lower ones: accumulate from the top down. */
	size_t above = 0;
	for (int i = AA_THRESHOLD_COUNT - 1; i >= 0; i--) {
		above += last_exceeded_count[i];
		out->exceed[i] = (double)above / (double)n;
	}
	out->ssim = NAN;
	out->flip_mean = NAN;
	for (int b = 0; b < AA_FOURIER_BANDS; b++)
		out->fourier[b] = NAN;
	return 0;
}

long aa_metrics_count_over(const struct aa_image_rgba8 *ref, const struct aa_image_rgba8 *test, double threshold)
{
	if (ref->width != test->width || ref->height != test->height || !ref->pixels || !test->pixels)
		return -1;
	const double limit = threshold * 255.0;
	const size_t n = (size_t)ref->width * ref->height;
	long over = 0;
	for (size_t p = 0; p < n; p++) {
		const uint8_t *r = ref->pixels + 4 * p, *t = test->pixels + 4 * p;
		bool any = false;
		for (int c = 0; c < 3; c++)
			any = any || abs((int)t[c] - (int)r[c]) > limit;
		over += any;
	}
	return over;
}

int aa_metrics_perceptual(const struct aa_image_rgba8 *ref, const struct aa_image_rgba8 *test,
			  struct aa_metrics *out, struct aa_image_rgba8 *flip_image, struct aa_error *err)
{
	return aa_metrics_perceptual_shared(NULL, ref, test, out, flip_image, err);
}

int aa_metrics_perceptual_shared(const struct aa_flip_reference *flip_ref, const struct aa_image_rgba8 *ref,
				 const struct aa_image_rgba8 *test, struct aa_metrics *out,
				 struct aa_image_rgba8 *flip_image, struct aa_error *err)
{
	out->flip_mean = NAN;
	if (check_same_size(ref->width, ref->height, test->width, test->height, err) != 0 ||
	    !have_pixels(ref->pixels, test->pixels, err))
		return -1;
	size_t n = (size_t)ref->width * ref->height;
	float *map = malloc(n * sizeof *map);
	if (!map)
		return aa_error_set(err, AA_ERR_LIMIT, "", "out of memory for a %dx%d FLIP map", ref->width, ref->height);
	int rc = flip_ref ? aa_flip_ldr_rgba8_against(flip_ref, test, NULL, map, err)
			  : aa_flip_ldr_rgba8(ref, test, NULL, map, err);
	if (rc == 0) {
		out->flip_mean = aa_flip_mean(map, n); /* the weighted quartiles (aa_flip_pool) are not reported */
		if (flip_image && flip_image->width == ref->width && flip_image->height == ref->height)
			aa_flip_colorize(map, true, flip_image);
	}
	free(map);
	if (rc == 0)
		rc = aa_fourier_bands_rgba8(ref, test, out->fourier, err);
	return rc;
}

int aa_metrics_psnr_linear(const struct aa_image_rgbaf *ref, const struct aa_image_rgbaf *test,
			   double *mse, double *psnr, bool *identical, struct aa_error *err)
{
	*mse = 0.0;
	*psnr = NAN;
	*identical = false;
	if (check_same_size(ref->width, ref->height, test->width, test->height, err) != 0 ||
	    !have_pixels(ref->pixels, test->pixels, err))
		return -1;
	size_t n = (size_t)ref->width * ref->height;
	double sum = 0.0;
	for (size_t p = 0; p < n; p++) {
		for (int c = 0; c < 3; c++) {
			double r = ref->pixels[4 * p + c], t = test->pixels[4 * p + c];
			/* A NaN or Inf would make every number NaN; say where it is instead. */
			if (!isfinite(r) || !isfinite(t))
				return aa_error_set(err, AA_ERR_INVALID, "",
						    "%s image has a non-finite value at pixel (%zu, %zu) channel %d",
						    isfinite(r) ? "test" : "reference", p % (size_t)ref->width,
						    p / (size_t)ref->width, c);
			double d = t - r;
			sum += d * d;
		}
	}
	if (!isfinite(sum))
		return aa_error_set(err, AA_ERR_INVALID, "",
				    "linear images differ by more than a double can square; check for runaway values");
	*mse = sum / (3.0 * (double)n);
	*identical = sum == 0.0;
	*psnr = aa_psnr_from_mse(*mse, 1.0);
	return 0;
}
