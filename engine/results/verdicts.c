/* Verdicts on the frames of a hard-case suite (docs/hard-cases.md, "Verdicts"). Each verdict reads only
 * what the run measured per frame (results.json has the same figures), so a failure can be checked by
 * hand from the file. */
#include <math.h>
#include <string.h>

#include "methods/methods.h"
#include "results/verdicts.h"
#include "run/job_spec.h"

static const char *const names[AA_VERDICT_COUNT] = {"finite", "range", "stuck", "drift", "vs_none", "dip"};

const char *aa_verdict_name(enum aa_verdict_kind k)
{
	return k >= 0 && k < AA_VERDICT_COUNT ? names[k] : "?";
}

/* The failures docs/hard-cases.md expects, with its reason ("Expected exceptions"); keep the two in step. */
static const struct {
	const char *scene, *method, *param, *value;
	enum aa_verdict_kind kind;
	const char *reason;
} expected_failures[] = {
#include "results/verdicts_expected.h"
};

/* Method m run with params p has parameter `name` at `value` (as aa_method_param_text writes it). */
static bool param_holds(const struct aa_method *m, const struct aa_method_params *p, const char *name,
			const char *value)
{
	char text[64];
	const int i = aa_method_param_index(m, name);
	if (i < 0)
		return false;
	aa_method_param_text(m, p, i, text, sizeof text);
	return !strcmp(text, value);
}

const char *aa_verdict_expected(const char *scene, const struct aa_method *m, const struct aa_method_params *p,
				enum aa_verdict_kind k)
{
	for (size_t i = 0; i < sizeof expected_failures / sizeof expected_failures[0]; i++)
		if (expected_failures[i].kind == k && !strcmp(expected_failures[i].scene, scene) &&
		    !strcmp(expected_failures[i].method, m->name) &&
		    (!expected_failures[i].param ||
		     param_holds(m, p, expected_failures[i].param, expected_failures[i].value)))
			return expected_failures[i].reason;
	return NULL;
}

/* PSNR of the mean MSE over frames [from, to); +inf when every one is identical. */
static double psnr_over(const struct aa_method_result *m, int from, int to)
{
	double sum = 0;
	int n = 0;
	for (int f = from; f < to && f < m->frame_count; f++) {
		const double mse = m->frames[f].metrics.identical ? 0.0 : m->frames[f].metrics.mse;
		if (isfinite(mse)) {
			sum += mse;
			n++;
		}
	}
	if (!n)
		return NAN;
	return sum > 0 ? aa_psnr_from_mse(sum / n, 255.0) : INFINITY;
}

/* PSNR of frame f; +inf when identical, NAN when not measured. */
static double frame_psnr(const struct aa_method_result *m, int f)
{
	const double mse = m->frames[f].metrics.identical ? 0.0 : m->frames[f].metrics.mse;
	if (!isfinite(mse))
		return NAN;
	return mse > 0 ? aa_psnr_from_mse(mse, 255.0) : INFINITY;
}

/* The smallest PSNR(m) - PSNR(none) over the frames both measured (matched by frame index); NAN if none.
 * A frame both render identically to the reference counts as 0. */
static double worst_frame_vs(const struct aa_method_result *m, const struct aa_method_result *none, int *at)
{
	double worst = NAN;
	for (int f = 0; f < m->frame_count && f < none->frame_count; f++) {
		const double a = frame_psnr(m, f), b = frame_psnr(none, f);
		if (isnan(a) || isnan(b) || (isinf(a) && isinf(b)))
			continue;
		const double d = isinf(a) ? INFINITY : isinf(b) ? -INFINITY : a - b;
		if (isnan(worst) || d < worst) {
			worst = d;
			*at = m->frames[f].frame;
		}
	}
	return worst;
}

static int find_none(const struct aa_job_result *c)
{
	for (int i = 0; i < c->method_count; i++)
		if (c->methods[i].method && !strcmp(c->methods[i].method->name, "none"))
			return i;
	return -1;
}

void aa_verdict_judge(const struct aa_job_result *c, int mi, struct aa_verdict *out)
{
	memset(out, 0, sizeof *out);
	const struct aa_method_result *m = &c->methods[mi];
	long nonfinite = 0, out_of_range = 0;
	double worst_ratio = INFINITY;
	for (int f = 0; f < m->frame_count; f++) {
		const struct aa_frame_result *fr = &m->frames[f];
		/* with job option debug_targets also what the method's intermediates held (0 without it) */
		nonfinite += fr->nonfinite + fr->intermediate_invalid;
		out_of_range += fr->out_of_range;
		/* stuck: the reference moved by at least 1/255 on average and the method by a tenth of that */
		if (isfinite(fr->ref_change) && fr->ref_change >= AA_VERDICT_STUCK_MIN_CHANGE && isfinite(fr->change)) {
			const double ratio = fr->change / fr->ref_change;
			worst_ratio = ratio < worst_ratio ? ratio : worst_ratio;
		}
	}
	out->value[AA_VERDICT_FINITE] = (double)nonfinite;
	out->state[AA_VERDICT_FINITE] = m->frame_count ? (nonfinite ? AA_VERDICT_FAIL : AA_VERDICT_PASS) : AA_VERDICT_NA;
	out->value[AA_VERDICT_RANGE] = (double)out_of_range;
	out->state[AA_VERDICT_RANGE] = m->frame_count ? (out_of_range ? AA_VERDICT_FAIL : AA_VERDICT_PASS)
						      : AA_VERDICT_NA;
	out->value[AA_VERDICT_STUCK] = isfinite(worst_ratio) ? worst_ratio : NAN;
	out->state[AA_VERDICT_STUCK] = !isfinite(worst_ratio)			  ? AA_VERDICT_NA
				       : worst_ratio < AA_VERDICT_STUCK_RATIO ? AA_VERDICT_FAIL
									      : AA_VERDICT_PASS;
	/* drift: on a held camera the reference is one image; a method that has converged must stay there */
	out->value[AA_VERDICT_DRIFT] = NAN;
	const int n = m->frame_count;
	bool still = !strcmp(c->spec.path, "static") && n >= AA_VERDICT_DRIFT_MIN_FRAMES;
	for (int f = 1; still && c->reference.frames && f < c->reference.frame_count; f++)
		still = c->reference.frames[f].reused; /* nothing moves: the reference is one image */
	if (still) {
		const double early = psnr_over(m, n / 4, n / 2), late = psnr_over(m, 3 * n / 4, n);
		double d = isinf(early) && isinf(late) ? 0.0 : late - early;
		out->value[AA_VERDICT_DRIFT] = d;
		out->state[AA_VERDICT_DRIFT] = isnan(d) ? AA_VERDICT_NA
					       : d < -AA_VERDICT_DRIFT_DB ? AA_VERDICT_FAIL
									   : AA_VERDICT_PASS;
	}
	out->value[AA_VERDICT_VS_NONE] = NAN;
	out->value[AA_VERDICT_DIP] = NAN;
	const int none = find_none(c);
	if (none >= 0 && none != mi) {
		const double mine = psnr_over(m, 0, n), base = psnr_over(&c->methods[none], 0, c->methods[none].frame_count);
		double d = isinf(mine) ? INFINITY : mine - base;
		out->value[AA_VERDICT_VS_NONE] = d;
		out->state[AA_VERDICT_VS_NONE] = isnan(d) ? AA_VERDICT_NA
						 : d < -AA_VERDICT_VS_NONE_DB ? AA_VERDICT_FAIL
									       : AA_VERDICT_PASS;
		int at = 0;
		const double dip = worst_frame_vs(m, &c->methods[none], &at);
		out->value[AA_VERDICT_DIP] = dip;
		out->dip_frame = at;
		out->state[AA_VERDICT_DIP] = isnan(dip) ? AA_VERDICT_NA
					     : dip < -AA_VERDICT_DIP_DB ? AA_VERDICT_FAIL
									 : AA_VERDICT_PASS;
	}
	for (int k = 0; k < AA_VERDICT_COUNT; k++)
		if (out->state[k] == AA_VERDICT_FAIL && m->method)
			out->expected[k] = aa_verdict_expected(c->scene_name, m->method, &m->params,
							      (enum aa_verdict_kind)k);
}

json_t *aa_verdicts_json(const struct aa_suite_result *r, int *failed)
{
	static const char *const states[] = {"n/a", "pass", "fail"};
	json_t *items = json_array();
	int unexpected = 0, expected = 0;
	for (int i = 0; i < r->case_count && i < AA_MAX_CASES; i++) {
		const struct aa_job_result *c = r->cases[i];
		char id[400];
		aa_case_id(&r->spec, i, id, sizeof id);
		for (int mi = 0; mi < c->method_count; mi++) {
			struct aa_verdict v;
			aa_verdict_judge(c, mi, &v);
			json_t *verdicts = json_object();
			for (int k = 0; k < AA_VERDICT_COUNT; k++) {
				json_t *one = json_pack("{s:s, s:o}", "state", states[v.state[k]], "value",
							isfinite(v.value[k]) ? json_real(v.value[k])
							: isinf(v.value[k])  ? json_string(v.value[k] > 0 ? "inf" : "-inf")
									     : json_null());
				if (v.expected[k])
					json_object_set_new(one, "expected", json_string(v.expected[k]));
				if (k == AA_VERDICT_DIP && v.state[k] != AA_VERDICT_NA)
					json_object_set_new(one, "frame", json_integer(v.dip_frame));
				if (v.state[k] == AA_VERDICT_FAIL && v.expected[k])
					expected++;
				else if (v.state[k] == AA_VERDICT_FAIL)
					unexpected++;
				json_object_set_new(verdicts, names[k], one);
			}
			json_array_append_new(items, json_pack("{s:s, s:s, s:s, s:o}", "case", id, "scene", c->scene_name,
							       "method", c->methods[mi].label, "verdicts", verdicts));
		}
	}
	if (failed)
		*failed = unexpected;
	return json_pack("{s:i, s:i, s:{s:f, s:f, s:f, s:f, s:f}, s:o}", "failed", unexpected, "expected_failures",
			 expected, "thresholds", "stuck_ratio", AA_VERDICT_STUCK_RATIO, "stuck_min_reference_change",
			 AA_VERDICT_STUCK_MIN_CHANGE, "drift_db", AA_VERDICT_DRIFT_DB, "vs_none_db", AA_VERDICT_VS_NONE_DB,
			 "dip_db", AA_VERDICT_DIP_DB,
			 "items", items);
}
