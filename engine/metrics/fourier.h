/* Fourier-band error: the power of the error image's spectrum, split into low, mid and high spatial
 * frequencies (seed 000's "MSE in the Fourier domain", made informative).
 *
 * Let e = test - ref per pixel and channel (R, G, B in 8-bit units) and E its 2-D DFT (unnormalised,
 * E(k) = sum over x of e(x) exp(-2 pi i k.x / N)). A frequency bin (kx, ky) of a WxH image has the radial
 * frequency f = sqrt(fx^2 + fy^2) in cycles per pixel, with fx = min(kx, W - kx) / W and likewise fy, so
 * 0 <= f <= sqrt(0.5^2 + 0.5^2). The bands are
 *   low   f <  1/16         periods longer than 16 pixels: shading, brightness, colour shifts
 *   mid   1/16 <= f < 1/4   periods of 4 to 16 pixels: blur, ringing, displaced edges
 *   high  f >= 1/4          periods shorter than 4 pixels: jaggies, crawling edges, per-pixel noise
 * Each band's value is sum over its bins and channels of |E(k)|^2 / (W H), divided by 3 W H. By Parseval,
 * sum over all bins of |E(k)|^2 / (W H) = sum over pixels of e(x)^2, so low + mid + high = MSE, the same
 * MSE as struct aa_metrics (8-bit units squared, per pixel and channel). */
#ifndef AA_FOURIER_H
#define AA_FOURIER_H

#include "util/error.h"
#include "image/image.h"

enum { AA_FOURIER_LOW, AA_FOURIER_MID, AA_FOURIER_HIGH, AA_FOURIER_BANDS };
/* Band edges in cycles per pixel. */
#define AA_FOURIER_LOW_MID 0.0625
#define AA_FOURIER_MID_HIGH 0.25

/* Names used in results.json and by aalab diff: "low", "mid", "high". */
extern const char *const aa_fourier_band_names[AA_FOURIER_BANDS];

/* MSE carried by each band of two 8-bit images of equal size (alpha ignored); the bands sum to the MSE.
 * Returns -1 with err on a size mismatch or when memory runs out. */
int aa_fourier_bands_rgba8(const struct aa_image_rgba8 *ref, const struct aa_image_rgba8 *test,
			   double band_mse[AA_FOURIER_BANDS], struct aa_error *err);

/* The energy sum of |F(k)|^2 / (W H) per band over `count` real fields of width*height doubles (row-major).
 * The three energies add up to the sum of the squared values (Parseval). threads 0: one per core. */
int aa_fourier_band_energy(const double *const *fields, int count, int width, int height, int threads,
			   double energy[AA_FOURIER_BANDS], struct aa_error *err);

/* Band of frequency bin (kx, ky) of a width x height spectrum. */
int aa_fourier_band_of(int kx, int ky, int width, int height);

/* Forward DFT of n complex values in place (re, im interleaved), unnormalised; any n >= 1 (mixed radix for
 * factors up to 13, Bluestein's algorithm otherwise). Exposed for the unit tests. */
int aa_fft(double *data, int n, struct aa_error *err);

#endif
