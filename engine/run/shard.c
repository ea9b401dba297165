/* Splitting a job into shards of frames, with the warm-up its temporal methods need (docs/farm.md). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "run/job_spec.h"
#include "run/shard.h"

int aa_shard_parse(const char *text, int *index, int *count, struct aa_error *err)
{
	char *end;
	const char *usage = "expected I/N: shard I (0 to N-1) of N shards, e.g. 0/4";
	if (!text || !*text || !(*text >= '0' && *text <= '9'))
		return aa_error_set(err, AA_ERR_INVALID, "shard", "%s, got \"%s\"", usage, text ? text : "");
	long i = strtol(text, &end, 10);
	if (*end != '/' || !(end[1] >= '0' && end[1] <= '9'))
		return aa_error_set(err, AA_ERR_INVALID, "shard", "%s, got \"%s\"", usage, text);
	long n = strtol(end + 1, &end, 10);
	if (*end)
		return aa_error_set(err, AA_ERR_INVALID, "shard", "%s, got \"%s\"", usage, text);
	if (n < 1 || n > AA_MAX_SHARDS)
		return aa_error_set(err, n < 1 ? AA_ERR_INVALID : AA_ERR_LIMIT, "shard",
				    "%ld shards is out of range; valid range: 1 to %d", n, AA_MAX_SHARDS);
	if (i >= n)
		return aa_error_set(err, AA_ERR_INVALID, "shard", "shard %ld of %ld does not exist; valid: 0 to %ld",
				    i, n, n - 1);
	*index = (int)i;
	*count = (int)n;
	return 0;
}

void aa_shard_range(int frames, int index, int count, int *begin, int *end)
{
	const int base = frames / count, extra = frames % count;
	*begin = index * base + (index < extra ? index : extra);
	*end = *begin + base + (index < extra ? 1 : 0);
}

/* Measured on moving-sphere and thin-wires at 160x90 and 320x180 (docs/farm.md, "Warm-up"): the frames
 * after which a shard's frame equals the unsharded run's, or differs by less than the stated tolerance. */
int aa_method_shard_warmup(const struct aa_method_spec *ms)
{
	const struct aa_method *m = ms->method;
	unsigned needs = m->needs_fn ? m->needs_fn(&ms->params) : m->needs;
	if (!(needs & AA_NEED_HISTORY))
		return 0;
	if (!strcmp(m->name, "taa") || !strcmp(m->name, "taa-sobel"))
		return AA_TAA_SHARD_WARMUP;
	if (!strcmp(m->name, "t2msaa"))
		return AA_T2MSAA_SHARD_WARMUP;
	if (!strcmp(m->name, "asaa"))
		return AA_ASAA_SHARD_WARMUP;
	return AA_HISTORY_SHARD_WARMUP; /* a method with history not measured yet */
}

int aa_job_shard_warmup(const struct aa_job_spec *spec)
{
	if (spec->shard_warmup >= 0)
		return spec->shard_warmup;
	int w = 0;
	for (int i = 0; i < spec->method_count; i++) {
		int m = aa_method_shard_warmup(&spec->methods[i]);
		w = m > w ? m : w;
	}
	return w;
}

static double case_cost(const struct aa_case_spec *c)
{
	return (double)c->frames * c->width * c->height;
}

void aa_shard_cases(const struct aa_job_spec *suite, int index, int count, int *begin, int *end)
{
	const int n = suite->case_count;
	double total = 0;
	for (int i = 0; i < n; i++)
		total += case_cost(&suite->cases[i]);
	/* cut k (1..count-1) after the case whose running cost is nearest k/count of the total, leaving every
	 * shard at least one case */
	int cut_prev = 0;
	for (int k = 1; k <= index + 1; k++) {
		int cut = n;
		if (k < count) {
			const double target = total * k / count;
			double run = 0;
			int best = cut_prev + 1;
			double best_gap = -1;
			for (int j = 1; j <= n; j++) {
				run += case_cost(&suite->cases[j - 1]);
				if (j < cut_prev + 1 || j > n - (count - k))
					continue;
				double gap = run > target ? run - target : target - run;
				if (best_gap < 0 || gap < best_gap) {
					best_gap = gap;
					best = j;
				}
			}
			cut = best;
		}
		if (k == index + 1) {
			*begin = cut_prev;
			*end = cut;
			return;
		}
		cut_prev = cut;
	}
}

int aa_shard_job(const struct aa_job_spec *whole, int index, int count, struct aa_job_spec *out,
		 struct aa_error *err)
{
	if (whole->is_suite) {
		if (count > whole->case_count)
			return aa_error_set(err, AA_ERR_INVALID, "shard", "%d shards of a suite of %d cases would leave "
					    "shards without cases (a suite is split by whole cases); valid: 1 to %d shards",
					    count, whole->case_count, whole->case_count);
		int begin, end;
		aa_shard_cases(whole, index, count, &begin, &end);
		*out = *whole;
		out->case_count = end - begin;
		memmove(out->cases, whole->cases + begin, (size_t)(end - begin) * sizeof *out->cases);
		out->warmup_frames = 0;
		out->order_ordinal = 0;
		return 0;
	}
	if (count > whole->frames)
		return aa_error_set(err, AA_ERR_INVALID, "shard", "%d shards of %d frames would leave shards "
				    "without frames; valid: 1 to %d shards", count, whole->frames, whole->frames);
	int begin, end;
	aa_shard_range(whole->frames, index, count, &begin, &end);
	const int warmup = aa_job_shard_warmup(whole);
	*out = *whole;
	out->first_frame = whole->first_frame + begin;
	out->frames = end - begin;
	out->warmup_frames = warmup < begin ? warmup : begin;
	out->order_ordinal = whole->order_ordinal + begin;
	return 0;
}

json_t *aa_shard_json(const struct aa_job_spec *whole, int index, int count)
{
	int begin, end;
	char hash[80];
	aa_job_hash(whole, hash, sizeof hash);
	json_t *j = json_pack("{s:i, s:i, s:s, s:o, s:i}", "index", index, "count", count, "job_hash", hash, "job",
			      aa_job_spec_to_json(whole), "warmup", whole->is_suite ? 0 : aa_job_shard_warmup(whole));
	if (whole->is_suite) {
		aa_shard_cases(whole, index, count, &begin, &end);
		json_object_set_new(j, "cases", json_pack("{s:i, s:i}", "first", begin, "count", end - begin));
	} else {
		aa_shard_range(whole->frames, index, count, &begin, &end);
		json_object_set_new(j, "frames", json_pack("{s:i, s:i}", "first", whole->first_frame + begin, "count",
							   end - begin));
	}
	return j;
}
