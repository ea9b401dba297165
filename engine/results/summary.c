/* Per-method summaries over frames (medians, percentiles, sequence PSNR) and freeing job results. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "results/results.h"

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

void aa_timing_stats_of(const double *values, int n, struct aa_timing_stats *out)
{
	*out = (struct aa_timing_stats){NAN, NAN, NAN, NAN, NAN, 0};
	for (int i = 0; values && i < n; i++)
		if (isfinite(values[i])) {
			out->n++;
			if (!(values[i] >= out->min))
				out->min = values[i];
		}
	if (out->n == 0)
		return;
	out->median = aa_percentile(values, n, 50);
	out->p10 = aa_percentile(values, n, 10);
	out->p90 = aa_percentile(values, n, 90);
	out->mean = finite_mean(values, n);
}

/* Times of every timed render, or of the scored frames for results without any (older files). */
static int collect_times(const struct aa_method_result *m, bool gpu, double *out)
{
	int n = 0;
	if (m->timed && m->timed_count > 0) {
		for (int i = 0; i < m->timed_count; i++)
			out[n++] = gpu ? m->timed[i].gpu_ms : m->timed[i].cpu_ms;
	} else {
		for (int i = 0; m->frames && i < m->frame_count; i++)
			out[n++] = gpu ? m->frames[i].gpu_ms : m->frames[i].cpu_ms;
	}
	return n;
}

void aa_pass_timing_stats(const struct aa_method_result *m, const char *name, struct aa_timing_stats *out)
{
	int cap = m->timed_count > m->frame_count ? m->timed_count : m->frame_count;
	double *v = malloc((size_t)(cap > 0 ? cap : 1) * sizeof *v);
	int n = 0;
	for (int i = 0; v && m->timed && i < m->timed_count; i++) {
		const struct aa_timed_render *t = &m->timed[i];
		if (t->ordinal < 0 || t->ordinal >= m->frame_count)
			continue;
		const struct aa_frame_result *f = &m->frames[t->ordinal];
		for (int k = 0; k < t->pass_count && k < f->pass_count && k < AA_MAX_PASSES; k++)
			if (strcmp(f->passes[k].name, name) == 0) {
				v[n++] = t->pass_ms[k];
				break; /* once per render */
			}
	}
	for (int i = 0; v && (!m->timed || m->timed_count == 0) && m->frames && i < m->frame_count; i++)
		for (int k = 0; k < m->frames[i].pass_count && k < AA_MAX_PASSES; k++)
			if (strcmp(m->frames[i].passes[k].name, name) == 0) {
				v[n++] = m->frames[i].passes[k].gpu_ms;
				break;
			}
	aa_timing_stats_of(v, n, out);
	free(v);
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
		.mse_mean = NAN, .psnr_mean = NAN, .ssim_mean = NAN, .flip_mean = NAN, .flicker_mean = NAN, .over_threshold_mean = NAN,
		.best_frame = -1, .worst_frame = -1, .best_psnr = NAN, .worst_psnr = NAN,
	};
	aa_timing_stats_of(NULL, 0, &out->gpu_ms);
	aa_timing_stats_of(NULL, 0, &out->cpu_ms);
	const int n = m->frames ? m->frame_count : 0;
	if (n <= 0)
		return;
	const int timed = m->timed && m->timed_count > n ? m->timed_count : n;
	double *v = malloc((size_t)(5 * n + 2 * timed) * sizeof *v);
	if (!v)
		return;
	double *mse = v, *ssim = v + n, *flicker = v + 2 * n, *over = v + 3 * n, *flip = v + 4 * n;
	double *gpu = v + 5 * n, *cpu = gpu + timed;
	for (int i = 0; i < n; i++) {
		mse[i] = m->frames[i].metrics.identical ? 0.0 : m->frames[i].metrics.mse;
		ssim[i] = m->frames[i].metrics.ssim;
		flip[i] = m->frames[i].metrics.flip_mean;
		flicker[i] = m->frames[i].flicker;
		over[i] = m->frames[i].over_threshold >= 0 ? (double)m->frames[i].over_threshold : NAN;
	}
	aa_timing_stats_of(gpu, collect_times(m, true, gpu), &out->gpu_ms);
	aa_timing_stats_of(cpu, collect_times(m, false, cpu), &out->cpu_ms);
	out->gpu_ms_median = out->gpu_ms.median;
	out->gpu_ms_p90 = out->gpu_ms.p90;
	out->gpu_ms_mean = out->gpu_ms.mean;
	out->cpu_ms_median = out->cpu_ms.median;
	out->mse_mean = finite_mean(mse, n);
	out->ssim_mean = finite_mean(ssim, n);
	out->flip_mean = finite_mean(flip, n);
	out->flicker_mean = finite_mean(flicker, n); /* frame 0 has none (NAN) */
	out->over_threshold_mean = finite_mean(over, n);
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

double aa_reference_convergence_psnr(const struct aa_reference_result *ref, bool *identical)
{
	double sum = 0;
	int n = 0;
	for (int i = 0; ref->frames && i < ref->frame_count; i++) {
		const double mse = ref->frames[i].convergence_identical ? 0.0 : ref->frames[i].convergence_mse;
		if (isfinite(mse)) {
			sum += mse;
			n++;
		}
	}
	*identical = n > 0 && sum == 0;
	return n && sum > 0 ? aa_psnr_from_mse(sum / n, 255.0) : NAN;
}
