/* The cost-quality front of a set of configurations (docs/results-format.md, "verdict"): which methods are
 * worth their cost, which tie, and what beats each of the others and by how much. Cost is the GPU time
 * over the timed renders (median, with its p10-p90 spread); quality is PSNR and FLIP. */
#ifndef AA_FRONT_H
#define AA_FRONT_H

#include <stdbool.h>

#include <jansson.h>

#include "results/results.h"

/* Fewer timed renders than this and a method's cost is not ranked ("n=1: not ranked"). */
#define AA_FRONT_MIN_TIMED_RENDERS AA_MIN_TIMED_RENDERS
/* The most entries aa_front_json takes: the methods of a job. */
#define AA_FRONT_MAX AA_MAX_METHODS

/* One configuration: a method of a case, or any other set a front is computed over. */
struct aa_front_entry {
	const char *label;
	struct aa_timing_stats cost; /* GPU ms over every timed render */
	double psnr;                 /* mean PSNR in dB, +INFINITY when identical to the reference, NAN when none */
	double flip;                 /* mean FLIP, NAN when none */
};

/* How one cost compares with another: their p10-p90 spreads apart (LOWER, HIGHER), overlapping (SAME),
 * or not comparable (too few timed renders, or a time missing). */
enum aa_cost_order { AA_COST_UNKNOWN, AA_COST_LOWER, AA_COST_SAME, AA_COST_HIGHER };

enum aa_front_place_kind { AA_PLACE_FRONT, AA_PLACE_DOMINATED, AA_PLACE_NOT_RANKED };

struct aa_front_place {
	enum aa_front_place_kind kind;
	int beaten_by;               /* DOMINATED: the entry that beats it (on the front, the cheapest such) */
	enum aa_cost_order beater_cost; /* DOMINATED: the beater's cost against this one's, LOWER or SAME */
};

/* The order of a's cost against b's (b cheaper: HIGHER). */
enum aa_cost_order aa_cost_order(const struct aa_timing_stats *a, const struct aa_timing_stats *b);

/* Places every entry: on the front (no other entry is at most as costly and at least as good in PSNR
 * and FLIP, and better in one of the three), beaten by another, or not ranked (its cost has fewer than
 * AA_FRONT_MIN_TIMED_RENDERS timed renders). Returns how many entries are ranked. */
int aa_front_compute(const struct aa_front_entry *e, int n, struct aa_front_place *place);

/* The front as results.json's verdict object (docs/results-format.md): the entries it was computed over,
 * the front, the ties in cost that touch it (pairs of ranked entries whose spreads overlap, one of them on
 * the front), each beaten entry with what beats it, and the headline and lines every output prints as
 * they are. At most AA_FRONT_MAX entries; NULL when out of memory or over. */
json_t *aa_front_json(const struct aa_front_entry *e, int n);

/* The front of each method family with at least 2 configurations among the entries, as the verdict's
 * "families" array (docs/results-format.md): one object per family, in the order of its first member,
 * {"family": "fxaa", "methods": [its labels, ascending median GPU cost], "front": [those of them nothing
 * of the family beats, by the rules of aa_front_compute, in the same order]}. A family is a label's text
 * before ':'. NULL when out of memory or over AA_FRONT_MAX entries. */
json_t *aa_front_families_json(const struct aa_front_entry *e, int n);

/* The verdict of one job (or case of a suite): the front over its methods, with "families". */
json_t *aa_verdict_json(const struct aa_job_result *r);

#endif
