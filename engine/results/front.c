/* The cost-quality front (docs/results-format.md, "verdict"). Quality is deterministic (the same build
 * renders the same images), so PSNR and FLIP compare exactly; cost is noisy, so one cost is lower than
 * another only when their p10-p90 spreads are apart, and costs whose spreads overlap are the same. An
 * entry with too few timed renders is not ranked at all: one render says nothing about its spread. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "results/front.h"

enum aa_cost_order aa_cost_order(const struct aa_timing_stats *a, const struct aa_timing_stats *b)
{
	if (a->n < AA_FRONT_MIN_TIMED_RENDERS || b->n < AA_FRONT_MIN_TIMED_RENDERS || !isfinite(a->p10) ||
	    !isfinite(a->p90) || !isfinite(b->p10) || !isfinite(b->p90))
		return AA_COST_UNKNOWN;
	if (a->p90 < b->p10)
		return AA_COST_LOWER;
	if (b->p90 < a->p10)
		return AA_COST_HIGHER;
	return AA_COST_SAME;
}

static bool ranked(const struct aa_front_entry *e)
{
	return e->cost.n >= AA_FRONT_MIN_TIMED_RENDERS && isfinite(e->cost.p10) && isfinite(e->cost.p90) &&
	       isfinite(e->cost.median);
}

/* A missing PSNR ranks below any; a missing FLIP (on either side) decides nothing. */
static double psnr_of(const struct aa_front_entry *e)
{
	return isnan(e->psnr) ? -INFINITY : e->psnr;
}

/* a beats b: at most b's cost, at least its PSNR and at most its FLIP, and better in one of them. */
static bool beats(const struct aa_front_entry *a, const struct aa_front_entry *b, enum aa_cost_order *cost)
{
	*cost = aa_cost_order(&a->cost, &b->cost);
	if (*cost != AA_COST_LOWER && *cost != AA_COST_SAME)
		return false;
	const double pa = psnr_of(a), pb = psnr_of(b);
	const bool flips = isfinite(a->flip) && isfinite(b->flip);
	if (pa < pb || (flips && a->flip > b->flip))
		return false;
	return *cost == AA_COST_LOWER || pa > pb || (flips && a->flip < b->flip);
}

int aa_front_compute(const struct aa_front_entry *e, int n, struct aa_front_place *place)
{
	int count = 0;
	for (int i = 0; i < n; i++) {
		place[i] = (struct aa_front_place){.kind = ranked(&e[i]) ? AA_PLACE_FRONT : AA_PLACE_NOT_RANKED,
						   .beaten_by = -1, .beater_cost = AA_COST_UNKNOWN};
		count += place[i].kind == AA_PLACE_FRONT;
	}
	for (int i = 0; i < n; i++)
		for (int j = 0; j < n && place[i].kind != AA_PLACE_NOT_RANKED; j++) {
			enum aa_cost_order cost;
			if (j != i && place[j].kind != AA_PLACE_NOT_RANKED && beats(&e[j], &e[i], &cost))
				place[i].kind = AA_PLACE_DOMINATED;
		}
	/* what beats a beaten entry: one on the front if any does (the cheapest), else the cheapest of all */
	for (int i = 0; i < n; i++) {
		if (place[i].kind != AA_PLACE_DOMINATED)
			continue;
		int best = -1;
		bool best_front = false;
		enum aa_cost_order best_cost = AA_COST_UNKNOWN;
		for (int j = 0; j < n; j++) {
			enum aa_cost_order cost;
			if (j == i || place[j].kind == AA_PLACE_NOT_RANKED || !beats(&e[j], &e[i], &cost))
				continue;
			const bool front = place[j].kind == AA_PLACE_FRONT;
			if (best < 0 || (front && !best_front) ||
			    (front == best_front && e[j].cost.median < e[best].cost.median)) {
				best = j;
				best_front = front;
				best_cost = cost;
			}
		}
		place[i].beaten_by = best;
		place[i].beater_cost = best_cost;
	}
	return count;
}

/* ------------------------------------------------------------------------------------------ text */

static json_t *num(double v)
{
	return isfinite(v) ? json_real(v) : json_null();
}

/* A difference as the tables print it: two decimals, more when it would read 0.00. */
static void amount(double v, int decimals, char *out, size_t size)
{
	if (v != 0 && fabs(v) < 0.5 * pow(10, -decimals))
		snprintf(out, size, "%.2g", v);
	else
		snprintf(out, size, "%.*f", decimals, v);
}

/* "taa: 2.38 dB less PSNR and 0.0100 more FLIP than msaa:4, for 1.25x its time": what choosing m instead
 * of what beats it gives up, and at what cost. */
static void beaten_line(const struct aa_front_entry *m, const struct aa_front_entry *by, enum aa_cost_order cost,
			char *out, size_t size)
{
	char dp_text[32], df_text[32], quality[256], cost_text[96];
	const double dp = psnr_of(by) - psnr_of(m);
	const bool flips = isfinite(m->flip) && isfinite(by->flip);
	const double df = flips ? m->flip - by->flip : 0;
	amount(dp, 2, dp_text, sizeof dp_text);
	amount(df, 4, df_text, sizeof df_text);
	if (isinf(by->psnr) && by->psnr > 0 && !isinf(m->psnr))
		snprintf(quality, sizeof quality, "not identical to the reference where %s is%s%s%s", by->label,
			 df > 0 ? ", and " : "", df > 0 ? df_text : "", df > 0 ? " more FLIP" : "");
	else if (dp > 0 && df > 0)
		snprintf(quality, sizeof quality, "%s dB less PSNR and %s more FLIP than %s", dp_text, df_text, by->label);
	else if (dp > 0)
		snprintf(quality, sizeof quality, "%s dB less PSNR than %s%s", dp_text, by->label,
			 flips ? " (the same FLIP)" : "");
	else if (df > 0)
		snprintf(quality, sizeof quality, "%s more FLIP than %s (the same PSNR)", df_text, by->label);
	else
		snprintf(quality, sizeof quality, "the same PSNR%s as %s", flips ? " and FLIP" : "", by->label);
	if (cost == AA_COST_LOWER)
		snprintf(cost_text, sizeof cost_text, "for %.2fx its time", m->cost.median / by->cost.median);
	else
		snprintf(cost_text, sizeof cost_text, "at a cost the timings cannot tell apart (p10-p90 overlap)");
	snprintf(out, size, "%s: %s, %s", m->label, quality, cost_text);
}

/* "a, b and c" of the labels of the entries marked in pick; the count written. */
static int list_labels(const struct aa_front_entry *e, const bool *pick, int n, char *out, size_t size)
{
	int total = 0, done = 0;
	for (int i = 0; i < n; i++)
		total += pick[i];
	size_t used = 0;
	out[0] = '\0';
	for (int i = 0; i < n && used < size; i++) {
		if (!pick[i])
			continue;
		const char *sep = done == 0 ? "" : done == total - 1 ? " and " : ", ";
		used += (size_t)snprintf(out + used, size - used, "%s%s", sep, e[i].label);
		done++;
	}
	return total;
}

/* Whether i and j tie in cost in a way that matters: both ranked, their spreads overlap, and one of them
 * is on the front. */
static bool tie(const struct aa_front_entry *e, const struct aa_front_place *place, int i, int j)
{
	return i != j && place[i].kind != AA_PLACE_NOT_RANKED && place[j].kind != AA_PLACE_NOT_RANKED &&
	       (place[i].kind == AA_PLACE_FRONT || place[j].kind == AA_PLACE_FRONT) &&
	       aa_cost_order(&e[i].cost, &e[j].cost) == AA_COST_SAME;
}

/* The fewest and most timed renders among the entries not ranked. */
static void not_ranked_counts(const struct aa_front_entry *e, const struct aa_front_place *place, int n, int *lo,
			      int *hi)
{
	*lo = -1;
	*hi = -1;
	for (int i = 0; i < n; i++)
		if (place[i].kind == AA_PLACE_NOT_RANKED) {
			*lo = *lo < 0 || e[i].cost.n < *lo ? e[i].cost.n : *lo;
			*hi = e[i].cost.n > *hi ? e[i].cost.n : *hi;
		}
}

static void headline(const struct aa_front_entry *e, const struct aa_front_place *place, int n, int ranked_count,
		     char *out, size_t size)
{
	char list[1024], counts[48];
	bool pick[AA_FRONT_MAX] = {false};
	int lo, hi;
	not_ranked_counts(e, place, n, &lo, &hi);
	if (lo == hi)
		snprintf(counts, sizeof counts, "n=%d", lo);
	else
		snprintf(counts, sizeof counts, "n=%d-%d", lo, hi);
	if (ranked_count == 0) {
		snprintf(out, size, "not ranked: %s timed render%s per method, %d needed to rank costs", counts,
			 hi == 1 ? "" : "s", AA_FRONT_MIN_TIMED_RENDERS);
		return;
	}
	size_t used = 0;
	for (int i = 0; i < n; i++)
		pick[i] = place[i].kind == AA_PLACE_FRONT;
	list_labels(e, pick, n, list, sizeof list);
	used += (size_t)snprintf(out + used, size - used, "front: %s", list);
	/* each tie once, under the first of its two on the front: "ties in cost: smaa with none and fxaa" */
	bool any = false;
	for (int i = 0; i < n && used < size; i++) {
		if (place[i].kind != AA_PLACE_FRONT)
			continue;
		for (int j = 0; j < n; j++)
			pick[j] = tie(e, place, i, j) && !(place[j].kind == AA_PLACE_FRONT && j < i);
		if (list_labels(e, pick, n, list, sizeof list) == 0)
			continue;
		used += (size_t)snprintf(out + used, size - used, "%s%s with %s", any ? "; " : "; ties in cost: ",
					 e[i].label, list);
		any = true;
	}
	for (int i = 0; i < n; i++)
		pick[i] = place[i].kind == AA_PLACE_NOT_RANKED;
	if (used < size && list_labels(e, pick, n, list, sizeof list) > 0)
		snprintf(out + used, size - used, "; not ranked (%s): %s", counts, list);
}

/* ------------------------------------------------------------------------------------------ JSON */

static const char *place_name(enum aa_front_place_kind k)
{
	return k == AA_PLACE_FRONT ? "front" : k == AA_PLACE_DOMINATED ? "beaten" : "not ranked";
}

json_t *aa_front_json(const struct aa_front_entry *e, int n)
{
	if (n < 0 || n > AA_FRONT_MAX)
		return NULL;
	struct aa_front_place *place = calloc((size_t)(n > 0 ? n : 1), sizeof *place);
	json_t *v = json_object(), *over = json_array(), *front = json_array(), *ties = json_array(),
	       *methods = json_array(), *lines = json_array(), *not_ranked = json_array();
	if (!place || !v || !over || !front || !ties || !methods || !lines || !not_ranked) {
		free(place);
		json_decref(v);
		json_decref(over);
		json_decref(front);
		json_decref(ties);
		json_decref(methods);
		json_decref(lines);
		json_decref(not_ranked);
		return NULL;
	}
	const int ranked_count = aa_front_compute(e, n, place);
	char text[2048];
	for (int i = 0; i < n; i++) {
		json_array_append_new(over, json_string(e[i].label));
		if (place[i].kind == AA_PLACE_FRONT)
			json_array_append_new(front, json_string(e[i].label));
		if (place[i].kind == AA_PLACE_NOT_RANKED)
			json_array_append_new(not_ranked, json_string(e[i].label));
		for (int j = i + 1; j < n; j++)
			if (tie(e, place, i, j))
				json_array_append_new(ties, json_pack("[s, s]", e[i].label, e[j].label));
		const bool identical = isinf(e[i].psnr) && e[i].psnr > 0;
		json_t *m = json_pack("{s:s, s:s, s:{s:o, s:o, s:o, s:i}, s:o, s:b, s:o}", "label", e[i].label, "place",
				      place_name(place[i].kind), "gpu_ms", "median", num(e[i].cost.median), "p10",
				      num(e[i].cost.p10), "p90", num(e[i].cost.p90), "n", e[i].cost.n, "psnr",
				      num(e[i].psnr), "psnr_identical", identical, "flip", num(e[i].flip));
		const int b = place[i].beaten_by;
		if (m && place[i].kind == AA_PLACE_DOMINATED && b >= 0) {
			const struct aa_front_entry *by = &e[b];
			const double dp = psnr_of(by) - psnr_of(&e[i]);
			json_object_set_new(m, "beaten_by",
					    json_pack("{s:s, s:s, s:o, s:o, s:o}", "method", by->label, "cost",
						      place[i].beater_cost == AA_COST_LOWER ? "lower" : "same", "time_ratio",
						      num(e[i].cost.median / by->cost.median), "psnr_db", num(dp),
						      "flip", num(e[i].flip - by->flip)));
			beaten_line(&e[i], by, place[i].beater_cost, text, sizeof text);
			json_array_append_new(lines, json_string(text));
		}
		json_array_append_new(methods, m);
	}
	headline(e, place, n, ranked_count, text, sizeof text);
	json_object_set_new(v, "headline", json_string(text));
	json_object_set_new(v, "lines", lines);
	json_object_set_new(v, "over", over);
	json_object_set_new(v, "ranked", json_boolean(ranked_count == n && n > 0));
	json_object_set_new(v, "front", front);
	json_object_set_new(v, "ties", ties);
	json_object_set_new(v, "not_ranked", not_ranked);
	json_object_set_new(v, "methods", methods);
	json_object_set_new(v, "rule", json_pack("{s:s, s:s, s:[s, s], s:i}", "cost", "gpu_ms",
						 "cost_order", "lower only when the p10-p90 spreads are apart",
						 "quality", "psnr", "flip", "min_timed_renders", AA_FRONT_MIN_TIMED_RENDERS));
	free(place);
	return v;
}

/* ------------------------------------------------------------------------------------------ families */

/* The family of a label: the text before its ':' ("fxaa" of "fxaa:preset=20"), the method's name (a user
 * method's own name). */
static size_t family_length(const char *label)
{
	return strcspn(label, ":");
}

static bool same_family(const char *a, const char *b)
{
	const size_t n = family_length(a);
	return n == family_length(b) && !strncmp(a, b, n);
}

/* Ascending median GPU cost; a missing median last; equal medians in job order. */
static bool cheaper(const struct aa_front_entry *e, int a, int b)
{
	const double ma = e[a].cost.median, mb = e[b].cost.median;
	if (isnan(ma) != isnan(mb))
		return isnan(mb);
	if (isnan(ma))
		return a < b;
	return ma < mb || (ma == mb && a < b);
}

json_t *aa_front_families_json(const struct aa_front_entry *e, int n)
{
	if (n < 0 || n > AA_FRONT_MAX)
		return NULL;
	json_t *families = json_array();
	for (int first = 0; families && first < n; first++) {
		/* each family once, at its first member in job order */
		bool seen = false;
		for (int j = 0; j < first && !seen; j++)
			seen = same_family(e[j].label, e[first].label);
		if (seen)
			continue;
		struct aa_front_entry member[AA_FRONT_MAX];
		struct aa_front_place place[AA_FRONT_MAX];
		int order[AA_FRONT_MAX], count = 0;
		for (int j = first; j < n; j++)
			if (same_family(e[j].label, e[first].label))
				member[count++] = e[j];
		if (count < 2)
			continue;
		aa_front_compute(member, count, place);
		for (int k = 0; k < count; k++) { /* insertion sort by cost: a family is a handful */
			int at = k;
			while (at > 0 && cheaper(member, k, order[at - 1])) {
				order[at] = order[at - 1];
				at--;
			}
			order[at] = k;
		}
		json_t *methods = json_array(), *front = json_array();
		for (int k = 0; k < count; k++) {
			json_array_append_new(methods, json_string(member[order[k]].label));
			if (place[order[k]].kind == AA_PLACE_FRONT)
				json_array_append_new(front, json_string(member[order[k]].label));
		}
		char name[AA_LABEL_MAX];
		snprintf(name, sizeof name, "%.*s", (int)family_length(e[first].label), e[first].label);
		json_array_append_new(families, json_pack("{s:s, s:o, s:o}", "family", name, "methods", methods,
							  "front", front));
	}
	return families;
}

json_t *aa_verdict_json(const struct aa_job_result *r)
{
	struct aa_front_entry e[AA_MAX_METHODS];
	int n = 0;
	for (int i = 0; i < r->method_count && i < AA_MAX_METHODS; i++) {
		struct aa_method_summary s;
		aa_method_summarize(&r->methods[i], &s);
		e[n++] = (struct aa_front_entry){.label = r->methods[i].label, .cost = s.gpu_ms,
						 .psnr = s.psnr_identical ? INFINITY : s.psnr_mean, .flip = s.flip_mean};
	}
	json_t *v = aa_front_json(e, n), *families = v ? aa_front_families_json(e, n) : NULL;
	if (v && !families) {
		json_decref(v);
		return NULL;
	}
	if (v)
		json_object_set_new(v, "families", families);
	return v;
}
