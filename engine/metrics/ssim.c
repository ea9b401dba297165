/* Mean SSIM with an 11-tap Gaussian window, computed the way scikit-image 0.19 does it (our test oracle).
 *
 * skimage.metrics.structural_similarity(gaussian_weights=True, sigma=1.5, use_sample_covariance=False,
 * data_range=L) converts each channel to float64, filters x, y, x*x, y*y and x*y with
 * scipy.ndimage.gaussian_filter (truncate 3.5 -> radius int(3.5*1.5+0.5) = 5, mode 'reflect', which is
 * half-sample symmetric: d c b a | a b c d), builds the SSIM map with K1 0.01, K2 0.03 and population
 * covariances, drops a border of (11-1)/2 = 5 pixels and averages; channels are averaged at the end.
 * Because the border dropped equals the filter radius, the kept pixels never read across an edge; the
 * reflection only matters for images smaller than the window, which skimage refuses and we average whole.
 *
 * The filter is separable: a vertical pass over a ring of the 11 source rows, then a horizontal pass,
 * each in blocks that stay in L1 and vectorise. Bands of rows run on separate threads. */
#include "metrics/metrics.h"

#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define SSIM_SIGMA 1.5
#define SSIM_RADIUS 5 /* int(3.5 * SSIM_SIGMA + 0.5), as scipy computes it */
#define SSIM_TAPS (2 * SSIM_RADIUS + 1)
#define SSIM_K1 0.01
#define SSIM_K2 0.03
#define MAX_CHANNELS 3
#define BLOCK 240 /* doubles per block: a multiple of 1, 2 and 3 channels, small enough for L1 */
#define MAX_THREADS 8
#define MIN_PIXELS_PER_THREAD 65536

#if defined(__x86_64__) && defined(__has_attribute)
#if __has_attribute(target_clones)
#define VECTOR_CLONES __attribute__((target_clones("avx2", "default")))
#endif
#endif
#ifndef VECTOR_CLONES
#define VECTOR_CLONES
#endif

/* The filtered quantities per pixel: weighted means of x, y, x*x + y*y and x*y. SSIM needs the x*x and
 * y*y means only through their sum (in vx + vy), so filtering the sum saves a fifth of the work; it
 * changes results only by rounding (below 1e-14 against skimage; the oracle allows 1e-4). */
enum { MU_X, MU_Y, MU_SQ, MU_XY, MOMENTS };

/* Two images of `channels` interleaved values per pixel: 8-bit RGBA (RGB used, 3 channels) or doubles. */
struct ssim_source {
	const uint8_t *ref8, *test8;
	const double *refd, *testd;
	int width, height, channels;
	double c1, c2;
	double weight[SSIM_RADIUS + 1]; /* weight[j] for offsets +j and -j */
	int x0, x1, y0, y1;             /* the SSIM-map pixels that are averaged */
};

/* One band of output rows and the scratch memory it needs. */
struct ssim_band {
	const struct ssim_source *src;
	int y_begin, y_end;
	double *ring_ref, *ring_test;        /* SSIM_TAPS source rows as doubles */
	size_t row_len;                      /* doubles per row, rounded up to whole blocks */
	int ring_row[SSIM_TAPS];             /* which source row each ring slot holds, -1 when none */
	double *moments[MOMENTS];            /* vertically filtered row, padded by SSIM_RADIUS pixels */
	double sum[MAX_CHANNELS];            /* sum of the SSIM map over the band, per channel */
};

/* scipy 'reflect' boundary: index into a sequence extended by mirror images of itself, edge repeated. */
static int reflect_index(int i, int n)
{
	int period = 2 * n;
	i %= period;
	if (i < 0)
		i += period;
	return i < n ? i : period - 1 - i;
}

static void gaussian_weights(double weight[SSIM_RADIUS + 1])
{
	double all[SSIM_TAPS], total = 0.0;
	for (int k = 0; k < SSIM_TAPS; k++) {
		double x = k - SSIM_RADIUS;
		all[k] = exp(-0.5 / (SSIM_SIGMA * SSIM_SIGMA) * x * x);
		total += all[k];
	}
	for (int j = 0; j <= SSIM_RADIUS; j++)
		weight[j] = all[SSIM_RADIUS + j] / total;
}

/* Returns source row y of both images as doubles, converting it into the ring on first use.
 * Rows an output row needs form a contiguous range of at most SSIM_TAPS rows, so y % SSIM_TAPS
 * never evicts a row that is still needed. */
static void ring_get(struct ssim_band *band, int y, const double **ref, const double **test)
{
	const struct ssim_source *src = band->src;
	size_t row_len = (size_t)src->width * src->channels;
	int slot = y % SSIM_TAPS;
	double *r = band->ring_ref + slot * band->row_len, *t = band->ring_test + slot * band->row_len;
	if (band->ring_row[slot] != y) {
		if (src->ref8) {
			const uint8_t *r8 = src->ref8 + (size_t)y * src->width * 4;
			const uint8_t *t8 = src->test8 + (size_t)y * src->width * 4;
			for (int x = 0; x < src->width; x++) {
				r[3 * x] = r8[4 * x];
				r[3 * x + 1] = r8[4 * x + 1];
				r[3 * x + 2] = r8[4 * x + 2];
				t[3 * x] = t8[4 * x];
				t[3 * x + 1] = t8[4 * x + 1];
				t[3 * x + 2] = t8[4 * x + 2];
			}
		} else {
			memcpy(r, src->refd + (size_t)y * row_len, row_len * sizeof(double));
			memcpy(t, src->testd + (size_t)y * row_len, row_len * sizeof(double));
		}
		band->ring_row[slot] = y;
	}
	*ref = r;
	*test = t;
}

/* Kernels: every loop runs exactly BLOCK times over restrict pointers (rows are allocated in whole
 * blocks), which lets the compiler vectorise them at plain -O2. They follow scipy's symmetric
 * correlation, w0*v0 + sum over j = R..1 of wj*(v[-j] + v[+j]), with squares taken before filtering.
 * On x86-64 each is also compiled for AVX2 (four doubles a vector rather than two), chosen at load time:
 * only adds and multiplies, never FMA, each lane in the scalar order, so the SSIM is the same to the bit. */
VECTOR_CLONES static void vertical_centre(const double *restrict a, const double *restrict b, double w0,
			    double *restrict mx, double *restrict my, double *restrict msq,
			    double *restrict mxy)
{
	for (int e = 0; e < BLOCK; e++) {
		mx[e] = a[e] * w0;
		my[e] = b[e] * w0;
		msq[e] = (a[e] * a[e] + b[e] * b[e]) * w0;
		mxy[e] = (a[e] * b[e]) * w0;
	}
}

VECTOR_CLONES static void vertical_tap(const double *restrict a_up, const double *restrict a_dn,
			 const double *restrict b_up, const double *restrict b_dn, double wj,
			 double *restrict mx, double *restrict my, double *restrict msq,
			 double *restrict mxy)
{
	for (int e = 0; e < BLOCK; e++) {
		mx[e] += (a_up[e] + a_dn[e]) * wj;
		my[e] += (b_up[e] + b_dn[e]) * wj;
		msq[e] += ((a_up[e] * a_up[e] + b_up[e] * b_up[e]) + (a_dn[e] * a_dn[e] + b_dn[e] * b_dn[e])) * wj;
		mxy[e] += (a_up[e] * b_up[e] + a_dn[e] * b_dn[e]) * wj;
	}
}

/* `step` is the distance between horizontally adjacent pixels: the channel count. */
VECTOR_CLONES static void horizontal_block(const double *restrict v, int step, const double *w, double *restrict out)
{
	for (int e = 0; e < BLOCK; e++)
		out[e] = v[e] * w[0];
	for (int j = SSIM_RADIUS; j >= 1; j--) {
		double wj = w[j];
		int off = j * step;
		for (int e = 0; e < BLOCK; e++)
			out[e] += (v[e - off] + v[e + off]) * wj;
	}
}

/* The SSIM map from the filtered moments, in skimage's order of operations. */
VECTOR_CLONES static void ssim_block(const double (*restrict h)[BLOCK], double c1, double c2, double *restrict ssim)
{
	for (int e = 0; e < BLOCK; e++) {
		double ux = h[MU_X][e], uy = h[MU_Y][e];
		double vx_plus_vy = h[MU_SQ][e] - (ux * ux + uy * uy);
		double vxy = h[MU_XY][e] - ux * uy;
		double a1 = 2.0 * ux * uy + c1, a2 = 2.0 * vxy + c2;
		double b1 = ux * ux + uy * uy + c1, b2 = vx_plus_vy + c2;
		ssim[e] = (a1 * a2) / (b1 * b2);
	}
}

/* Vertical pass for output row y: filters the moments down the columns into band->moments. */
static void filter_vertical(struct ssim_band *band, int y)
{
	const struct ssim_source *src = band->src;
	const double *w = src->weight;
	const double *ref_row[SSIM_TAPS], *test_row[SSIM_TAPS];
	for (int k = 0; k < SSIM_TAPS; k++)
		ring_get(band, reflect_index(y + k - SSIM_RADIUS, src->height), &ref_row[k], &test_row[k]);

	size_t pad = (size_t)SSIM_RADIUS * src->channels;
	for (size_t e = 0; e < band->row_len; e += BLOCK) {
		double *mx = band->moments[MU_X] + pad + e, *my = band->moments[MU_Y] + pad + e;
		double *msq = band->moments[MU_SQ] + pad + e, *mxy = band->moments[MU_XY] + pad + e;
		vertical_centre(ref_row[SSIM_RADIUS] + e, test_row[SSIM_RADIUS] + e, w[0], mx, my, msq, mxy);
		for (int j = SSIM_RADIUS; j >= 1; j--)
			vertical_tap(ref_row[SSIM_RADIUS - j] + e, ref_row[SSIM_RADIUS + j] + e,
				     test_row[SSIM_RADIUS - j] + e, test_row[SSIM_RADIUS + j] + e, w[j],
				     mx, my, msq, mxy);
	}
}

/* Fills the SSIM_RADIUS padding pixels on each side of the moment rows by reflection. */
static void pad_moments(struct ssim_band *band)
{
	const struct ssim_source *src = band->src;
	int ch = src->channels;
	for (int m = 0; m < MOMENTS; m++) {
		double *row = band->moments[m] + SSIM_RADIUS * ch;
		for (int p = 1; p <= SSIM_RADIUS; p++) {
			int left = reflect_index(-p, src->width), right = reflect_index(src->width - 1 + p, src->width);
			for (int c = 0; c < ch; c++) {
				row[-p * ch + c] = row[left * ch + c];
				row[(src->width - 1 + p) * ch + c] = row[right * ch + c];
			}
		}
	}
}

/* Horizontal pass over the kept columns, then the SSIM map, summed per channel. */
static void filter_horizontal_and_sum(struct ssim_band *band)
{
	const struct ssim_source *src = band->src;
	int ch = src->channels;
	double h[MOMENTS][BLOCK], ssim[BLOCK];
	int n_begin = src->x0 * ch, n_end = src->x1 * ch;
	double row_sum[MAX_CHANNELS] = { 0 };
	for (int e0 = n_begin; e0 < n_end; e0 += BLOCK) {
		for (int m = 0; m < MOMENTS; m++)
			horizontal_block(band->moments[m] + SSIM_RADIUS * ch + e0, ch, src->weight, h[m]);
		ssim_block((const double (*)[BLOCK])h, src->c1, src->c2, ssim);
		/* Only the kept pixels count; blocks start on a pixel (BLOCK is a multiple of ch). */
		int len = e0 + BLOCK < n_end ? BLOCK : n_end - e0;
		for (int e = 0; e < len; e += ch)
			for (int c = 0; c < ch; c++)
				row_sum[c] += ssim[e + c];
	}
	for (int c = 0; c < ch; c++)
		band->sum[c] += row_sum[c];
}

static void *band_run(void *arg)
{
	struct ssim_band *band = arg;
	for (int y = band->y_begin; y < band->y_end; y++) {
		filter_vertical(band, y);
		pad_moments(band);
		filter_horizontal_and_sum(band);
	}
	return NULL;
}

static void band_free(struct ssim_band *band)
{
	free(band->ring_ref);
	free(band->ring_test);
	for (int m = 0; m < MOMENTS; m++)
		free(band->moments[m]);
}

static int band_init(struct ssim_band *band, const struct ssim_source *src, int y_begin, int y_end)
{
	memset(band, 0, sizeof *band);
	band->src = src;
	band->y_begin = y_begin;
	band->y_end = y_end;
	/* Zero-filled, so the tails of the last block hold finite values that are computed and ignored. */
	size_t pixels_len = (size_t)src->width * src->channels;
	band->row_len = (pixels_len + BLOCK - 1) / BLOCK * BLOCK;
	/* Moment rows: left padding, the blocks the vertical pass writes, and what the last horizontal block
	 * reads beyond them (it starts at x0 and looks SSIM_RADIUS pixels further). */
	size_t moments_len = band->row_len + 4 * (size_t)SSIM_RADIUS * src->channels;
	band->ring_ref = calloc(SSIM_TAPS * band->row_len, sizeof(double));
	band->ring_test = calloc(SSIM_TAPS * band->row_len, sizeof(double));
	int ok = band->ring_ref && band->ring_test;
	for (int m = 0; m < MOMENTS; m++) {
		band->moments[m] = calloc(moments_len, sizeof(double));
		ok = ok && band->moments[m];
	}
	for (int k = 0; k < SSIM_TAPS; k++)
		band->ring_row[k] = -1;
	if (!ok) {
		band_free(band);
		return -1;
	}
	return 0;
}

static int thread_count(long pixels)
{
	long cpus = sysconf(_SC_NPROCESSORS_ONLN);
	long by_size = pixels / MIN_PIXELS_PER_THREAD;
	long n = cpus < by_size ? cpus : by_size;
	if (n > MAX_THREADS)
		n = MAX_THREADS;
	return n < 1 ? 1 : (int)n;
}

/* Runs the bands (on threads when the image is large enough) and returns the mean SSIM;
 * NaN if memory runs out. */
static double ssim_run(struct ssim_source *src, double data_range)
{
	src->c1 = (SSIM_K1 * data_range) * (SSIM_K1 * data_range);
	src->c2 = (SSIM_K2 * data_range) * (SSIM_K2 * data_range);
	gaussian_weights(src->weight);
	/* skimage crops the window radius; images smaller than the window are averaged whole. */
	bool crop = src->width >= SSIM_TAPS && src->height >= SSIM_TAPS;
	int border = crop ? SSIM_RADIUS : 0;
	src->x0 = border;
	src->x1 = src->width - border;
	src->y0 = border;
	src->y1 = src->height - border;

	int rows = src->y1 - src->y0;
	int threads = thread_count((long)rows * (src->x1 - src->x0));
	if (threads > rows)
		threads = rows;
	struct ssim_band bands[MAX_THREADS];
	pthread_t tids[MAX_THREADS];
	bool started[MAX_THREADS] = { false };
	int ready = 0;
	for (int t = 0; t < threads; t++) {
		int y_begin = src->y0 + (int)((long)rows * t / threads);
		int y_end = src->y0 + (int)((long)rows * (t + 1) / threads);
		if (band_init(&bands[t], src, y_begin, y_end) != 0)
			break;
		ready++;
	}
	if (ready < threads) {
		for (int t = 0; t < ready; t++)
			band_free(&bands[t]);
		return NAN;
	}
	/* Band 0 runs on this thread; a band whose thread cannot start also runs here. */
	for (int t = 1; t < threads; t++)
		started[t] = pthread_create(&tids[t], NULL, band_run, &bands[t]) == 0;
	band_run(&bands[0]);
	for (int t = 1; t < threads; t++) {
		if (started[t])
			pthread_join(tids[t], NULL);
		else
			band_run(&bands[t]);
	}

	double per_channel[MAX_CHANNELS] = { 0 };
	for (int t = 0; t < threads; t++) {
		for (int c = 0; c < src->channels; c++)
			per_channel[c] += bands[t].sum[c];
		band_free(&bands[t]);
	}
	double count = (double)rows * (double)(src->x1 - src->x0);
	double mean = 0.0;
	for (int c = 0; c < src->channels; c++)
		mean += per_channel[c] / count;
	return mean / src->channels;
}

double aa_ssim_rgba8(const struct aa_image_rgba8 *ref, const struct aa_image_rgba8 *test)
{
	if (!ref->pixels || !test->pixels || ref->width != test->width || ref->height != test->height ||
	    ref->width <= 0 || ref->height <= 0)
		return NAN;
	struct ssim_source src = {
		.ref8 = ref->pixels, .test8 = test->pixels,
		.width = ref->width, .height = ref->height, .channels = 3,
	};
	return ssim_run(&src, 255.0);
}

double aa_ssim_channel(const double *ref, const double *test, int width, int height, double data_range)
{
	if (!ref || !test || width <= 0 || height <= 0 || !(data_range > 0.0))
		return NAN;
	struct ssim_source src = {
		.refd = ref, .testd = test, .width = width, .height = height, .channels = 1,
	};
	return ssim_run(&src, data_range);
}
