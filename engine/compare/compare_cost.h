/* Inside engine/results: the cost statistic of a comparison (compare_cost.c), used by compare.c. */
#ifndef AA_COMPARE_COST_H
#define AA_COMPARE_COST_H

#include <stdbool.h>
#include <stdint.h>

#include "util/error.h"

/* The cost statistic and its interval (docs/compare.md, "How a cost change counts"). */
#define COST_QUANTILE 10.0         /* p10: on a shared machine other work only adds time */
#define INTERVAL_LEVEL 0.90
#define MIN_TIMED_RENDERS 5
#define RESAMPLES 2000

/* One timed-render list per paired method of a case (gpu_ms or cpu_ms), in the order of the NEW run. */
struct cost_input {
	const double *b, *n;
	int nb, nn;
};


/* One method's cost change: as measured, judged against the case's machine factor, and its interval. */
struct cost_change {
	double base_median, base_p10, base_p90, new_median, new_p10, new_p90;
	int base_n, new_n;
	double change, change_pct;         /* the p10 as measured: new - base (ms), relative in percent */
	double change_median_pct;          /* the median as measured, relative */
	double factor;                     /* the case's machine factor the judged change is divided by */
	double judged, judged_pct;         /* the change judged by the gates: new / factor - base */
	double interval[2], interval_pct[2]; /* their bootstrap interval; NAN when not estimable */
	bool eligible;                     /* enough timed renders on both sides */
};


/* A seed from three strings (FNV-1a): the same two runs always resample alike. */
uint64_t aa_compare_seed(const char *a, const char *b, const char *c);
/* The cost changes of a case's paired methods (compare_cost.c says how); -1 with err when out of memory. */
int aa_compare_case_costs(const struct cost_input *in, int count, bool raw, uint64_t seed, struct cost_change *out,
			  double *factor, double factor_interval[2], struct aa_error *err);

#endif
