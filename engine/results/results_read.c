/* results.json read back into a struct aa_job_result (aa_results_from_json):
 * what results_json.c writes per frame and per timed render. The merge of shards reads each shard's
 * results with it. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "types/job.h"
#include "results/results.h"
#include "run/engine.h"
#include "run/job_spec.h"

/* A number, or NAN for null and absent keys (the writer's num() wrote non-finite values as null). */
static double jnum(const json_t *obj, const char *key)
{
	const json_t *v = json_object_get(obj, key);
	return json_is_number(v) ? json_number_value(v) : NAN;
}

static double jnum_at(const json_t *arr, int i)
{
	const json_t *v = json_array_get(arr, (size_t)i);
	return json_is_number(v) ? json_number_value(v) : NAN;
}

static void jstr(const json_t *obj, const char *key, char *out, size_t size)
{
	const char *s = json_string_value(json_object_get(obj, key));
	snprintf(out, size, "%s", s ? s : "");
}

static int need_array(const json_t *obj, const char *key, const char *path, const json_t **out, struct aa_error *err)
{
	*out = json_object_get(obj, key);
	if (!json_is_array(*out))
		return aa_error_set(err, AA_ERR_INVALID, path, "expected an array");
	return 0;
}

static void read_metrics(const json_t *f, const double *curve, struct aa_metrics *m)
{
	m->identical = json_is_true(json_object_get(f, "identical"));
	m->psnr = jnum(f, "psnr");
	m->mse = jnum(f, "mse");
	m->rmsd = jnum(f, "rmsd");
	m->snr = jnum(f, "snr");
	m->ssim = jnum(f, "ssim");
	m->max_abs = jnum(f, "max_abs");
	m->flip_mean = jnum(f, "flip");
	const json_t *fourier = json_object_get(f, "fourier");
	for (int k = 0; k < AA_FOURIER_BANDS; k++)
		m->fourier[k] = jnum(fourier, aa_fourier_band_names[k]);
	for (int t = 0; t < AA_THRESHOLD_COUNT; t++)
		m->exceed[t] = curve[t];
}

static int read_frames(const json_t *jm, const char *path, int first_frame, int frames, int repeat,
		       struct aa_method_result *m, struct aa_error *err)
{
	char where[128];
	const json_t *arr, *timed, *item;
	size_t i;
	snprintf(where, sizeof where, "%s.frames", path);
	if (need_array(jm, "frames", where, &arr, err))
		return -1;
	if ((int)json_array_size(arr) != frames)
		return aa_error_set(err, AA_ERR_INVALID, where, "%zu frames; the job has %d", json_array_size(arr), frames);
	/* the job's error-threshold curve: results.json stores the mean over frames only */
	double curve[AA_THRESHOLD_COUNT];
	const json_t *share = json_object_get(json_object_get(json_object_get(jm, "metrics"), "error_threshold_curve"),
					      "share");
	for (int t = 0; t < AA_THRESHOLD_COUNT; t++)
		curve[t] = jnum_at(share, t);
	m->frames = calloc((size_t)frames, sizeof *m->frames);
	m->timed = calloc((size_t)frames * (size_t)repeat, sizeof *m->timed);
	if (!m->frames || !m->timed)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	json_array_foreach(arr, i, item) {
		struct aa_frame_result *f = &m->frames[i];
		f->frame = (int)json_integer_value(json_object_get(item, "frame"));
		if (f->frame != first_frame + (int)i) {
			snprintf(where, sizeof where, "%s.frames[%zu].frame", path, i);
			return aa_error_set(err, AA_ERR_INVALID, where, "%d, expected %d", f->frame, first_frame + (int)i);
		}
		f->gpu_ms = jnum(item, "gpu_ms");
		f->cpu_ms = jnum(item, "cpu_ms");
		const json_t *passes = json_object_get(item, "passes"), *p;
		size_t k;
		json_array_foreach(passes, k, p) {
			if (k >= AA_MAX_PASSES)
				break;
			jstr(p, "name", f->passes[k].name, sizeof f->passes[k].name);
			f->passes[k].gpu_ms = jnum(p, "gpu_ms");
			f->pass_count = (int)k + 1;
		}
		read_metrics(item, curve, &f->metrics);
		f->nonfinite = (long)json_integer_value(json_object_get(item, "nonfinite"));
		f->over_threshold = (long)json_integer_value(json_object_get(item, "over_threshold"));
		f->flicker = jnum(item, "flicker");
		f->out_of_range = (long)json_integer_value(json_object_get(item, "out_of_range"));
		f->change = jnum(item, "change");
		f->ref_change = jnum(item, "reference_change");
		const json_t *in = json_object_get(item, "intermediates"); /* job option debug_targets */
		if (in) {
			f->targets_read = (int)json_integer_value(json_object_get(in, "targets_read"));
			f->intermediate_invalid = (long)json_integer_value(json_object_get(in, "invalid_texels"));
			const json_t *bad = json_object_get(in, "invalid_targets"), *t;
			json_array_foreach(bad, k, t) {
				if (k >= AA_MAX_INVALID_TARGETS)
					break;
				jstr(t, "name", f->invalid_targets[k].name, sizeof f->invalid_targets[k].name);
				f->invalid_targets[k].texels = (long)json_integer_value(json_object_get(t, "invalid_texels"));
				f->invalid_target_count = (int)k + 1;
			}
		}
	}
	m->frame_count = frames;
	snprintf(where, sizeof where, "%s.timed_renders", path);
	if (need_array(jm, "timed_renders", where, &timed, err))
		return -1;
	if ((int)json_array_size(timed) != frames * repeat)
		return aa_error_set(err, AA_ERR_INVALID, where, "%zu timed renders; the job has %d", json_array_size(timed),
				    frames * repeat);
	json_array_foreach(timed, i, item) {
		const int ordinal = (int)json_integer_value(json_object_get(item, "frame")) - first_frame;
		const int r = (int)json_integer_value(json_object_get(item, "repeat"));
		if (ordinal < 0 || ordinal >= frames || r < 0 || r >= repeat) {
			snprintf(where, sizeof where, "%s.timed_renders[%zu]", path, i);
			return aa_error_set(err, AA_ERR_INVALID, where, "frame or repeat outside the job");
		}
		struct aa_timed_render *t = &m->timed[ordinal * repeat + r];
		const struct aa_frame_result *f = &m->frames[ordinal];
		*t = (struct aa_timed_render){.ordinal = ordinal, .repeat = r,
					      .position = (int)json_integer_value(json_object_get(item, "position")),
					      .gpu_ms = jnum(item, "gpu_ms"), .cpu_ms = jnum(item, "cpu_ms")};
		/* pass times are stored by the scored render's pass names, or not at all */
		const json_t *passes = json_object_get(item, "passes");
		if (json_object_size(passes) > 0) {
			t->pass_count = f->pass_count;
			for (int k = 0; k < f->pass_count; k++)
				t->pass_ms[k] = jnum(passes, f->passes[k].name);
		}
	}
	m->timed_count = frames * repeat;
	return 0;
}

int aa_results_from_json(const json_t *doc, const json_t *curves_per_method, struct aa_job_result *out,
			 struct aa_error *err)
{
	memset(out, 0, sizeof *out);
	if (json_object_get(doc, "cases"))
		return aa_error_set(err, AA_ERR_INVALID, "cases", "the results of a suite; expected those of one job");
	if (aa_job_spec_from_json(json_object_get(doc, "job"), &out->spec, err) < 0) {
		aa_error_prefix(err, "job");
		return -1;
	}
	const struct aa_job_spec *spec = &out->spec;
	const json_t *scene = json_object_get(doc, "scene"), *device = json_object_get(doc, "device"), *v, *item;
	size_t i;
	jstr(doc, "started_at", out->started_at, sizeof out->started_at);
	out->wall_seconds = jnum(doc, "wall_seconds");
	jstr(scene, "name", out->scene_name, sizeof out->scene_name);
	jstr(scene, "file", out->scene_file, sizeof out->scene_file);
	out->scene_triangles = (uint64_t)json_integer_value(json_object_get(scene, "triangles"));
	jstr(device, "name", out->device_name, sizeof out->device_name);
	jstr(device, "driver", out->driver_info, sizeof out->driver_info);
	out->timestamp_period_ns = jnum(device, "timestamp_period_ns");
	/* the scene's warnings, as written (code "scene"; a string in older files): "... and N more" stands for
	 * those not kept; the other warnings are computed again from the numbers */
	json_array_foreach(json_object_get(doc, "warnings"), i, item) {
		const char *code = json_string_value(json_object_get(item, "code"));
		const char *w = json_is_string(item) ? json_string_value(item) :
				code && (!strcmp(code, "scene") || !strcmp(code, "scene-warnings-capped")) ?
				json_string_value(json_object_get(item, "message")) : NULL;
		int more;
		if (!w)
			continue;
		if (sscanf(w, "... and %d more", &more) == 1)
			out->warnings_dropped = more;
		else if (out->warning_count < AA_MAX_WARNINGS)
			snprintf(out->warnings[out->warning_count++], sizeof out->warnings[0], "%s", w);
	}
	/* timing.repeat "auto" is written as the repeat it chose: the flag is in timing.auto */
	out->spec.timing_auto = json_is_true(json_object_get(json_object_get(doc, "timing"), "auto"));
	if (need_array(doc, "passes", "passes", &v, err))
		return -1;
	json_array_foreach(v, i, item) {
		if (i >= AA_MAX_PASSES)
			break;
		jstr(item, "pass", out->plan[i].pass, sizeof out->plan[i].pass);
		jstr(item, "reason", out->plan[i].reason, sizeof out->plan[i].reason);
		out->plan[i].ran = json_is_true(json_object_get(item, "ran"));
		out->plan_count = (int)i + 1;
	}

	const json_t *ref = json_object_get(doc, "reference");
	out->reference.samples = (int)json_integer_value(json_object_get(ref, "samples"));
	out->reference.auto_samples = !strcmp(json_string_value(json_object_get(ref, "mode")) ?
					      json_string_value(json_object_get(ref, "mode")) : "", "auto");
	out->reference.target_psnr = out->reference.auto_samples ?
					     json_number_value(json_object_get(ref, "target_psnr")) : NAN;
	jstr(ref, "pattern", out->reference.pattern, sizeof out->reference.pattern);
	out->reference.memory_bytes = (uint64_t)json_integer_value(json_object_get(ref, "memory_bytes"));
	if (need_array(ref, "per_frame", "reference.per_frame", &v, err))
		return -1;
	if ((int)json_array_size(v) != spec->frames)
		return aa_error_set(err, AA_ERR_INVALID, "reference.per_frame", "%zu frames; the job has %d",
				    json_array_size(v), spec->frames);
	out->reference.frames = calloc((size_t)spec->frames, sizeof *out->reference.frames);
	if (!out->reference.frames)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	json_array_foreach(v, i, item) {
		struct aa_reference_frame *f = &out->reference.frames[i];
		f->frame = (int)json_integer_value(json_object_get(item, "frame"));
		f->gpu_ms = jnum(item, "gpu_ms");
		f->cpu_ms = jnum(item, "cpu_ms");
		f->convergence_identical = json_is_true(json_object_get(item, "convergence_identical"));
		f->convergence_psnr = jnum(item, "convergence_psnr");
		f->convergence_mse = jnum(item, "convergence_mse");
		f->nonfinite = (long)json_integer_value(json_object_get(item, "nonfinite"));
		f->reused = json_is_true(json_object_get(item, "reused"));
		f->samples = (int)json_integer_value(json_object_get(item, "samples"));
		jstr(item, "cache", f->cache, sizeof f->cache);
	}
	out->reference.frame_count = spec->frames;
	const json_t *cache = json_object_get(ref, "cache");
	if (json_is_object(cache)) {
		struct aa_reference_cache_result *c = &out->reference.cache;
		c->used = true;
		c->hits = (int)json_integer_value(json_object_get(cache, "hits"));
		c->misses = (int)json_integer_value(json_object_get(cache, "misses"));
		c->continued = (int)json_integer_value(json_object_get(cache, "continued"));
		c->unkeyed = (int)json_integer_value(json_object_get(cache, "unkeyed"));
		c->bytes_read = (uint64_t)json_integer_value(json_object_get(cache, "bytes_read"));
		c->bytes_written = (uint64_t)json_integer_value(json_object_get(cache, "bytes_written"));
		c->discarded = (int)json_integer_value(json_object_get(cache, "discarded"));
		const json_t *w;
		size_t k;
		json_array_foreach(json_object_get(cache, "warnings"), k, w)
			if (c->warning_count < AA_REFERENCE_CACHE_WARNINGS)
				snprintf(c->warnings[c->warning_count++], sizeof c->warnings[0], "%s",
					 json_string_value(w) ? json_string_value(w) : "");
	}

	if (need_array(doc, "methods", "methods", &v, err))
		return -1;
	if ((int)json_array_size(v) != spec->method_count)
		return aa_error_set(err, AA_ERR_INVALID, "methods", "%zu methods; the job has %d", json_array_size(v),
				    spec->method_count);
	out->method_count = spec->method_count;
	json_array_foreach(v, i, item) {
		struct aa_method_result *m = &out->methods[i];
		const struct aa_method_spec *ms = &spec->methods[i];
		char path[64];
		snprintf(path, sizeof path, "methods[%zu]", i);
		jstr(item, "label", m->label, sizeof m->label);
		if (strcmp(m->label, ms->label) != 0)
			return aa_error_set(err, AA_ERR_INVALID, path, "label \"%s\"; the job has \"%s\"", m->label, ms->label);
		m->method = ms->method;
		m->params = ms->params;
		jstr(item, "path_taken", m->path_taken, sizeof m->path_taken);
		m->memory_bytes = (uint64_t)json_integer_value(json_object_get(item, "memory_bytes"));
		const json_t *mem = json_object_get(item, "memory"), *mi;
		size_t k;
		json_array_foreach(mem, k, mi) {
			if (k >= AA_MAX_MEMORY_ITEMS)
				break;
			jstr(mi, "name", m->memory[k].name, sizeof m->memory[k].name);
			m->memory[k].bytes = (uint64_t)json_integer_value(json_object_get(mi, "bytes"));
			m->memory_count = (int)k + 1;
		}
		if (read_frames(item, path, spec->first_frame, spec->frames, spec->timing_repeat, m, err))
			return -1;
		/* a shard's per-frame curves (aa_shard_results_write) replace the mean curve */
		const json_t *curves = json_array_get(curves_per_method, i);
		for (int k = 0; json_is_array(curves) && k < m->frame_count; k++) {
			const json_t *curve = json_array_get(curves, (size_t)k);
			for (int t = 0; json_array_size(curve) == AA_THRESHOLD_COUNT && t < AA_THRESHOLD_COUNT; t++)
				m->frames[k].metrics.exceed[t] = jnum_at(curve, t);
		}
	}
	return 0;
}
