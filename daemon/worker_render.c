/* Rendering one job with an engine and a scene cache: every case of a suite through aa_suite_run, the
 * results written under the job directory and each engine event handed to a sink. It runs in the worker
 * thread (worker.c) or in the worker process (worker_process.c); it knows neither. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "run/farm.h"
#include "jobs.h"
#include "methods/user_method.h"
#include "worker_job.h"
#include "loop.h"
#include "results/results.h"
#include "methods/methods.h"
#include "report/report.h"
#include "run/job_spec.h"

/* The engine side of a job: renders it into its directory and hands each event to a sink, the job's log
 * in this thread or the worker process's pipe to this thread (worker_process.c). */
struct render_ctx {
	const struct aa_job_spec *spec; /* the whole job: a suite's events name their case from it */
	const char *dir;
	struct scene_cache *scenes;
	bool inline_scene;
	long total;               /* units of work: per case frames x (1 + methods x repeats) */
	int done;                 /* frame events so far */
	const struct worker_sink *sink;
	int failed_writes;
	struct aa_error write_err;
};

/* JSON has no NaN or Infinity: undefined numbers are null. */
static json_t *num(double v)
{
	return isfinite(v) ? json_real(v) : json_null();
}

static json_t *started_event(const struct aa_job_result *r)
{
	json_t *plan = json_array(), *methods = json_array();
	for (int i = 0; i < r->plan_count; i++)
		json_array_append_new(plan, json_pack("{ss ss sb}", "pass", r->plan[i].pass, "reason",
						      r->plan[i].reason, "ran", r->plan[i].ran));
	json_t *alpha_rules = json_array(), *warnings = json_array();
	for (int i = 0; i < r->warning_count && i < AA_MAX_WARNINGS; i++)
		json_array_append_new(warnings, json_string(r->warnings[i]));
	for (int i = 0; i < r->method_count; i++) {
		json_array_append_new(methods, json_string(r->methods[i].label));
		json_array_append_new(alpha_rules, json_string(aa_alpha_rule_name(
			aa_method_alpha_rule(r->methods[i].method, &r->methods[i].params))));
	}
	return json_pack("{ss ss ss so so so so si si si si}", "event", "job_started", "scene", r->scene_name, "device",
			 r->device_name, "plan", plan, "methods", methods, "alpha_rules", alpha_rules, "warnings", warnings,
			 "frames", r->spec.frames, "width", r->spec.width, "height", r->spec.height, "repeat",
			 r->spec.timing_repeat);
}

/* A suite's events name their case; its images live in the case's folder (cases/NAME/...). */
static void add_case(const struct aa_job_spec *spec, const struct aa_event *ev, json_t *o)
{
	if (!spec->is_suite)
		return;
	char id[512];
	aa_case_id(spec, ev->case_index, id, sizeof id);
	json_object_set_new(o, "case", json_string(id));
	json_object_set_new(o, "case_index", json_integer(ev->case_index));
	if (ev->type != AA_EVENT_JOB_STARTED && ev->result) { /* the case's size: raw frames streamed need it */
		json_object_set_new(o, "width", json_integer(ev->result->spec.width));
		json_object_set_new(o, "height", json_integer(ev->result->spec.height));
	}
	if (ev->type == AA_EVENT_JOB_STARTED)
		json_object_set_new(o, "cases", json_integer(spec->case_count));
}

static void case_path(const struct aa_job_spec *spec, const struct aa_event *ev, char *rel, size_t size)
{
	char dir[600], inner[512];
	aa_case_relpath(spec, ev->case_index, dir, sizeof dir);
	if (!dir[0])
		return;
	snprintf(inner, sizeof inner, "%s", rel);
	snprintf(rel, size, "%s/%s", dir, inner);
}

static json_t *frame_event(struct render_ctx *ctx, const struct aa_event *ev)
{
	char rel[1200];
	json_t *o;
	bool images = ctx->spec->keep_frames;
	if (ev->type == AA_EVENT_REFERENCE_FRAME) {
		const struct aa_reference_frame *rf = &ev->result->reference.frames[ev->frame_ordinal];
		o = json_pack("{ss ss si si sf so}", "event", "reference_frame", "method", "reference", "frame",
			      ev->frame, "ordinal", ev->frame_ordinal, "gpu_ms", rf->gpu_ms, "convergence_psnr",
			      num(rf->convergence_psnr));
		aa_results_frame_relpath("frames", "reference", ev->frame_ordinal, rel, sizeof rel);
	} else {
		const struct aa_method_result *m = &ev->result->methods[ev->method_index];
		const struct aa_frame_result *fr = &m->frames[ev->frame_ordinal];
		json_t *passes = json_array();
		for (int i = 0; i < fr->pass_count; i++)
			json_array_append_new(passes, json_pack("{ss so}", "name", fr->passes[i].name, "gpu_ms",
								num(fr->passes[i].gpu_ms)));
		/* the scored render; its place in the frame's rotating method order (re-timings follow it and
		 * reach the client in results.json) */
		int position = m->timed ? m->timed[ev->frame_ordinal * ev->result->spec.timing_repeat].position : 0;
		o = json_pack("{ss ss si si si so so so s{so sb so so}}", "event", "method_frame", "method", m->label,
			      "frame", ev->frame, "ordinal", ev->frame_ordinal, "position", position, "gpu_ms",
			      num(fr->gpu_ms), "cpu_ms", num(fr->cpu_ms), "passes", passes, "metrics", "psnr",
			      num(fr->metrics.psnr), "identical", fr->metrics.identical, "ssim", num(fr->metrics.ssim),
			      "mse", num(fr->metrics.mse));
		aa_results_frame_relpath("frames", m->label, ev->frame_ordinal, rel, sizeof rel);
		if (images) {
			char diff[1200];
			aa_results_frame_relpath("diff", m->label, ev->frame_ordinal, diff, sizeof diff);
			case_path(ctx->spec, ev, diff, sizeof diff);
			json_object_set_new(o, "diff", json_string(diff));
		}
	}
	case_path(ctx->spec, ev, rel, sizeof rel);
	add_case(ctx->spec, ev, o);
	if (images)
		json_object_set_new(o, "image", json_string(rel));
	const char *label = ev->type == AA_EVENT_REFERENCE_FRAME ? "reference" : ev->result->methods[ev->method_index].label;
	if (images && ctx->spec->linear_frames) {
		aa_results_linear_relpath(label, ev->frame_ordinal, rel, sizeof rel);
		case_path(ctx->spec, ev, rel, sizeof rel);
		json_object_set_new(o, "linear", json_string(rel));
	}
	if (images && ctx->spec->exr_frames) {
		aa_results_exr_relpath(label, ev->frame_ordinal, rel, sizeof rel);
		case_path(ctx->spec, ev, rel, sizeof rel);
		json_object_set_new(o, "exr", json_string(rel));
	}
	json_object_set_new(o, "done", json_integer(++ctx->done));
	json_object_set_new(o, "total", json_integer(ctx->total));
	return o;
}

static int on_event(const struct aa_event *ev, void *user)
{
	struct render_ctx *ctx = user;
	const struct worker_sink *sink = ctx->sink;
	switch (ev->type) {
	case AA_EVENT_JOB_STARTED: {
		json_t *o = started_event(ev->result);
		add_case(ctx->spec, ev, o);
		return sink->event(sink->ctx, o);
	}
	case AA_EVENT_REFERENCE_FRAME:
	case AA_EVENT_METHOD_FRAME:
		if (ctx->spec->keep_frames && aa_suite_write_event_images(ctx->dir, ctx->spec, ev, &ctx->write_err)) {
			ctx->failed_writes++;
			return 1; /* stored results must be complete; a failed write fails the job */
		}
		return sink->event(sink->ctx, frame_event(ctx, ev));
	case AA_EVENT_PROGRESS:
		return sink->progress(sink->ctx, ev->done, ev->total);
	default:
		return 0;
	}
}

/* Per-method cost and accuracy, the numbers a dashboard plots: taken from results.json's methods (for a
 * suite, of every case, each entry naming its case). */
static void summarize_case(json_t *out, json_t *doc, const char *case_id)
{
	json_t *m;
	size_t i;
	json_array_foreach(json_object_get(doc, "methods"), i, m) {
		json_t *metrics = json_object_get(m, "metrics"), *gpu = json_object_get(m, "gpu_ms");
		json_t *e = json_pack("{sO sO sO sO sO sO sO sO sO}", "label", json_object_get(m, "label"),
			"gpu_ms", json_object_get(gpu, "median"), "gpu_ms_p10", json_object_get(gpu, "p10"),
			"gpu_ms_p90", json_object_get(gpu, "p90"), "gpu_ms_n", json_object_get(gpu, "n"),
			"memory_bytes", json_object_get(m, "memory_bytes"),
			"psnr", json_object_get(json_object_get(metrics, "psnr"), "mean"),
			"ssim", json_object_get(json_object_get(metrics, "ssim"), "mean"),
			"alpha_rule", json_object_get(m, "alpha_rule"));
		/* what trends plot besides (/v1/series) */
		json_object_set(e, "flip", json_object_get(json_object_get(metrics, "flip"), "mean"));
		json_object_set(e, "flicker", json_object_get(json_object_get(metrics, "flicker"), "mean"));
		if (case_id)
			json_object_set_new(e, "case", json_string(case_id));
		json_array_append_new(out, e);
	}
}

static json_t *summarize(const json_t *results)
{
	json_t *out = json_array(), *c;
	size_t i;
	json_t *cases = json_object_get(results, "cases");
	if (!cases)
		summarize_case(out, (json_t *)results, NULL);
	json_array_foreach(cases, i, c)
		summarize_case(out, c, json_string_value(json_object_get(c, "id")));
	return out;
}

static const struct aa_scene *find_scene(struct scene_cache *scenes, const char *scene_name, bool inline_scene,
					 const char *dir, char *file, size_t size, struct aa_error *err)
{
	if (!inline_scene) {
		if (aa_scene_resolve(scene_name, file, size, err))
			return NULL;
	} else if ((size_t)snprintf(file, size, "%s/scene.json", dir) >= size) {
		aa_error_set(err, AA_ERR_IO, "", "state directory path too long");
		return NULL;
	}
	/* errors name the file as found in its scene folder (names have no '/'), or the scene sent with the job,
	 * never by a path of the server's (docs/aalabd.8, SCENES) */
	const char *base = strrchr(file, '/');
	return scene_cache_get(scenes, file, inline_scene ? "scene.json (sent with the job)" : base ? base + 1 : file, err);
}

/* Each case's scene, from the scene cache (aa_suite_run asks once per case). */
static const struct aa_scene *case_scene(const struct aa_job_spec *c, void *user, struct aa_error *err)
{
	struct render_ctx *ctx = user;
	char file[1400];
	return find_scene(ctx->scenes, c->scene, ctx->inline_scene, ctx->dir, file, sizeof file, err);
}

void worker_render(struct aa_engine *engine, struct scene_cache *scenes, const struct aa_job_spec *spec,
		   bool inline_scene, const char *dir, const struct worker_sink *sink, struct worker_outcome *out)
{
	struct render_ctx ctx = {.spec = spec, .dir = dir, .scenes = scenes, .inline_scene = inline_scene,
				 .sink = sink, .total = aa_suite_total_units(spec)};
	char file[1400] = "";
	memset(out, 0, sizeof *out);
	struct aa_suite_result *result = NULL;
	double t0 = worker_now_s();
	int rc = aa_suite_run(engine, spec, case_scene, &ctx, on_event, &ctx, &result, &out->err);
	out->busy = worker_now_s() - t0;
	if (rc && ctx.failed_writes)
		out->err = ctx.write_err;
	if (rc == 0) {
		/* the scenes came from the cache: say which file each case used */
		for (int i = 0; i < result->case_count; i++) {
			struct aa_error ignored = {0};
			if (inline_scene)
				snprintf(file, sizeof file, "scene.json");
			else if (aa_scene_resolve(result->cases[i]->spec.scene, file, sizeof file, &ignored))
				file[0] = '\0';
			snprintf(result->cases[i]->scene_file, sizeof result->cases[i]->scene_file, "%.1000s", file);
		}
		json_t *results = aa_suite_results_to_json(result);
		out->summary = summarize(results);
		json_decref(results);
		if (aa_suite_results_write(result, dir, &out->err))
			rc = -1;
	}
	aa_suite_result_free(result);
	out->rc = rc;
	out->failed_writes = ctx.failed_writes;
}
