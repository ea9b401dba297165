/* Fourier-band error (fourier.h): a 2-D FFT of the error image, its power summed per frequency band.
 *
 * The FFT is our own: recursive mixed-radix decimation in time with butterflies for radix 2, 3, 4 and 5
 * and a generic one for 7, 11 and 13; lengths with a larger prime factor use Bluestein's algorithm (a
 * chirp convolution done with a power-of-two FFT). Two real channels share one complex transform
 * (z = eR + i eG): the band of a bin equals the band of its mirror -k, so summing |Z(k)|^2 over a band gives
 * the band energy of R plus that of G without separating the spectra. Rows are transformed in place, then
 * columns are gathered a few at a time and their power accumulated per band; both passes are split
 * between threads. */
#include "metrics/fourier.h"

#include <math.h>
#include <pthread.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define MAX_DIRECT_PRIME 13
#define MAX_FACTORS 40
#define MAX_THREADS 8
#define MIN_PIXELS_PER_THREAD 32768
#define GATHER 8 /* columns gathered at once: 8 complex values of a row are two cache lines */

const char *const aa_fourier_band_names[AA_FOURIER_BANDS] = { "low", "mid", "high" };

struct cpx {
	double re, im;
};

static inline struct cpx cmul(struct cpx a, struct cpx b)
{
	return (struct cpx){ a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re };
}

struct fft_plan {
	int n;
	int factor_count;
	int factors[MAX_FACTORS];
	struct cpx *twiddle;        /* exp(-2 pi i j / n), j < n */
	/* Bluestein: n is computed as a convolution of length m (a power of two) */
	struct fft_plan *conv;
	struct cpx *chirp;          /* exp(-pi i j^2 / n), j < n */
	struct cpx *chirp_spectrum; /* DFT of the conjugate chirp, wrapped to length m */
};

/* Scratch memory one thread needs to run a plan. */
struct fft_work {
	struct cpx *a, *b; /* n (or m with Bluestein) values each */
};

static void plan_free(struct fft_plan *p)
{
	if (!p)
		return;
	free(p->twiddle);
	free(p->chirp);
	free(p->chirp_spectrum);
	plan_free(p->conv);
	free(p);
}

/* Splits n into radices: 4s first (the cheapest butterfly), then 2, 3, 5, ... Returns false when a prime
 * factor is larger than MAX_DIRECT_PRIME. */
static bool factorise(int n, struct fft_plan *p)
{
	p->factor_count = 0;
	while (n % 4 == 0) {
		p->factors[p->factor_count++] = 4;
		n /= 4;
	}
	for (int f = 2; n > 1 && f <= MAX_DIRECT_PRIME;) {
		if (n % f == 0) {
			p->factors[p->factor_count++] = f;
			n /= f;
		} else {
			f++;
		}
	}
	return n == 1;
}

static void fft_run(const struct fft_plan *p, struct cpx *out, const struct cpx *in, struct fft_work *w);

static struct fft_plan *plan_create(int n)
{
	struct fft_plan *p = calloc(1, sizeof *p);
	if (!p)
		return NULL;
	p->n = n;
	if (n == 1 || factorise(n, p)) {
		p->twiddle = malloc((size_t)n * sizeof *p->twiddle);
		if (!p->twiddle)
			goto fail;
		for (int j = 0; j < n; j++) {
			double angle = -2.0 * M_PI * (double)j / (double)n;
			p->twiddle[j] = (struct cpx){ cos(angle), sin(angle) };
		}
		return p;
	}
	int m = 1;
	while (m < 2 * n - 1)
		m *= 2;
	p->conv = plan_create(m);
	p->chirp = malloc((size_t)n * sizeof *p->chirp);
	p->chirp_spectrum = calloc((size_t)m, sizeof *p->chirp_spectrum);
	struct cpx *tmp = malloc((size_t)m * sizeof *tmp);
	struct fft_work w = { malloc((size_t)m * sizeof(struct cpx)), malloc((size_t)m * sizeof(struct cpx)) };
	bool ok = p->conv && p->chirp && p->chirp_spectrum && tmp && w.a && w.b;
	if (ok) {
		for (int j = 0; j < n; j++) {
			/* j^2 mod 2n keeps the angle small, and so exact enough, for large j */
			long long j2 = (long long)j * j % (2LL * n);
			double angle = -M_PI * (double)j2 / (double)n;
			p->chirp[j] = (struct cpx){ cos(angle), sin(angle) };
		}
		struct cpx *b = p->chirp_spectrum; /* b(j) = conj(chirp(|j|)), wrapped: b(m - j) = b(j) */
		for (int j = 0; j < n; j++) {
			b[j] = (struct cpx){ p->chirp[j].re, -p->chirp[j].im };
			if (j > 0)
				b[m - j] = b[j];
		}
		memcpy(tmp, b, (size_t)m * sizeof *tmp);
		fft_run(p->conv, b, tmp, &w);
	}
	free(tmp);
	free(w.a);
	free(w.b);
	if (ok)
		return p;
fail:
	plan_free(p);
	return NULL;
}

/* One stage: combines `radix` DFTs of length m (stored one after the other in out) into one of length
 * radix*m. tw_step scales indices of this length into the twiddle table of the plan. */
static void butterflies(const struct cpx *tw, struct cpx *out, int m, int radix, int tw_step)
{
	if (radix == 2) {
		for (int k = 0; k < m; k++) {
			struct cpx a = out[k], t = cmul(out[k + m], tw[k * tw_step]);
			out[k] = (struct cpx){ a.re + t.re, a.im + t.im };
			out[k + m] = (struct cpx){ a.re - t.re, a.im - t.im };
		}
		return;
	}
	if (radix == 4) {
		for (int k = 0; k < m; k++) {
			struct cpx a0 = out[k], a1 = cmul(out[k + m], tw[k * tw_step]);
			struct cpx a2 = cmul(out[k + 2 * m], tw[2 * k * tw_step]);
			struct cpx a3 = cmul(out[k + 3 * m], tw[3 * k * tw_step]);
			struct cpx b0 = { a0.re + a2.re, a0.im + a2.im }, b1 = { a0.re - a2.re, a0.im - a2.im };
			struct cpx b2 = { a1.re + a3.re, a1.im + a3.im }, b3 = { a1.re - a3.re, a1.im - a3.im };
			out[k] = (struct cpx){ b0.re + b2.re, b0.im + b2.im };
			out[k + 2 * m] = (struct cpx){ b0.re - b2.re, b0.im - b2.im };
			/* forward transform: X1 = b1 - i b3, X3 = b1 + i b3 */
			out[k + m] = (struct cpx){ b1.re + b3.im, b1.im - b3.re };
			out[k + 3 * m] = (struct cpx){ b1.re - b3.im, b1.im + b3.re };
		}
		return;
	}
	if (radix == 3) {
		const double h = -0.86602540378443864676; /* -sin(2 pi / 3) */
		for (int k = 0; k < m; k++) {
			struct cpx t0 = out[k], t1 = cmul(out[k + m], tw[k * tw_step]);
			struct cpx t2 = cmul(out[k + 2 * m], tw[2 * k * tw_step]);
			struct cpx s = { t1.re + t2.re, t1.im + t2.im }, d = { t1.re - t2.re, t1.im - t2.im };
			struct cpx c = { t0.re - 0.5 * s.re, t0.im - 0.5 * s.im };
			out[k] = (struct cpx){ t0.re + s.re, t0.im + s.im };
			/* X1 = c + i h d, X2 = c - i h d */
			out[k + m] = (struct cpx){ c.re - h * d.im, c.im + h * d.re };
			out[k + 2 * m] = (struct cpx){ c.re + h * d.im, c.im - h * d.re };
		}
		return;
	}
	if (radix == 5) {
		const double c1 = 0.30901699437494742410, c2 = -0.80901699437494742410;
		const double s1 = 0.95105651629515357212, s2 = 0.58778525229247312917;
		for (int k = 0; k < m; k++) {
			struct cpx t0 = out[k], t[5];
			for (int q = 1; q < 5; q++)
				t[q] = cmul(out[k + q * m], tw[q * k * tw_step]);
			struct cpx a1 = { t[1].re + t[4].re, t[1].im + t[4].im }, b1 = { t[1].re - t[4].re, t[1].im - t[4].im };
			struct cpx a2 = { t[2].re + t[3].re, t[2].im + t[3].im }, b2 = { t[2].re - t[3].re, t[2].im - t[3].im };
			struct cpx p1 = { t0.re + c1 * a1.re + c2 * a2.re, t0.im + c1 * a1.im + c2 * a2.im };
			struct cpx p2 = { t0.re + c2 * a1.re + c1 * a2.re, t0.im + c2 * a1.im + c1 * a2.im };
			struct cpx q1 = { s1 * b1.re + s2 * b2.re, s1 * b1.im + s2 * b2.im };
			struct cpx q2 = { s2 * b1.re - s1 * b2.re, s2 * b1.im - s1 * b2.im };
			out[k] = (struct cpx){ t0.re + a1.re + a2.re, t0.im + a1.im + a2.im };
			/* X1 = p1 - i q1, X4 = p1 + i q1, X2 = p2 - i q2, X3 = p2 + i q2 */
			out[k + m] = (struct cpx){ p1.re + q1.im, p1.im - q1.re };
			out[k + 4 * m] = (struct cpx){ p1.re - q1.im, p1.im + q1.re };
			out[k + 2 * m] = (struct cpx){ p2.re + q2.im, p2.im - q2.re };
			out[k + 3 * m] = (struct cpx){ p2.re - q2.im, p2.im + q2.re };
		}
		return;
	}
	struct cpx t[MAX_DIRECT_PRIME];
	const int root_step = tw_step * m; /* exp(-2 pi i / radix) in the table */
	for (int k = 0; k < m; k++) {
		for (int q = 0; q < radix; q++)
			t[q] = q == 0 ? out[k] : cmul(out[k + q * m], tw[q * k * tw_step]);
		for (int s = 0; s < radix; s++) {
			struct cpx sum = t[0];
			for (int q = 1; q < radix; q++) {
				struct cpx v = cmul(t[q], tw[(q * s % radix) * root_step]);
				sum.re += v.re;
				sum.im += v.im;
			}
			out[k + s * m] = sum;
		}
	}
}

static void fft_recursive(const struct fft_plan *p, struct cpx *out, const struct cpx *in, size_t stride, int n,
			  const int *factors, int tw_step)
{
	const int radix = factors[0], m = n / radix;
	if (m == 1) {
		for (int q = 0; q < radix; q++)
			out[q] = in[q * stride];
	} else {
		/* Sub-transform q takes every radix-th input starting at q. */
		for (int q = 0; q < radix; q++)
			fft_recursive(p, out + q * m, in + q * stride, stride * radix, m, factors + 1, tw_step * radix);
	}
	butterflies(p->twiddle, out, m, radix, tw_step);
}

/* out = DFT(in); in and out must not overlap. */
static void fft_run(const struct fft_plan *p, struct cpx *out, const struct cpx *in, struct fft_work *w)
{
	if (p->n == 1) {
		out[0] = in[0];
		return;
	}
	if (!p->conv) {
		fft_recursive(p, out, in, 1, p->n, p->factors, 1);
		return;
	}
	/* Bluestein: X(k) = c(k) sum_j (x(j) c(j)) conj(c(k - j)), a convolution of length m. */
	const int n = p->n, m = p->conv->n;
	struct cpx *a = w->a, *spec = w->b;
	for (int j = 0; j < n; j++)
		a[j] = cmul(in[j], p->chirp[j]);
	memset(a + n, 0, (size_t)(m - n) * sizeof *a);
	struct fft_work inner = { NULL, NULL }; /* the power-of-two plan needs no scratch */
	fft_run(p->conv, spec, a, &inner);
	/* Inverse transform as conj(DFT(conj(.))) / m. */
	for (int k = 0; k < m; k++) {
		struct cpx v = cmul(spec[k], p->chirp_spectrum[k]);
		spec[k] = (struct cpx){ v.re, -v.im };
	}
	fft_run(p->conv, a, spec, &inner);
	const double scale = 1.0 / m;
	for (int k = 0; k < n; k++) {
		struct cpx v = { a[k].re * scale, -a[k].im * scale };
		out[k] = cmul(v, p->chirp[k]);
	}
}

static int work_alloc(const struct fft_plan *p, struct fft_work *w)
{
	size_t len = (size_t)(p->conv ? p->conv->n : p->n);
	w->a = malloc(len * sizeof *w->a);
	w->b = malloc(len * sizeof *w->b);
	return w->a && w->b ? 0 : -1;
}

static void work_free(struct fft_work *w)
{
	free(w->a);
	free(w->b);
}

int aa_fft(double *data, int n, struct aa_error *err)
{
	if (n < 1)
		return aa_error_set(err, AA_ERR_INVALID, "", "FFT length must be positive, got %d", n);
	struct fft_plan *p = plan_create(n);
	struct fft_work w = { NULL, NULL };
	struct cpx *in = malloc((size_t)n * sizeof *in), *out = malloc((size_t)n * sizeof *out);
	int rc = -1;
	if (p && in && out && work_alloc(p, &w) == 0) {
		memcpy(in, data, (size_t)n * sizeof *in);
		fft_run(p, out, in, &w);
		memcpy(data, out, (size_t)n * sizeof *out);
		rc = 0;
	} else {
		aa_error_set(err, AA_ERR_LIMIT, "", "out of memory for an FFT of length %d", n);
	}
	work_free(&w);
	free(in);
	free(out);
	plan_free(p);
	return rc;
}

/* ------------------------------------------------------------------------------------------------ bands */

static inline int band_of_f2(double f2)
{
	if (f2 < AA_FOURIER_LOW_MID * AA_FOURIER_LOW_MID)
		return AA_FOURIER_LOW;
	return f2 < AA_FOURIER_MID_HIGH * AA_FOURIER_MID_HIGH ? AA_FOURIER_MID : AA_FOURIER_HIGH;
}

static inline double axis_frequency(int k, int n)
{
	int folded = k <= n - k ? k : n - k;
	return (double)folded / (double)n;
}

int aa_fourier_band_of(int kx, int ky, int width, int height)
{
	double fx = axis_frequency(kx, width), fy = axis_frequency(ky, height);
	return band_of_f2(fx * fx + fy * fy);
}

struct spectrum_job {
	struct cpx *field;          /* width x height, row-major */
	int width, height;
	const struct fft_plan *row_plan, *col_plan;
	const double *fx2, *fy2;    /* squared axis frequencies */
};

struct spectrum_worker {
	const struct spectrum_job *job;
	int row_begin, row_end, col_begin, col_end;
	struct fft_work row_work, col_work;
	struct cpx *line, *gathered; /* max(width, height) and GATHER x height */
	double energy[AA_FOURIER_BANDS];
	int failed;
};

static void *transform_rows(void *arg)
{
	struct spectrum_worker *wk = arg;
	const struct spectrum_job *job = wk->job;
	for (int y = wk->row_begin; y < wk->row_end; y++) {
		struct cpx *row = job->field + (size_t)y * job->width;
		memcpy(wk->line, row, (size_t)job->width * sizeof *row);
		fft_run(job->row_plan, row, wk->line, &wk->row_work);
	}
	return NULL;
}

static void *transform_columns(void *arg)
{
	struct spectrum_worker *wk = arg;
	const struct spectrum_job *job = wk->job;
	const int w = job->width, h = job->height;
	double energy[AA_FOURIER_BANDS] = { 0 };
	for (int x0 = wk->col_begin; x0 < wk->col_end; x0 += GATHER) {
		int cols = wk->col_end - x0 < GATHER ? wk->col_end - x0 : GATHER;
		for (int y = 0; y < h; y++)
			for (int c = 0; c < cols; c++)
				wk->gathered[(size_t)c * h + y] = job->field[(size_t)y * w + x0 + c];
		for (int c = 0; c < cols; c++) {
			fft_run(job->col_plan, wk->line, wk->gathered + (size_t)c * h, &wk->col_work);
			const double fx2 = job->fx2[x0 + c];
			/* Each band's sum in a register: a bin adds its power to its band and +0.0 to the other
			 * two, which leaves a sum of non-negative values unchanged, so every band adds the same
			 * values in the same order as a sum indexed by band would, without its round trip
			 * through memory for every bin. */
			double low = energy[AA_FOURIER_LOW], mid = energy[AA_FOURIER_MID], high = energy[AA_FOURIER_HIGH];
			for (int ky = 0; ky < h; ky++) {
				struct cpx v = wk->line[ky];
				const double power = v.re * v.re + v.im * v.im;
				const int band = band_of_f2(fx2 + job->fy2[ky]);
				low += band == AA_FOURIER_LOW ? power : 0.0;
				mid += band == AA_FOURIER_MID ? power : 0.0;
				high += band == AA_FOURIER_HIGH ? power : 0.0;
			}
			energy[AA_FOURIER_LOW] = low;
			energy[AA_FOURIER_MID] = mid;
			energy[AA_FOURIER_HIGH] = high;
		}
	}
	for (int b = 0; b < AA_FOURIER_BANDS; b++)
		wk->energy[b] += energy[b];
	return NULL;
}

static int thread_count(int requested, long pixels, int lines)
{
	long n = requested;
	if (n <= 0) {
		long cpus = sysconf(_SC_NPROCESSORS_ONLN), by_size = pixels / MIN_PIXELS_PER_THREAD;
		n = cpus < by_size ? cpus : by_size;
	}
	n = n > MAX_THREADS ? MAX_THREADS : n;
	n = n > lines ? lines : n;
	return n < 1 ? 1 : (int)n;
}

/* Runs fn on every worker, worker 0 on this thread (and any whose thread cannot start). */
static void run_workers(struct spectrum_worker *workers, int count, void *(*fn)(void *))
{
	pthread_t tids[MAX_THREADS];
	bool started[MAX_THREADS] = { false };
	for (int t = 1; t < count; t++)
		started[t] = pthread_create(&tids[t], NULL, fn, &workers[t]) == 0;
	fn(&workers[0]);
	for (int t = 1; t < count; t++) {
		if (started[t])
			pthread_join(tids[t], NULL);
		else
			fn(&workers[t]);
	}
}

/* Writes complex field `pair` (0, 1, ...: z = field 2 pair + i field 2 pair + 1) of `pixels` values. */
typedef void (*field_fill)(const void *source, int pair, struct cpx *field, size_t pixels);

/* The band energies of `count` real fields given by fill, two per complex transform. */
static int band_energy(field_fill fill, const void *source, int count, int width, int height, int threads,
		       double energy[AA_FOURIER_BANDS], struct aa_error *err)
{
	for (int b = 0; b < AA_FOURIER_BANDS; b++)
		energy[b] = 0.0;
	if (width <= 0 || height <= 0 || count < 0)
		return aa_error_set(err, AA_ERR_INVALID, "", "cannot transform an empty %dx%d image", width, height);
	const size_t pixels = (size_t)width * height;
	const int nthreads = thread_count(threads, (long)pixels, width < height ? width : height);
	struct spectrum_job job = { .width = width, .height = height };
	struct spectrum_worker workers[MAX_THREADS];
	memset(workers, 0, sizeof workers);
	job.field = malloc(pixels * sizeof *job.field);
	double *fx2 = malloc((size_t)width * sizeof *fx2), *fy2 = malloc((size_t)height * sizeof *fy2);
	job.row_plan = plan_create(width);
	job.col_plan = plan_create(height);
	bool ok = job.field && fx2 && fy2 && job.row_plan && job.col_plan;
	const int longest = width > height ? width : height;
	for (int t = 0; ok && t < nthreads; t++) {
		struct spectrum_worker *wk = &workers[t];
		wk->job = &job;
		wk->row_begin = (int)((long)height * t / nthreads);
		wk->row_end = (int)((long)height * (t + 1) / nthreads);
		/* Column ranges start on a multiple of GATHER so gathers read whole cache lines. */
		int blocks = (width + GATHER - 1) / GATHER;
		wk->col_begin = (int)((long)blocks * t / nthreads) * GATHER;
		wk->col_end = (int)((long)blocks * (t + 1) / nthreads) * GATHER;
		wk->col_end = wk->col_end > width ? width : wk->col_end;
		wk->line = malloc((size_t)longest * sizeof *wk->line);
		wk->gathered = malloc((size_t)GATHER * height * sizeof *wk->gathered);
		ok = wk->line && wk->gathered && work_alloc(job.row_plan, &wk->row_work) == 0 &&
		     work_alloc(job.col_plan, &wk->col_work) == 0;
	}
	if (ok) {
		for (int x = 0; x < width; x++)
			fx2[x] = axis_frequency(x, width) * axis_frequency(x, width);
		for (int y = 0; y < height; y++)
			fy2[y] = axis_frequency(y, height) * axis_frequency(y, height);
		job.fx2 = fx2;
		job.fy2 = fy2;
		/* Two real fields per complex transform: z = f[i] + i f[i+1]. */
		for (int i = 0; i < count; i += 2) {
			fill(source, i / 2, job.field, pixels);
			run_workers(workers, nthreads, transform_rows);
			run_workers(workers, nthreads, transform_columns);
		}
		for (int t = 0; t < nthreads; t++)
			for (int b = 0; b < AA_FOURIER_BANDS; b++)
				energy[b] += workers[t].energy[b];
		for (int b = 0; b < AA_FOURIER_BANDS; b++)
			energy[b] /= (double)pixels;
	}
	for (int t = 0; t < nthreads; t++) {
		free(workers[t].line);
		free(workers[t].gathered);
		work_free(&workers[t].row_work);
		work_free(&workers[t].col_work);
	}
	plan_free((struct fft_plan *)job.row_plan);
	plan_free((struct fft_plan *)job.col_plan);
	free(job.field);
	free(fx2);
	free(fy2);
	if (!ok)
		return aa_error_set(err, AA_ERR_LIMIT, "", "out of memory for the spectrum of a %dx%d image", width,
				    height);
	return 0;
}

struct given_fields {
	const double *const *fields;
	int count;
};

static void fill_from_fields(const void *source, int pair, struct cpx *field, size_t pixels)
{
	const struct given_fields *g = source;
	const double *re = g->fields[2 * pair], *im = 2 * pair + 1 < g->count ? g->fields[2 * pair + 1] : NULL;
	for (size_t p = 0; p < pixels; p++)
		field[p] = (struct cpx){ re[p], im ? im[p] : 0.0 };
}

int aa_fourier_band_energy(const double *const *fields, int count, int width, int height, int threads,
			   double energy[AA_FOURIER_BANDS], struct aa_error *err)
{
	const struct given_fields g = { fields, count };
	return band_energy(fill_from_fields, &g, count, width, height, threads, energy, err);
}

/* The error image test - ref of two 8-bit images, written straight into the transform's field (R + i G,
 * then B + i 0): the same doubles as three error planes copied in, without the planes. */
struct image_pair {
	const struct aa_image_rgba8 *ref, *test;
};

static void fill_from_difference(const void *source, int pair, struct cpx *field, size_t pixels)
{
	const struct image_pair *ip = source;
	const uint8_t *r = ip->ref->pixels, *t = ip->test->pixels;
	if (pair == 0) {
		for (size_t p = 0; p < pixels; p++)
			field[p] = (struct cpx){ (double)t[4 * p] - (double)r[4 * p],
						 (double)t[4 * p + 1] - (double)r[4 * p + 1] };
		return;
	}
	for (size_t p = 0; p < pixels; p++)
		field[p] = (struct cpx){ (double)t[4 * p + 2] - (double)r[4 * p + 2], 0.0 };
}

int aa_fourier_bands_rgba8(const struct aa_image_rgba8 *ref, const struct aa_image_rgba8 *test,
			   double band_mse[AA_FOURIER_BANDS], struct aa_error *err)
{
	for (int b = 0; b < AA_FOURIER_BANDS; b++)
		band_mse[b] = NAN;
	if (ref->width != test->width || ref->height != test->height)
		return aa_error_set(err, AA_ERR_INVALID, "", "cannot compare a %dx%d image against a %dx%d reference",
				    test->width, test->height, ref->width, ref->height);
	if (!ref->pixels || !test->pixels || ref->width <= 0 || ref->height <= 0)
		return aa_error_set(err, AA_ERR_INVALID, "", "cannot compare empty images");
	const size_t n = (size_t)ref->width * ref->height;
	const struct image_pair ip = { ref, test };
	double energy[AA_FOURIER_BANDS];
	if (band_energy(fill_from_difference, &ip, 3, ref->width, ref->height, 0, energy, err) != 0)
		return -1;
	for (int b = 0; b < AA_FOURIER_BANDS; b++)
		band_mse[b] = energy[b] / (3.0 * (double)n);
	return 0;
}
