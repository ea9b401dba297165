/* results.json (docs/results-format.md): the job, the plan, the reference and per-method cost and accuracy.
 * JSON has no NaN or Infinity, so every double goes through num(): non-finite values become null. */
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "results/front.h"
#include "results/results.h"
#include "results/warnings.h"
#include "util/file_io.h"
#include "methods/user_method.h"
#include "methods/methods.h"
#include "run/job_spec.h"

#define RESULTS_VERSION 1

/* Builder state: the first failed allocation is remembered and the whole document is dropped, rather
 * than writing a results.json with fields silently missing. */
struct builder {
	bool ok;
};

static json_t *num(double v)
{
	return isfinite(v) ? json_real(v) : json_null();
}

static json_t *u64(uint64_t v)
{
	return json_integer(v > (uint64_t)LLONG_MAX ? LLONG_MAX : (json_int_t)v);
}

/* Strings from drivers or file systems need not be UTF-8; jansson refuses those, so replace such bytes. */
static json_t *str(const char *s)
{
	json_t *v = json_string(s ? s : "");
	if (v)
		return v;
	char buf[1024];
	size_t n = 0;
	for (; s[n] && n + 1 < sizeof buf; n++)
		buf[n] = (unsigned char)s[n] < 0x80 ? s[n] : '?';
	buf[n] = '\0';
	return json_string(buf);
}

/* Both take ownership of value, as json_object_set_new does, even when they fail. */
static void put(struct builder *b, json_t *obj, const char *key, json_t *value)
{
	if (!obj || !value) {
		json_decref(value);
		b->ok = false;
	} else if (json_object_set_new(obj, key, value) < 0) {
		b->ok = false;
	}
}

static void push(struct builder *b, json_t *arr, json_t *value)
{
	if (!arr || !value) {
		json_decref(value);
		b->ok = false;
	} else if (json_array_append_new(arr, value) < 0) {
		b->ok = false;
	}
}

/* {"psnr": x} or {"psnr": null, "identical": true}: the rule for every PSNR the file holds. */
static void put_psnr(struct builder *b, json_t *obj, const char *key, const char *identical_key, double psnr,
		     bool identical)
{
	put(b, obj, key, identical ? json_null() : num(psnr));
	put(b, obj, identical_key, json_boolean(identical));
}

/* A frame's PSNR as reported: null when identical; recomputed from MSE if the metrics left it unset. */
static double frame_psnr(const struct aa_metrics *m)
{
	if (m->identical)
		return NAN;
	return isfinite(m->psnr) ? m->psnr : aa_psnr_from_mse(m->mse, 255.0);
}

/* {"low": x, "mid": y, "high": z}: the MSE carried by each frequency band (metrics/fourier.h). */
static json_t *fourier_json(struct builder *b, const double band[AA_FOURIER_BANDS])
{
	json_t *obj = json_object();
	for (int i = 0; i < AA_FOURIER_BANDS; i++)
		put(b, obj, aa_fourier_band_names[i], num(band[i]));
	return obj;
}

static json_t *params_json(struct builder *b, const struct aa_method *method, const struct aa_method_params *p)
{
	json_t *obj = json_object();
	const int n = method ? (method->param_count < AA_MAX_PARAMS ? method->param_count : AA_MAX_PARAMS) : 0;
	for (int i = 0; i < n; i++) {
		const struct aa_param_def *d = &method->params[i];
		char text[64];
		json_t *v = NULL;
		switch (d->type) {
		case AA_PARAM_INT:
			v = isfinite(p->v[i]) ? json_integer((json_int_t)llround(p->v[i])) : json_null();
			break;
		case AA_PARAM_FLOAT:
			v = num(p->v[i]);
			break;
		case AA_PARAM_ENUM:
			aa_method_param_text(method, p, i, text, sizeof text);
			v = str(text);
			break;
		case AA_PARAM_BOOL:
			v = json_boolean(p->v[i] != 0);
			break;
		}
		put(b, obj, d->name, v);
	}
	return obj;
}

static json_t *image_path(const struct aa_job_result *r, const char *kind, const char *label, int ordinal)
{
	char rel[512];
	if (!r->spec.keep_frames)
		return json_null(); /* no images were written */
	aa_results_frame_relpath(kind, label, ordinal, rel, sizeof rel);
	return str(rel);
}

/* {"median", "p10", "p90", "min", "mean", "n"}: a time's distribution (null fields when n is 0). */
static json_t *timing_json(const struct aa_timing_stats *t)
{
	return json_pack("{s:o, s:o, s:o, s:o, s:o, s:i}", "median", num(t->median), "p10", num(t->p10), "p90",
			 num(t->p90), "min", num(t->min), "mean", num(t->mean), "n", t->n);
}

/* Every pass name seen over the frames, in order of first appearance, with its GPU time over every timed
 * render that ran it: `gpu_ms` the median (as before), then the spread. */
static json_t *pass_stats(struct builder *b, const struct aa_method_result *m)
{
	json_t *arr = json_array();
	for (int i = 0; i < m->frame_count; i++) {
		for (int k = 0; k < m->frames[i].pass_count && k < AA_MAX_PASSES; k++) {
			const char *name = m->frames[i].passes[k].name;
			bool earlier = false;
			for (int j = 0; j < i && !earlier; j++)
				for (int q = 0; q < m->frames[j].pass_count && q < AA_MAX_PASSES && !earlier; q++)
					earlier = strcmp(m->frames[j].passes[q].name, name) == 0;
			for (int q = 0; q < k && !earlier; q++)
				earlier = strcmp(m->frames[i].passes[q].name, name) == 0;
			if (earlier)
				continue;
			struct aa_timing_stats t;
			aa_pass_timing_stats(m, name, &t);
			json_t *pass = json_object();
			put(b, pass, "name", str(name));
			put(b, pass, "gpu_ms", num(t.median));
			put(b, pass, "p10", num(t.p10));
			put(b, pass, "p90", num(t.p90));
			put(b, pass, "min", num(t.min));
			put(b, pass, "n", json_integer(t.n));
			push(b, arr, pass);
		}
	}
	return arr;
}

/* Every timed render in the order of frames and repeats: its place in the round's method order, totals
 * and pass times by name. */
static json_t *timed_renders_json(struct builder *b, const struct aa_method_result *m)
{
	json_t *arr = json_array();
	for (int i = 0; m->timed && i < m->timed_count; i++) {
		const struct aa_timed_render *t = &m->timed[i];
		json_t *obj = json_object(), *passes = json_object();
		const struct aa_frame_result *f = t->ordinal >= 0 && t->ordinal < m->frame_count ? &m->frames[t->ordinal]
												  : NULL;
		for (int k = 0; f && k < t->pass_count && k < f->pass_count && k < AA_MAX_PASSES; k++)
			put(b, passes, f->passes[k].name, num(t->pass_ms[k]));
		put(b, obj, "frame", json_integer(f ? f->frame : -1));
		put(b, obj, "repeat", json_integer(t->repeat));
		put(b, obj, "position", json_integer(t->position));
		put(b, obj, "gpu_ms", num(t->gpu_ms));
		put(b, obj, "cpu_ms", num(t->cpu_ms));
		put(b, obj, "passes", passes);
		push(b, arr, obj);
	}
	return arr;
}

static json_t *frame_json(struct builder *b, const struct aa_job_result *r, const struct aa_method_result *m,
			  int ordinal)
{
	const struct aa_frame_result *f = &m->frames[ordinal];
	json_t *obj = json_object(), *passes = json_array();
	put(b, obj, "frame", json_integer(f->frame));
	put(b, obj, "gpu_ms", num(f->gpu_ms));
	put(b, obj, "cpu_ms", num(f->cpu_ms));
	for (int k = 0; k < f->pass_count && k < AA_MAX_PASSES; k++) {
		json_t *pass = json_object();
		put(b, pass, "name", str(f->passes[k].name));
		put(b, pass, "gpu_ms", num(f->passes[k].gpu_ms));
		push(b, passes, pass);
	}
	put(b, obj, "passes", passes);
	put_psnr(b, obj, "psnr", "identical", frame_psnr(&f->metrics), f->metrics.identical);
	put(b, obj, "ssim", num(f->metrics.ssim));
	put(b, obj, "flicker", num(f->flicker));
	put(b, obj, "mse", num(f->metrics.identical ? 0.0 : f->metrics.mse));
	put(b, obj, "rmsd", num(f->metrics.identical ? 0.0 : f->metrics.rmsd));
	put(b, obj, "snr", f->metrics.identical ? json_null() : num(f->metrics.snr));
	put(b, obj, "max_abs", num(f->metrics.max_abs));
	put(b, obj, "flip", num(f->metrics.flip_mean));
	put(b, obj, "fourier", fourier_json(b, f->metrics.fourier));
	put(b, obj, "nonfinite", json_integer(f->nonfinite));
	put(b, obj, "over_threshold", json_integer(f->over_threshold));
	put(b, obj, "out_of_range", json_integer(f->out_of_range));
	put(b, obj, "change", num(f->change));
	put(b, obj, "reference_change", num(f->ref_change));
	if (r->spec.debug_targets) { /* job option debug_targets: the method's intermediates after this frame */
		json_t *in = json_object(), *bad = json_array();
		put(b, in, "targets_read", json_integer(f->targets_read));
		put(b, in, "invalid_texels", json_integer(f->intermediate_invalid));
		for (int k = 0; k < f->invalid_target_count && k < AA_MAX_INVALID_TARGETS; k++) {
			json_t *t = json_object();
			put(b, t, "name", str(f->invalid_targets[k].name));
			put(b, t, "invalid_texels", json_integer(f->invalid_targets[k].texels));
			push(b, bad, t);
		}
		put(b, in, "invalid_targets", bad);
		put(b, obj, "intermediates", in);
	}
	put(b, obj, "image", image_path(r, "frames", m->label, ordinal));
	put(b, obj, "diff", image_path(r, "diff", m->label, ordinal));
	put(b, obj, "flip_map", image_path(r, "flip", m->label, ordinal));
	return obj;
}

/* {"frame": 3, "value": 41.2} or {"frame": 3, "value": null, "identical": true}; null frame when none. */
static json_t *extreme_json(struct builder *b, const struct aa_method_result *m, int frame, double value)
{
	json_t *obj = json_object();
	bool identical = false;
	for (int i = 0; i < m->frame_count; i++)
		if (m->frames[i].frame == frame)
			identical = m->frames[i].metrics.identical;
	put(b, obj, "frame", frame >= 0 ? json_integer(frame) : json_null());
	put_psnr(b, obj, "value", "identical", value, identical);
	return obj;
}

static json_t *metrics_json(struct builder *b, const struct aa_job_result *r, const struct aa_method_result *m,
			    const struct aa_method_summary *s)
{
	json_t *metrics = json_object(), *psnr = json_object(), *ssim = json_object();
	json_t *psnr_frames = json_array(), *ssim_frames = json_array();
	double snr_sum = 0, max_abs = NAN;
	int snr_n = 0;
	for (int i = 0; i < m->frame_count; i++) {
		const struct aa_metrics *fm = &m->frames[i].metrics;
		push(b, psnr_frames, num(frame_psnr(fm)));
		push(b, ssim_frames, num(fm->ssim));
		if (!fm->identical && isfinite(fm->snr)) {
			snr_sum += fm->snr;
			snr_n++;
		}
		if (isfinite(fm->max_abs) && !(fm->max_abs <= max_abs))
			max_abs = fm->max_abs;
	}
	put_psnr(b, psnr, "mean", "identical", s->psnr_mean, s->psnr_identical);
	put(b, psnr, "per_frame", psnr_frames);
	put(b, psnr, "best", extreme_json(b, m, s->best_frame, s->best_psnr));
	put(b, psnr, "worst", extreme_json(b, m, s->worst_frame, s->worst_psnr));
	put(b, metrics, "psnr", psnr);
	put(b, metrics, "mse", json_pack("{s:o}", "mean", num(s->mse_mean)));
	/* RMS difference over all pixels of all frames, consistent with PSNR from the mean MSE. */
	put(b, metrics, "rmsd", json_pack("{s:o}", "mean", num(sqrt(s->mse_mean))));
	put(b, metrics, "snr", json_pack("{s:o}", "mean", num(snr_n ? snr_sum / snr_n : NAN)));
	put(b, ssim, "mean", num(s->ssim_mean));
	put(b, ssim, "per_frame", ssim_frames);
	put(b, metrics, "ssim", ssim);
	put(b, metrics, "max_abs", json_pack("{s:o}", "max", num(max_abs)));

	/* FLIP and the Fourier bands: means over the frames that have them. */
	json_t *flip = json_object(), *flip_frames = json_array();
	double band_sum[AA_FOURIER_BANDS] = { 0 }, band_mean[AA_FOURIER_BANDS];
	int band_n = 0;
	for (int i = 0; i < m->frame_count; i++) {
		const struct aa_metrics *fm = &m->frames[i].metrics;
		push(b, flip_frames, num(fm->flip_mean));
		bool bands_ok = true;
		for (int k = 0; k < AA_FOURIER_BANDS; k++)
			bands_ok = bands_ok && isfinite(fm->fourier[k]);
		for (int k = 0; bands_ok && k < AA_FOURIER_BANDS; k++)
			band_sum[k] += fm->fourier[k];
		band_n += bands_ok;
	}
	put(b, flip, "mean", num(s->flip_mean));
	put(b, flip, "per_frame", flip_frames);
	put(b, flip, "ppd", num(AA_FLIP_DEFAULT_PPD));
	put(b, metrics, "flip", flip);
	json_t *flicker = json_object(), *flicker_frames = json_array();
	for (int i = 0; i < m->frame_count; i++)
		push(b, flicker_frames, num(m->frames[i].flicker));
	put(b, flicker, "mean", num(s->flicker_mean));
	put(b, flicker, "per_frame", flicker_frames);
	put(b, metrics, "flicker", flicker);
	/* idiff's count of pixels over a threshold (any of R,G,B), per frame and as a mean share */
	json_t *over = json_object(), *over_frames = json_array();
	for (int i = 0; i < m->frame_count; i++)
		push(b, over_frames, json_integer(m->frames[i].over_threshold));
	put(b, over, "threshold", num(r->spec.over_threshold));
	put(b, over, "mean_share", num(s->over_threshold_mean / ((double)r->spec.width * r->spec.height)));
	put(b, over, "per_frame", over_frames);
	put(b, metrics, "over_threshold", over);
	for (int k = 0; k < AA_FOURIER_BANDS; k++)
		band_mean[k] = band_n ? band_sum[k] / band_n : NAN;
	json_t *fourier = fourier_json(b, band_mean);
	put(b, fourier, "edges", json_pack("[f, f]", AA_FOURIER_LOW_MID, AA_FOURIER_MID_HIGH));
	put(b, metrics, "fourier", fourier);

	json_t *curve = json_object(), *thresholds = json_array(), *share = json_array();
	for (int t = 0; t < AA_THRESHOLD_COUNT; t++) {
		double sum = 0;
		int n = 0;
		for (int i = 0; i < m->frame_count; i++)
			if (isfinite(m->frames[i].metrics.exceed[t])) {
				sum += m->frames[i].metrics.exceed[t];
				n++;
			}
		push(b, thresholds, num(t / 100.0));
		push(b, share, num(n ? sum / n : NAN));
	}
	put(b, curve, "thresholds", thresholds);
	put(b, curve, "share", share);
	put(b, metrics, "error_threshold_curve", curve);
	return metrics;
}

static json_t *method_json(struct builder *b, const struct aa_job_result *r, const struct aa_method_result *m)
{
	struct aa_method_summary s;
	aa_method_summarize(m, &s);
	char name[AA_LABEL_MAX];
	snprintf(name, sizeof name, "%s", m->method ? m->method->name : m->label);
	name[strcspn(name, ":")] = '\0';

	json_t *obj = json_object(), *memory = json_array(), *frames = json_array();
	put(b, obj, "name", str(name));
	put(b, obj, "label", str(m->label));
	put(b, obj, "params", params_json(b, m->method, &m->params));
	const struct aa_user_method *um = aa_user_method_of(m->method);
	if (um) { /* "name" says what kind of method it is; the file says which one, and its hash which version */
		put(b, obj, "name", str("user"));
		put(b, obj, "user_method", json_pack("{s:s, s:s, s:s, s:s}", "name", um->name, "file", um->file,
						     "sha256", um->sha256, "summary", um->summary));
	}
	put(b, obj, "path_taken", str(m->path_taken));
	put(b, obj, "alpha_rule", str(m->method ? aa_alpha_rule_name(aa_method_alpha_rule(m->method, &m->params))
						: ""));
	put(b, obj, "gpu_ms", timing_json(&s.gpu_ms));
	put(b, obj, "cpu_ms", timing_json(&s.cpu_ms));
	put(b, obj, "memory_bytes", u64(m->memory_bytes));
	for (int i = 0; i < m->memory_count && i < AA_MAX_MEMORY_ITEMS; i++)
		push(b, memory, json_pack("{s:o, s:o}", "name", str(m->memory[i].name), "bytes", u64(m->memory[i].bytes)));
	put(b, obj, "memory", memory);
	put(b, obj, "passes", pass_stats(b, m));
	put(b, obj, "timed_renders", timed_renders_json(b, m));
	put(b, obj, "metrics", metrics_json(b, r, m, &s));
	for (int i = 0; i < m->frame_count; i++)
		push(b, frames, frame_json(b, r, m, i));
	put(b, obj, "frames", frames);
	return obj;
}

/* What the reference store did (null: the run had none). */
static json_t *reference_cache_json(struct builder *b, const struct aa_reference_cache_result *c)
{
	if (!c->used)
		return json_null();
	json_t *obj = json_object(), *warnings = json_array();
	put(b, obj, "hits", json_integer(c->hits));
	put(b, obj, "misses", json_integer(c->misses));
	put(b, obj, "continued", json_integer(c->continued));
	put(b, obj, "unkeyed", json_integer(c->unkeyed));
	put(b, obj, "bytes_read", u64(c->bytes_read));
	put(b, obj, "bytes_written", u64(c->bytes_written));
	put(b, obj, "discarded", json_integer(c->discarded));
	for (int i = 0; i < c->warning_count && i < AA_REFERENCE_CACHE_WARNINGS; i++)
		push(b, warnings, str(c->warnings[i]));
	put(b, obj, "warnings", warnings);
	return obj;
}

static json_t *reference_json(struct builder *b, const struct aa_job_result *r)
{
	const struct aa_reference_result *ref = &r->reference;
	const int n = ref->frames ? ref->frame_count : 0;
	double *v = malloc((size_t)(n > 0 ? n : 1) * 2 * sizeof *v);
	json_t *obj = json_object(), *per_frame = json_array();
	if (!v) {
		b->ok = false;
		json_decref(per_frame);
		return obj;
	}
	double mse_sum = 0;
	int mse_n = 0;
	for (int i = 0; i < n; i++) {
		const struct aa_reference_frame *f = &ref->frames[i];
		v[i] = f->gpu_ms;
		v[n + i] = f->cpu_ms;
		double mse = f->convergence_identical ? 0.0 : f->convergence_mse;
		/* A frame with a PSNR but no MSE still counts: recover its MSE from the PSNR. */
		if (!f->convergence_identical && !(mse > 0) && isfinite(f->convergence_psnr))
			mse = 255.0 * 255.0 / pow(10.0, f->convergence_psnr / 10.0);
		if (isfinite(mse)) {
			mse_sum += mse;
			mse_n++;
		}
		json_t *fo = json_object();
		put(b, fo, "frame", json_integer(f->frame));
		put(b, fo, "gpu_ms", num(f->gpu_ms));
		put(b, fo, "cpu_ms", num(f->cpu_ms));
		/* From the MSE when there is one, so that per-frame values and the mean agree by construction. */
		const double psnr = mse > 0 && isfinite(mse) ? aa_psnr_from_mse(mse, 255.0) : f->convergence_psnr;
		put_psnr(b, fo, "convergence_psnr", "convergence_identical", psnr, f->convergence_identical);
		put(b, fo, "convergence_mse", num(mse));
		put(b, fo, "nonfinite", json_integer(f->nonfinite));
		put(b, fo, "reused", json_boolean(f->reused));
		put(b, fo, "samples", json_integer(f->samples));
		if (f->cache[0])
			put(b, fo, "cache", str(f->cache));
		put(b, fo, "image", image_path(r, "frames", "reference", i));
		push(b, per_frame, fo);
	}
	const double mse_mean = mse_n ? mse_sum / mse_n : NAN;
	put(b, obj, "samples", json_integer(ref->samples));
	/* "auto": samples is the cap and each frame says the N it reached */
	put(b, obj, "mode", str(ref->auto_samples ? "auto" : "fixed"));
	if (ref->auto_samples)
		put(b, obj, "target_psnr", num(ref->target_psnr));
	put(b, obj, "alpha_rule", str(aa_alpha_rule_name(AA_ALPHA_PER_SAMPLE))); /* each jittered render tests its own */
	put(b, obj, "pattern", str(ref->pattern));
	put(b, obj, "memory_bytes", u64(ref->memory_bytes));
	put(b, obj, "gpu_ms", json_pack("{s:o, s:o}", "median", num(aa_percentile(v, n, 50)), "p90",
					 num(aa_percentile(v, n, 90))));
	put(b, obj, "cpu_ms", json_pack("{s:o}", "median", num(aa_percentile(v + n, n, 50))));
	put_psnr(b, obj, "convergence_psnr", "convergence_identical",
		 mse_mean > 0 ? aa_psnr_from_mse(mse_mean, 255.0) : NAN, mse_n > 0 && mse_mean == 0);
	put(b, obj, "convergence_mse", num(mse_mean));
	put(b, obj, "cache", reference_cache_json(b, &ref->cache));
	put(b, obj, "per_frame", per_frame);
	free(v);
	return obj;
}

json_t *aa_results_to_json(const struct aa_job_result *r)
{
	struct builder b = { .ok = true };
	json_t *root = json_object(), *plan = json_array(), *methods = json_array();
	put(&b, root, "version", json_integer(RESULTS_VERSION));
	put(&b, root, "name", str(r->spec.name));
	put(&b, root, "started_at", str(r->started_at));
	put(&b, root, "wall_seconds", num(r->wall_seconds));
	/* first, what a reader wants to know: the verdict, and the warnings that qualify it */
	json_t *verdict = aa_verdict_json(r);
	put(&b, root, "verdict", verdict ? json_incref(verdict) : NULL);
	put(&b, root, "warnings", verdict ? aa_results_warnings_json(r, verdict) : NULL);
	json_decref(verdict);
	put(&b, root, "job", aa_job_spec_to_json(&r->spec));
	/* for build farms: what run this was, which suite, and a hash of the work that equals another run's
	 * exactly when both rendered the same job */
	json_t *labels = json_object();
	for (int i = 0; i < r->spec.label_count && i < AA_MAX_LABELS; i++)
		put(&b, labels, r->spec.labels[i].key, str(r->spec.labels[i].value));
	put(&b, root, "labels", labels);
	put(&b, root, "suite", str(r->spec.suite));
	char hash[80];
	aa_job_hash(&r->spec, hash, sizeof hash);
	put(&b, root, "job_hash", str(hash));
	put(&b, root, "scene", json_pack("{s:o, s:o, s:o}", "name", str(r->scene_name), "file", str(r->scene_file),
					 "triangles", u64(r->scene_triangles)));
	put(&b, root, "device", json_pack("{s:o, s:o, s:o}", "name", str(r->device_name), "driver",
					  str(r->driver_info), "timestamp_period_ns", num(r->timestamp_period_ns)));
	put(&b, root, "size", json_pack("{s:i, s:i}", "width", r->spec.width, "height", r->spec.height));
	put(&b, root, "frames", json_integer(r->spec.frames));
	put(&b, root, "first_frame", json_integer(r->spec.first_frame));
	/* how times were taken: every method's frame `repeat` times, the order rotating each round */
	const int repeat = r->spec.timing_repeat > 0 ? r->spec.timing_repeat : 1;
	put(&b, root, "timing", json_pack("{s:i, s:b, s:s, s:i, s:i}", "repeat", repeat, "auto", r->spec.timing_auto,
					  "order", "rotating", "timed_renders_per_method", r->spec.frames * repeat,
					  "min_timed_renders", AA_FRONT_MIN_TIMED_RENDERS));
	for (int i = 0; i < r->plan_count && i < AA_MAX_PASSES; i++)
		push(&b, plan, json_pack("{s:o, s:o, s:b}", "pass", str(r->plan[i].pass), "reason", str(r->plan[i].reason),
					 "ran", r->plan[i].ran));
	put(&b, root, "passes", plan);
	put(&b, root, "reference", reference_json(&b, r));
	for (int i = 0; i < r->method_count && i < AA_MAX_METHODS; i++)
		push(&b, methods, method_json(&b, r, &r->methods[i]));
	put(&b, root, "methods", methods);
	if (!b.ok) {
		json_decref(root);
		return NULL;
	}
	return root;
}

int aa_results_write_file_atomic(const char *dir, const char *name, const char *data, size_t size,
				 struct aa_error *err)
{
	const struct aa_file_part part = {data, size};
	return aa_file_write_atomic(dir, name, &part, 1, err);
}

int aa_results_write_json_doc(const json_t *root, const char *dir, const char *name, struct aa_error *err)
{
	/* 15 significant digits: exact enough for every metric, and 0.1 prints as 0.1. */
	char *text = json_dumps(root, JSON_INDENT(2) | JSON_REAL_PRECISION(15));
	if (!text)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "cannot serialise %s", name);
	const size_t len = strlen(text);
	char *with_newline = realloc(text, len + 2);
	if (!with_newline) {
		free(text);
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory writing %s", name);
	}
	with_newline[len] = '\n';
	with_newline[len + 1] = '\0';
	int rc = aa_results_write_file_atomic(dir, name, with_newline, len + 1, err);
	free(with_newline);
	return rc;
}

int aa_results_write_json(const struct aa_job_result *r, const char *dir, struct aa_error *err)
{
	json_t *root = aa_results_to_json(r);
	if (!root)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory building results.json");
	int rc = aa_results_write_json_doc(root, dir, "results.json", err);
	json_decref(root);
	return rc;
}
