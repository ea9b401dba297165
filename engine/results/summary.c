/* Per-method summaries over frames (medians, percentiles, sequence PSNR) and freeing job results. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "results.h"

static int compare_doubles(const void *a, const void *b)
{
	const double x = *(const double *)a, y = *(const double *)b;
	return (x > y) - (x < y);
}

/* Non-finite values are skipped: they carry no timing or quality, and NaN would break the sort order. */
double aa_percentile(const double *values, int n, double p)
{
	if (!values || n <= 0)
		return NAN;
	double *sorted = malloc((size_t)n * sizeof *sorted);
	if (!sorted)
		return NAN;
	int count = 0;
	for (int i = 0; i < n; i++)
		if (isfinite(values[i]))
			sorted[count++] = values[i];
	double result = NAN;
	if (count > 0) {
		qsort(sorted, (size_t)count, sizeof *sorted, compare_doubles);
		if (!(p >= 0))
			p = 0; /* also catches NaN */
		if (p > 100)
			p = 100;
		const double rank = p / 100.0 * (count - 1);
		const int lo = (int)floor(rank), hi = lo + 1 < count ? lo + 1 : lo;
		result = sorted[lo] + (sorted[hi] - sorted[lo]) * (rank - lo);
	}
	free(sorted);
	return result;
}

/* Mean of the finite values, NAN when there are none. */
static double finite_mean(const double *values, int n)
{
	double sum = 0;
	int count = 0;
	for (int i = 0; i < n; i++)
		if (isfinite(values[i])) {
			sum += values[i];
			count++;
		}
	return count ? sum / count : NAN;
}

/* Orders frames by quality: identical beats any PSNR; a frame without a usable PSNR ranks last. */
static double psnr_rank(const struct aa_frame_result *f)
{
	if (f->metrics.identical || f->metrics.mse == 0)
		return INFINITY;
	if (isfinite(f->metrics.psnr))
		return f->metrics.psnr;
	const double from_mse = aa_psnr_from_mse(f->metrics.mse, 255.0);
	return isfinite(from_mse) ? from_mse : -INFINITY;
}

void aa_method_summarize(const struct aa_method_result *m, struct aa_method_summary *out)
{
	*out = (struct aa_method_summary){
		.gpu_ms_median = NAN, .gpu_ms_p90 = NAN, .gpu_ms_mean = NAN, .cpu_ms_median = NAN,
		.mse_mean = NAN, .psnr_mean = NAN, .ssim_mean = NAN, .flicker_mean = NAN,
		.best_frame = -1, .worst_frame = -1, .best_psnr = NAN, .worst_psnr = NAN,
	};
	const int n = m->frames ? m->frame_count : 0;
	if (n <= 0)
		return;
	double *v = malloc((size_t)n * 5 * sizeof *v);
	if (!v)
		return;
	double *gpu = v, *cpu = v + n, *mse = v + 2 * n, *ssim = v + 3 * n, *flicker = v + 4 * n;
	for (int i = 0; i < n; i++) {
		gpu[i] = m->frames[i].gpu_ms;
		cpu[i] = m->frames[i].cpu_ms;
		mse[i] = m->frames[i].metrics.identical ? 0.0 : m->frames[i].metrics.mse;
		ssim[i] = m->frames[i].metrics.ssim;
		flicker[i] = m->frames[i].flicker;
	}
	out->gpu_ms_median = aa_percentile(gpu, n, 50);
	out->gpu_ms_p90 = aa_percentile(gpu, n, 90);
	out->gpu_ms_mean = finite_mean(gpu, n);
	out->cpu_ms_median = aa_percentile(cpu, n, 50);
	out->mse_mean = finite_mean(mse, n);
	out->ssim_mean = finite_mean(ssim, n);
	out->flicker_mean = finite_mean(flicker, n); /* frame 0 has none (NAN) */
	/* PSNR of the mean MSE, not the mean of PSNRs: one identical frame would make the latter infinite,
	 * and dB do not average meaningfully. */
	out->psnr_identical = out->mse_mean == 0;
	out->psnr_mean = out->psnr_identical || !isfinite(out->mse_mean) ? NAN
									  : aa_psnr_from_mse(out->mse_mean, 255.0);
	free(v);

	double best = 0, worst = 0;
	for (int i = 0; i < n; i++) {
		const double r = psnr_rank(&m->frames[i]);
		if (out->best_frame < 0 || r > best) {
			best = r;
			out->best_frame = m->frames[i].frame;
		}
		if (out->worst_frame < 0 || r < worst) {
			worst = r;
			out->worst_frame = m->frames[i].frame;
		}
	}
	out->best_psnr = isfinite(best) ? best : NAN;
	out->worst_psnr = isfinite(worst) ? worst : NAN;
}

void aa_job_result_free(struct aa_job_result *r)
{
	if (!r)
		return;
	for (int i = 0; i < r->method_count && i < AA_MAX_METHODS; i++) {
		free(r->methods[i].frames);
		r->methods[i].frames = NULL;
		r->methods[i].frame_count = 0;
	}
	free(r->reference.frames);
	r->reference.frames = NULL;
	r->reference.frame_count = 0;
}
