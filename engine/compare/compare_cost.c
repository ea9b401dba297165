/* The cost side of comparing two runs (docs/compare.md, "How a cost change counts"): each method's p10
 * over its timed renders, the case's machine factor, and a seeded bootstrap interval of the judged
 * change. Quality needs none of this: it is deterministic and compared exactly (compare.c). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "compare/compare_cost.h"

/* A small, seeded generator (xorshift64*): the same two runs always give the same interval. */
static uint64_t next_random(uint64_t *state)
{
	uint64_t x = *state;
	x ^= x >> 12;
	x ^= x << 25;
	x ^= x >> 27;
	*state = x;
	return x * 0x2545F4914F6CDD1DULL;
}

uint64_t aa_compare_seed(const char *a, const char *b, const char *c)
{
	uint64_t h = 0xcbf29ce484222325ULL; /* FNV-1a */
	const char *parts[3] = {a, b, c};
	for (int i = 0; i < 3; i++) {
		for (const char *p = parts[i]; p && *p; p++) {
			h ^= (unsigned char)*p;
			h *= 0x100000001b3ULL;
		}
		h ^= 0xff;
		h *= 0x100000001b3ULL;
	}
	return h ? h : 1;
}

/* The k-th smallest of v[0..n) (v is reordered): Hoare's selection, expected linear time. */
static double select_kth(double *v, int n, int k)
{
	int lo = 0, hi = n - 1;
	while (lo < hi) {
		double pivot = v[lo + (hi - lo) / 2];
		int i = lo, j = hi;
		while (i <= j) {
			while (v[i] < pivot)
				i++;
			while (v[j] > pivot)
				j--;
			if (i <= j) {
				double t = v[i];
				v[i] = v[j];
				v[j] = t;
				i++;
				j--;
			}
		}
		if (k <= j)
			hi = j;
		else if (k >= i)
			lo = i;
		else
			return v[k];
	}
	return v[k];
}

/* The p-th percentile with linear interpolation between ranked values, as aa_percentile (v reordered). */
static double quantile(double *v, int n, double p)
{
	if (n <= 0)
		return NAN;
	double rank = p / 100.0 * (n - 1);
	int lo = (int)floor(rank);
	double a = select_kth(v, n, lo);
	if (lo + 1 >= n || rank == lo)
		return a;
	double b = v[lo + 1]; /* after selection everything right of lo is >= a: its minimum is next */
	for (int i = lo + 2; i < n; i++)
		if (v[i] < b)
			b = v[i];
	return a + (b - a) * (rank - lo);
}


static double percentile_copy(const double *v, int n, double p, double *scratch)
{
	memcpy(scratch, v, (size_t)n * sizeof *v);
	return quantile(scratch, n, p);
}

static double median_of(double *v, int n)
{
	return quantile(v, n, 50);
}


/* The cost changes of every paired method of a case, judged together (docs/compare.md, "How a cost
 * change counts"): each method's p10 over its timed renders; the case's machine factor, the median over
 * methods of the ratio NEW/BASE of their p10s (how much faster or slower the machine ran this case: the
 * methods of a frame render back to back, so load slows them alike); each method's judged change, its
 * ratio divided by the factor; and a bootstrap interval of it, each run's renders resampled with
 * replacement, the factor recomputed in every resample. raw skips the factor (a dedicated machine). */
int aa_compare_case_costs(const struct cost_input *in, int count, bool raw, uint64_t seed, struct cost_change *out,
		      double *factor, double factor_interval[2], struct aa_error *err)
{
	int most = 1, eligible = 0;
	for (int m = 0; m < count; m++) {
		most = in[m].nb > most ? in[m].nb : most;
		most = in[m].nn > most ? in[m].nn : most;
	}
	double *scratch = malloc((size_t)(most + count) * sizeof *scratch);
	if (!scratch)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	double *ratios = scratch + most;
	for (int m = 0; m < count; m++) {
		struct cost_change *c = &out[m];
		*c = (struct cost_change){NAN, NAN, NAN, NAN, NAN, NAN, in[m].nb, in[m].nn, NAN, NAN, NAN, 1.0, NAN, NAN,
					  {NAN, NAN}, {NAN, NAN}, false};
		if (in[m].nb > 0) {
			c->base_median = percentile_copy(in[m].b, in[m].nb, 50, scratch);
			c->base_p10 = percentile_copy(in[m].b, in[m].nb, COST_QUANTILE, scratch);
			c->base_p90 = percentile_copy(in[m].b, in[m].nb, 90, scratch);
		}
		if (in[m].nn > 0) {
			c->new_median = percentile_copy(in[m].n, in[m].nn, 50, scratch);
			c->new_p10 = percentile_copy(in[m].n, in[m].nn, COST_QUANTILE, scratch);
			c->new_p90 = percentile_copy(in[m].n, in[m].nn, 90, scratch);
		}
		c->change = c->new_p10 - c->base_p10;
		c->change_pct = c->base_p10 > 0 ? 100.0 * c->change / c->base_p10 : NAN;
		c->change_median_pct = c->base_median > 0 ? 100.0 * (c->new_median / c->base_median - 1) : NAN;
		c->eligible = in[m].nb >= MIN_TIMED_RENDERS && in[m].nn >= MIN_TIMED_RENDERS && c->base_p10 > 0 &&
			      isfinite(c->new_p10);
		if (c->eligible)
			ratios[eligible++] = c->new_p10 / c->base_p10;
	}
	/* the factor needs a few methods to be told apart from any one method's own change */
	bool corrected = !raw && eligible >= 3;
	*factor = corrected ? median_of(ratios, eligible) : 1.0;
	factor_interval[0] = factor_interval[1] = corrected ? NAN : 1.0;
	for (int m = 0; m < count; m++) {
		out[m].factor = *factor;
		out[m].judged = out[m].new_p10 / *factor - out[m].base_p10;
		out[m].judged_pct = out[m].base_p10 > 0 ? 100.0 * out[m].judged / out[m].base_p10 : NAN;
	}
	if (eligible == 0) {
		free(scratch);
		return 0;
	}
	/* fewer resamples for very long runs: the interval of a p10 over thousands of renders is narrow */
	long work = 0;
	for (int m = 0; m < count; m++)
		work += in[m].nb + in[m].nn;
	int resamples = RESAMPLES;
	if (work * RESAMPLES > 20000000L)
		resamples = 20000000L / work > 200 ? (int)(20000000L / work) : 200;
	double *sample_ratio = malloc((size_t)resamples * (size_t)(2 * count + 1) * sizeof *sample_ratio);
	if (!sample_ratio) {
		free(scratch);
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	}
	double *sample_ms = sample_ratio + (size_t)resamples * count, *sample_factor = sample_ms + (size_t)resamples * count;
	uint64_t state = seed;
	double *qb = malloc((size_t)count * 2 * sizeof *qb);
	if (!qb) {
		free(sample_ratio);
		free(scratch);
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	}
	double *qn = qb + count;
	for (int r = 0; r < resamples; r++) {
		int k = 0;
		for (int m = 0; m < count; m++) {
			if (!out[m].eligible)
				continue;
			for (int i = 0; i < in[m].nb; i++)
				scratch[i] = in[m].b[next_random(&state) % (uint64_t)in[m].nb];
			qb[m] = quantile(scratch, in[m].nb, COST_QUANTILE);
			for (int i = 0; i < in[m].nn; i++)
				scratch[i] = in[m].n[next_random(&state) % (uint64_t)in[m].nn];
			qn[m] = quantile(scratch, in[m].nn, COST_QUANTILE);
			ratios[k++] = qb[m] > 0 ? qn[m] / qb[m] : NAN;
		}
		double f = corrected ? median_of(ratios, k) : 1.0;
		sample_factor[r] = f;
		for (int m = 0; m < count; m++) {
			sample_ratio[(size_t)m * resamples + r] = out[m].eligible ? 100.0 * (qn[m] / f / qb[m] - 1) : NAN;
			sample_ms[(size_t)m * resamples + r] = out[m].eligible ? qn[m] / f - qb[m] : NAN;
		}
	}
	const double tail = 100.0 * (1 - INTERVAL_LEVEL) / 2;
	for (int m = 0; m < count; m++) {
		if (!out[m].eligible)
			continue;
		double *ratio = sample_ratio + (size_t)m * resamples, *ms = sample_ms + (size_t)m * resamples;
		out[m].interval_pct[0] = quantile(ratio, resamples, tail);
		out[m].interval_pct[1] = quantile(ratio, resamples, 100 - tail);
		out[m].interval[0] = quantile(ms, resamples, tail);
		out[m].interval[1] = quantile(ms, resamples, 100 - tail);
	}
	if (corrected) {
		factor_interval[0] = quantile(sample_factor, resamples, tail);
		factor_interval[1] = quantile(sample_factor, resamples, 100 - tail);
	}
	free(qb);
	free(sample_ratio);
	free(scratch);
	return 0;
}
