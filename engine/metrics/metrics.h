/* Image-quality metrics of a test image against a reference, computed on the CPU in double precision. */
#ifndef AA_METRICS_H
#define AA_METRICS_H

#include <stdbool.h>

#include "image/image.h"
#include "metrics/flip.h"
#include "metrics/fourier.h"

/* The error-threshold curve (seed 002, Fig. 1): thresholds 0, 0.01, ..., 1.00 on luminance error. */
#define AA_THRESHOLD_COUNT 101

struct aa_metrics {
	double mse;        /* mean over pixels and R,G,B of squared error, in 8-bit units (0..255) */
	double rmsd;       /* sqrt(mse) */
	double psnr;       /* 10 log10(255^2 / mse) dB; NAN when identical */
	bool identical;    /* mse == 0 exactly: psnr is reported as null */
	double snr;        /* 10 log10(signal power of reference / mse) dB; NAN when identical or no signal */
	double ssim;       /* mean SSIM, Gaussian 11x11 sigma 1.5, K1 0.01, K2 0.03, L 255, averaged over R,G,B */
	double max_abs;    /* largest |difference| over pixels and R,G,B, 8-bit units */
	/* share (0..1) of pixels whose luminance error |Y(test) - Y(ref)| > threshold i/100, where Y is
	 * Rec. 709 luma of the sRGB-encoded values scaled to [0,1]. */
	double exceed[AA_THRESHOLD_COUNT];
	/* Filled by aa_metrics_perceptual; NAN until then (and in results.json, null). */
	double flip_mean;  /* mean LDR-FLIP error (flip.h) at AA_FLIP_DEFAULT_PPD, 0 = identical, 1 = most */
	double fourier[AA_FOURIER_BANDS]; /* the MSE split into low, mid and high frequencies (fourier.h) */
};

/* Compares two 8-bit sRGB images of equal size (alpha ignored). Returns -1 with err on size mismatch. */
int aa_metrics_compare(const struct aa_image_rgba8 *ref, const struct aa_image_rgba8 *test,
		       struct aa_metrics *out, struct aa_error *err);

/* The same without SSIM (NAN): the error sums alone, e.g. a reference's N/2 image against its N one. */
int aa_metrics_compare_pixels(const struct aa_image_rgba8 *ref, const struct aa_image_rgba8 *test,
			      struct aa_metrics *out, struct aa_error *err);

/* idiff's count: pixels where any of R,G,B differs by more than threshold x 255 (threshold a share of
 * full scale, 0..1). -1 on a size mismatch. */
long aa_metrics_count_over(const struct aa_image_rgba8 *ref, const struct aa_image_rgba8 *test, double threshold);

/* FLIP (mean over the map) and the Fourier bands of two 8-bit sRGB images, into out->flip_mean and
 * out->fourier. When flip_image is not NULL (allocated at the images' size) it receives the FLIP error
 * map in the magma colour map. Returns -1 with err on a size mismatch or when memory runs out. */
int aa_metrics_perceptual(const struct aa_image_rgba8 *ref, const struct aa_image_rgba8 *test,
			  struct aa_metrics *out, struct aa_image_rgba8 *flip_image, struct aa_error *err);
/* The same with the FLIP reference side made once for ref (aa_flip_reference_rgba8 at the default ppd),
 * for scoring several images against one reference; flip_ref NULL makes it here. Identical results. */
int aa_metrics_perceptual_shared(const struct aa_flip_reference *flip_ref, const struct aa_image_rgba8 *ref,
				 const struct aa_image_rgba8 *test, struct aa_metrics *out,
				 struct aa_image_rgba8 *flip_image, struct aa_error *err);

/* Linear-float mode: MSE/PSNR on linear values with peak 1.0 (values are not clamped). */
int aa_metrics_psnr_linear(const struct aa_image_rgbaf *ref, const struct aa_image_rgbaf *test,
			   double *mse, double *psnr, bool *identical, struct aa_error *err);

/* PSNR of a mean MSE (for sequence means): NAN when mse == 0. */
double aa_psnr_from_mse(double mse, double peak);

/* SSIM alone, on RGB(A)8 averaged over R,G,B (L = 255) or on one channel of doubles with the given
 * data range. Matches skimage.metrics.structural_similarity(gaussian_weights=True, sigma=1.5,
 * use_sample_covariance=False); images smaller than 11x11, which skimage refuses, are averaged over
 * every pixel with reflected borders. NaN on size mismatch or when out of memory. */
double aa_ssim_rgba8(const struct aa_image_rgba8 *ref, const struct aa_image_rgba8 *test);
double aa_ssim_channel(const double *ref, const double *test, int width, int height, double data_range);

/* engine/metrics/flicker.c: the mean over pixels and R,G,B of |(m[t] - m[t-1]) - (r[t] - r[t-1])|, the
 * change between frames that the reference does not have (8-bit units); all four images of one size.
 * aa_job_run scores each frame with it, and aalab merge the frames across shard borders. */
/* engine/metrics/change.c: the mean over pixels and R,G,B of |a - b| (8-bit units). */
double aa_metrics_mean_change(const struct aa_image_rgba8 *a, const struct aa_image_rgba8 *b);
double aa_metrics_flicker(const struct aa_image_rgba8 *m, const struct aa_image_rgba8 *m_prev,
			  const struct aa_image_rgba8 *r, const struct aa_image_rgba8 *r_prev);

#endif
