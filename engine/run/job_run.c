/* Runs a job: for every frame on the camera path, the reference, then every method, then metrics against
 * the reference, reported as events (docs/architecture.md, "One job"). The scoring of a frame and its
 * events run beside the next frame's reference (run/frame_scoring.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "run/engine.h"
#include "render/debug_targets.h"
#include "run/engine_internal.h"
#include "render/frame_plan.h"
#include "reference/reference.h"
#include "reference/reference_store.h"
#include "render/renderer.h"
#include "methods/methods.h"
#include "run/frame_scoring.h"

static float half_to_float(uint16_t h)
{
	uint32_t sign = (uint32_t)(h >> 15) << 31, exp = (h >> 10) & 0x1f, mant = h & 0x3ff, bits;
	if (exp == 0) {
		if (mant == 0) {
			bits = sign;
		} else { /* subnormal: normalise */
			exp = 127 - 15 + 1;
			while (!(mant & 0x400)) {
				mant <<= 1;
				exp--;
			}
			bits = sign | (exp << 23) | ((mant & 0x3ff) << 13);
		}
	} else if (exp == 31) {
		bits = sign | 0x7f800000u | (mant << 13);
	} else {
		bits = sign | ((exp - 15 + 127) << 23) | (mant << 13);
	}
	float f;
	memcpy(&f, &bits, sizeof f);
	return f;
}

struct job_state {
	struct aa_engine *engine;
	const struct aa_job_spec *spec;
	struct aa_scene *scene;          /* loaded here, freed at the end */
	const struct aa_scene *borrowed; /* or given by the caller */
	struct aa_renderer *renderer;
	struct aa_reference reference;
	struct aa_reference_store store; /* the engine's store of references, if it has one */
	struct aa_method_state *states[AA_MAX_METHODS];
	/* timing.repeat > 1: a second instance of each method with history, never scored, that re-times its
	 * frames so that the scored instance's history advances exactly once per frame */
	struct aa_method_state *twins[AA_MAX_METHODS];
	struct aa_gpu_timer timer;
	struct aa_gpu_buffer readback;
	struct aa_image_rgbaf full, half;
	struct aa_image_rgba8 ref8, half8;
	struct aa_scoring *scoring;      /* scores each frame and emits its events beside the rendering */
	struct aa_scoring_frame *scored; /* the frame being filled for it */
	struct aa_job_result *result;
	struct aa_debug_targets *debug_targets; /* job option debug_targets, else NULL */
};

static void job_state_free(struct job_state *js)
{
	for (int i = 0; i < js->spec->method_count; i++) {
		if (js->states[i])
			js->spec->methods[i].method->destroy(js->states[i]);
		if (js->twins[i])
			js->spec->methods[i].method->destroy(js->twins[i]);
	}
	aa_reference_destroy(&js->reference);
	if (js->renderer)
		js->renderer->debug_targets = NULL;
	aa_debug_targets_destroy(js->debug_targets);
	if (js->renderer) {
		aa_gpu_buffer_destroy(&js->engine->gpu, &js->readback);
		aa_gpu_timer_destroy(&js->engine->gpu, &js->timer);
	}
	aa_engine_renderer_release(js->engine, js->renderer); /* kept, with its pipelines, for the next job */
	if (!js->borrowed)
		aa_scene_free(js->scene);
	aa_image_rgbaf_free(&js->full);
	aa_image_rgbaf_free(&js->half);
	aa_image_rgba8_free(&js->ref8);
	aa_image_rgba8_free(&js->half8);
}

static int emit(aa_event_fn fn, void *user, struct aa_event *ev, struct aa_error *err)
{
	if (fn && fn(ev, user))
		return aa_error_set(err, AA_ERR_CANCELLED, "", "the job was cancelled");
	return 0;
}

static bool has_history(const struct aa_method_spec *ms)
{
	unsigned needs = ms->method->needs_fn ? ms->method->needs_fn(&ms->params) : ms->method->needs;
	return (needs & AA_NEED_HISTORY) != 0;
}

static int setup(struct job_state *js, struct aa_error *err)
{
	const struct aa_job_spec *spec = js->spec;
	struct aa_job_result *res = js->result;
	char file[1024] = "";
	struct aa_gpu *gpu = &js->engine->gpu;
	/* the set-up is cut at its steps too (the scene's load, its upload and targets, each method's
	 * creation): a cancel waits for one step, not for all of them */
	if (aa_gpu_interrupted(gpu, err))
		return -1; /* before the scene is even looked up */
	if (js->borrowed) {
		js->scene = (struct aa_scene *)js->borrowed;
	} else if (aa_scene_resolve(spec->scene, file, sizeof file, err) ||
		   aa_scene_load(file, &js->scene, err)) {
		return -1;
	}
	if (!aa_scene_find_path(js->scene, spec->path)) {
		char names[512] = "default, static";
		for (int i = 0; i < js->scene->path_count; i++) {
			size_t len = strlen(names);
			snprintf(names + len, sizeof names - len, ", %s", js->scene->paths[i].name);
		}
		return aa_error_set(err, AA_ERR_NOT_FOUND, "path", "scene '%s' has no camera path '%s' (paths: %s)",
				    js->scene->name, spec->path, names);
	}
	struct aa_frame_plan plan;
	aa_frame_plan_build(js->scene, spec, &plan);
	struct aa_scene_upload *upload = NULL;
	if (aa_gpu_interrupted(gpu, err) || !(upload = aa_engine_scene_upload(js->engine, js->scene, err)) ||
	    aa_gpu_interrupted(gpu, err) ||
	    aa_engine_renderer(js->engine, js->scene, upload, &plan, spec->width, spec->height, &js->renderer, err) ||
	    aa_gpu_timer_create(gpu, &js->timer, err) ||
	    aa_reference_create(js->renderer, spec->reference_samples, &js->reference, err))
		return -1;
	/* after the reference: only the methods' images are entered, each under its method's index */
	if (spec->debug_targets) {
		if (aa_debug_targets_create(gpu, &js->debug_targets, err))
			return -1;
		js->renderer->debug_targets = js->debug_targets;
	}

	res->spec = *spec;
	snprintf(res->scene_name, sizeof res->scene_name, "%s", js->scene->name);
	snprintf(res->scene_file, sizeof res->scene_file, "%s", file);
	res->scene_triangles = aa_scene_triangle_count(js->scene);
	snprintf(res->device_name, sizeof res->device_name, "%s", gpu->properties.deviceName);
	snprintf(res->driver_info, sizeof res->driver_info, "%s", gpu->driver_info);
	res->timestamp_period_ns = gpu->timestamp_period_ns;
	res->plan_count = plan.entry_count;
	memcpy(res->plan, plan.entries, sizeof plan.entries);
	_Static_assert(AA_MAX_WARNINGS == AA_SCENE_MAX_WARNINGS, "the scene's warnings fit the result");
	res->warning_count = js->scene->warning_count;
	res->warnings_dropped = js->scene->warnings_dropped;
	memcpy(res->warnings, js->scene->warnings, sizeof res->warnings);
	res->reference.samples = spec->reference_samples;
	res->reference.auto_samples = spec->reference_auto;
	res->reference.target_psnr = spec->reference_auto ? spec->reference_target_psnr : NAN;
	snprintf(res->reference.pattern, sizeof res->reference.pattern, "%s", AA_REFERENCE_PATTERN);
	/* a frame with injected NaN (tests) is not the reference its key names */
	aa_reference_store_job(&js->store, spec->inject_nonfinite_frame < 0 ? js->engine->reference_cache : NULL,
			       spec->reference_verify, spec->explain_key, &res->reference.cache, res->reference.pattern,
			       js->scene->file, spec->path, spec->width, spec->height, spec->reference_samples,
			       spec->reference_auto);
	res->reference.memory_bytes = js->reference.memory_bytes;
	res->reference.frames = calloc((size_t)spec->frames, sizeof *res->reference.frames);
	if (!res->reference.frames)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	res->method_count = spec->method_count;
	for (int i = 0; i < spec->method_count; i++) {
		struct aa_method_result *m = &res->methods[i];
		const struct aa_method_spec *ms = &spec->methods[i];
		snprintf(m->label, sizeof m->label, "%s", ms->label);
		m->method = ms->method;
		m->params = ms->params;
		m->frames = calloc((size_t)spec->frames, sizeof *m->frames);
		m->timed = calloc((size_t)spec->frames * (size_t)spec->timing_repeat, sizeof *m->timed);
		if (!m->frames || !m->timed)
			return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
		if (aa_gpu_interrupted(gpu, err))
			return -1;
		if (js->debug_targets)
			js->debug_targets->owner = i;
		int failed_create = aa_method_create(ms->method, js->renderer, &ms->params, m, &js->states[i], err);
		if (js->debug_targets)
			js->debug_targets->owner = -1; /* the twin's images are never read back */
		if (failed_create) {
			aa_error_prefix(err, "%s", ms->label);
			if (!err->path[0]) /* the job field at fault (a user method's shader that does not compile) */
				snprintf(err->path, sizeof err->path, "methods[%d]", i);
			return -1;
		}
		if (spec->timing_repeat > 1 && has_history(ms)) {
			if (aa_gpu_interrupted(gpu, err))
				return -1;
			struct aa_method_result *scratch = calloc(1, sizeof *scratch); /* its memory is not the method's */
			int failed = !scratch ||
				     aa_method_create(ms->method, js->renderer, &ms->params, scratch, &js->twins[i], err);
			free(scratch);
			if (failed) {
				if (!scratch)
					aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
				aa_error_prefix(err, "%s (the instance that re-times frames)", ms->label);
				return -1;
			}
		}
	}
	int w = spec->width, h = spec->height;
	if (aa_image_rgbaf_alloc(&js->full, w, h) || aa_image_rgbaf_alloc(&js->half, w, h) ||
	    aa_image_rgba8_alloc(&js->ref8, w, h) || aa_image_rgba8_alloc(&js->half8, w, h))
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory for %dx%d images", w, h);
	return 0;
}

static int render_reference(struct job_state *js, int ordinal, bool reuse, const struct aa_frame_ctx *ctx,
			    struct aa_error *err)
{
	struct aa_reference_frame *rf = &js->result->reference.frames[ordinal];
	if (reuse) {
		/* a held camera over a scene where nothing moves: every frame's reference is the first one */
		*rf = js->result->reference.frames[0];
		rf->frame = js->spec->first_frame + ordinal;
		rf->reused = true;
		js->result->reference.frame_count = ordinal + 1;
		return 0;
	}
	rf->frame = js->spec->first_frame + ordinal;
	if (aa_gpu_interrupted(&js->engine->gpu, err))
		return -1;
	struct aa_metrics m;
	aa_reference_store_frame(&js->store, &js->reference, ctx);
	if (js->spec->reference_auto) {
		if (aa_reference_render_auto(&js->reference, &js->timer, js->spec->reference_target_psnr, &js->full,
					     &js->half, &js->ref8, &js->half8, &rf->samples, &m, &rf->gpu_ms,
					     &rf->cpu_ms, &js->store, err))
			return -1;
		rf->nonfinite = aa_count_nonfinite(&js->full) + aa_count_nonfinite(&js->half);
	} else {
		/* the store's entry when it has one, else rendered and stored */
		if (!aa_reference_store_load(&js->store, &js->reference, &js->full, &js->half, &rf->gpu_ms, &rf->cpu_ms)) {
			if (aa_reference_render(&js->reference, &js->timer, &js->full, &js->half, &rf->gpu_ms,
						&rf->cpu_ms, err))
				return -1;
			aa_reference_store_save(&js->store, &js->reference, rf->gpu_ms, rf->cpu_ms);
		}
		rf->samples = js->spec->reference_samples;
		rf->nonfinite = aa_count_nonfinite(&js->full) + aa_count_nonfinite(&js->half);
		aa_image_encode_srgb8(&js->full, &js->ref8);
		aa_image_encode_srgb8(&js->half, &js->half8);
		if (aa_metrics_compare_pixels(&js->ref8, &js->half8, &m, err)) /* its MSE: no SSIM is reported */
			return -1;
	}
	rf->convergence_mse = m.mse;
	rf->convergence_psnr = m.psnr;
	rf->convergence_identical = m.identical;
	aa_reference_store_frame_done(&js->store, rf->cache, sizeof rf->cache);
	js->result->reference.frame_count = ordinal + 1;
	return 0;
}

/* One untimed frame of every method before timing starts: lavapipe compiles shader variants on first use,
 * which would otherwise be charged to the first frame (hundreds of ms). History is reset afterwards. */
static int warm_up(struct job_state *js, struct aa_frame_ctx *ctx, struct aa_error *err)
{
	struct aa_gpu *gpu = &js->engine->gpu;
	for (int k = 0; k < 2 * js->spec->method_count; k++) {
		int i = k % js->spec->method_count;
		struct aa_method_state *state = k < js->spec->method_count ? js->states[i] : js->twins[i];
		if (!state)
			continue;
		const struct aa_method *method = js->spec->methods[i].method;
		struct aa_frame_ctx warm = *ctx;
		if (aa_gpu_interrupted(gpu, err) || aa_gpu_begin(gpu, &warm.cmd, err))
			return -1;
		aa_gpu_timer_reset(warm.cmd, &js->timer);
		aa_renderer_record_shadow(js->renderer, warm.cmd);
		warm.timer = &js->timer;
		if (method->render(state, &warm, err)) {
			aa_gpu_submit_wait(gpu, warm.cmd, NULL);
			aa_error_prefix(err, "%s", js->spec->methods[i].label);
			return -1;
		}
		if (aa_gpu_submit_wait(gpu, warm.cmd, err))
			return -1;
		if (method->reset)
			method->reset(state);
	}
	return 0;
}

/* Records one frame of a method into a command buffer (shadow map, its passes, the readback of its
 * output), submits it and waits; fills t with the wall time and each pass's GPU time. The same for a
 * scored render and a repeat, so that both are timed alike. */
static int timed_render(struct job_state *js, int i, struct aa_method_state *state, struct aa_frame_ctx *ctx,
			struct aa_timed_render *t, struct aa_error *err)
{
	struct aa_gpu *gpu = &js->engine->gpu;
	const struct aa_method *method = js->spec->methods[i].method;
	double t0 = aa_now_ms();
	if (ctx->cut && method->reset)
		method->reset(state);
	/* a job asked to stop does so between renders: each is one bounded piece of GPU work */
	if (aa_gpu_interrupted(gpu, err) || aa_gpu_begin(gpu, &ctx->cmd, err))
		return -1;
	aa_gpu_timer_reset(ctx->cmd, &js->timer);
	if (js->renderer->plan.shadow_map) {
		/* every method pays for the shadow map it uses, as it would in an engine */
		int span = aa_gpu_timer_begin(ctx->cmd, &js->timer, "shadow-map");
		aa_renderer_record_shadow(js->renderer, ctx->cmd);
		aa_gpu_timer_end(ctx->cmd, &js->timer, span);
	}
	ctx->timer = &js->timer;
	ctx->output = NULL;
	if (js->debug_targets) /* an image a method makes while rendering is entered too (not the twin's) */
		js->debug_targets->owner = state == js->states[i] ? i : -1;
	int failed_render = method->render(state, ctx, err);
	if (js->debug_targets)
		js->debug_targets->owner = -1;
	if (failed_render || !ctx->output || ctx->output->width != ctx->width ||
	    ctx->output->height != ctx->height ||
	    (ctx->output->format != VK_FORMAT_R16G16B16A16_SFLOAT &&
	     ctx->output->format != VK_FORMAT_R32G32B32A32_SFLOAT) ||
	    aa_gpu_record_readback(gpu, ctx->cmd, ctx->output, &js->readback, err)) {
		aa_gpu_submit_wait(gpu, ctx->cmd, NULL);
		if (!err->message[0])
			aa_error_set(err, AA_ERR_INTERNAL, "", "%s produced no frame-sized RGBA16F/RGBA32F output",
				     method->name);
		aa_error_prefix(err, "%s", js->spec->methods[i].label);
		return -1;
	}
	if (aa_gpu_submit_wait(gpu, ctx->cmd, err))
		return -1;
	t->cpu_ms = aa_now_ms() - t0;
	double ms[AA_GPU_TIMER_MAX / 2];
	if (aa_gpu_timer_read(gpu, &js->timer, ms, err))
		return -1;
	t->pass_count = js->timer.span_count < AA_MAX_PASSES ? js->timer.span_count : AA_MAX_PASSES;
	t->gpu_ms = 0;
	for (int s = 0; s < t->pass_count; s++) {
		t->pass_ms[s] = ms[s];
		t->gpu_ms += ms[s];
	}
	return 0;
}

/* Repeat r (1..) of method i's frame: timed like the scored render, never scored. A method with
 * history re-times on its twin, reset whenever the scored instance is, so the scored history never
 * sees a frame twice (docs/methods.md, "Timing"). */
static int retime_method(struct job_state *js, int i, struct aa_frame_ctx *ctx, int r, int position,
			 struct aa_error *err)
{
	struct aa_method_result *m = &js->result->methods[i];
	struct aa_timed_render *t = &m->timed[ctx->ordinal * js->spec->timing_repeat + r];
	*t = (struct aa_timed_render){.ordinal = ctx->ordinal, .repeat = r, .position = position};
	struct aa_method_state *state = js->twins[i] ? js->twins[i] : js->states[i];
	if (timed_render(js, i, state, ctx, t, err))
		return -1;
	/* pass times are kept by the scored render's pass names; a different list keeps only the total */
	const struct aa_frame_result *fr = &m->frames[ctx->ordinal];
	bool same = t->pass_count == fr->pass_count;
	for (int k = 0; same && k < t->pass_count; k++)
		same = strcmp(js->timer.spans[k].name, fr->passes[k].name) == 0;
	if (!same)
		t->pass_count = 0;
	m->timed_count = ctx->ordinal * js->spec->timing_repeat + r + 1;
	return 0;
}

/* The scored render of method i's frame (repeat 0): timed, read back and compared with the reference. */
static int render_method(struct job_state *js, int i, struct aa_frame_ctx *ctx, int position, struct aa_error *err)
{
	struct aa_method_result *mr = &js->result->methods[i];
	struct aa_frame_result *fr = &mr->frames[ctx->ordinal];
	struct aa_timed_render *t = &mr->timed[ctx->ordinal * js->spec->timing_repeat];
	*t = (struct aa_timed_render){.ordinal = ctx->ordinal, .repeat = 0, .position = position};
	if (timed_render(js, i, js->states[i], ctx, t, err))
		return -1;
	/* after the timed submission, in its own: the readback never shows in the method's times */
	if (aa_debug_targets_check(js->debug_targets, i, fr, err)) {
		aa_error_prefix(err, "%s (debug_targets readback)", js->spec->methods[i].label);
		return -1;
	}
	mr->timed_count = ctx->ordinal * js->spec->timing_repeat + 1;
	fr->cpu_ms = t->cpu_ms;
	fr->frame = ctx->frame;
	fr->pass_count = t->pass_count;
	fr->gpu_ms = t->gpu_ms;
	for (int s = 0; s < fr->pass_count; s++) {
		snprintf(fr->passes[s].name, sizeof fr->passes[s].name, "%s", js->timer.spans[s].name);
		fr->passes[s].gpu_ms = t->pass_ms[s];
	}
	/* the scoring (metrics, difference and FLIP images, events) runs beside the next frame's reference */
	struct aa_image_rgbaf *output = &js->scored->outputs[i];
	size_t n = (size_t)ctx->width * ctx->height * 4;
	if (ctx->output->format == VK_FORMAT_R32G32B32A32_SFLOAT) {
		memcpy(output->pixels, js->readback.mapped, n * sizeof(float));
	} else {
		const uint16_t *half = js->readback.mapped;
		for (size_t k = 0; k < n; k++)
			output->pixels[k] = half_to_float(half[k]);
	}
	return 0;
}

/* A shard's warm-up frame (docs/farm.md, "Warm-up"): each method with history renders it so that its
 * history at the shard's first scored frame is close to the unsharded run's; methods without history,
 * the reference and the metrics skip it, and nothing of it is kept. */
static int shard_warmup_frame(struct job_state *js, struct aa_frame_ctx *ctx, struct aa_error *err)
{
	for (int i = 0; i < js->spec->method_count; i++) {
		if (!has_history(&js->spec->methods[i]))
			continue;
		struct aa_frame_ctx c = *ctx;
		struct aa_timed_render unused = {0};
		if (timed_render(js, i, js->states[i], &c, &unused, err))
			return -1;
	}
	return 0;
}

int aa_job_run(struct aa_engine *engine, const struct aa_job_spec *spec, aa_event_fn on_event, void *user,
	       struct aa_job_result **result, struct aa_error *err)
{
	return aa_job_run_scene(engine, spec, NULL, on_event, user, result, err);
}

int aa_job_run_scene(struct aa_engine *engine, const struct aa_job_spec *spec, const struct aa_scene *scene,
		     aa_event_fn on_event, void *user, struct aa_job_result **result, struct aa_error *err)
{
	double t_start = aa_now_ms();
	struct job_state js = {.engine = engine, .spec = spec, .borrowed = scene};
	js.result = calloc(1, sizeof *js.result);
	if (!js.result)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	time_t now = time(NULL);
	struct tm tm;
	gmtime_r(&now, &tm);
	strftime(js.result->started_at, sizeof js.result->started_at, "%Y-%m-%dT%H:%M:%SZ", &tm);

	int rc = setup(&js, err);
	struct aa_event ev = {.type = AA_EVENT_JOB_STARTED, .result = js.result};
	if (rc == 0)
		rc = emit(on_event, user, &ev, err);
	if (rc == 0)
		rc = aa_scoring_create(spec, js.result, on_event, user, false, &js.scoring, err);
	const struct aa_camera_path *path = rc == 0 ? aa_scene_find_path(js.scene, spec->path) : NULL;
	bool hold_first = strcmp(spec->path, "static") == 0;
	bool still = hold_first && js.scene && !aa_scene_has_animation(js.scene) && spec->inject_nonfinite_frame < 0;
	double fps = js.scene && js.scene->fps > 0 ? js.scene->fps : 30.0;
	if (js.result)
		js.result->fps = fps;
	/* a shard's warm-up frames come first, at negative ordinals: history only (shard_warmup_frame) */
	const int start = -spec->warmup_frames;
	for (int ordinal = start; rc == 0 && ordinal < spec->frames; ordinal++) {
		struct aa_frame_ctx ctx = {.ordinal = ordinal, .frame = spec->first_frame + ordinal};
		double t = ctx.frame / fps, t_before = (ctx.frame - 1) / fps;
		struct aa_camera cam, prev_cam;
		/* a cut between the previous frame on the path and this one, even when this is the job's
		 * first frame: velocity must not be measured across it */
		bool path_cut = false, unused = false;
		aa_camera_path_eval(path, hold_first, ctx.frame > 0 ? t_before : -1.0, t, &cam, &path_cut);
		aa_camera_path_eval(path, hold_first, -1.0, t_before, &prev_cam, &unused);
		ctx.cut = path_cut || ordinal == start; /* history starts empty at the first frame */
		bool has_prev = ctx.frame > 0 && !path_cut;
		js.renderer->inject_nonfinite = ctx.frame == spec->inject_nonfinite_frame;
		aa_renderer_set_frame(js.renderer, &cam, t, has_prev ? &prev_cam : NULL, t_before, &ctx);

		if (ordinal == start)
			rc = warm_up(&js, &ctx, err);
		if (ordinal < 0) {
			if (rc == 0)
				rc = shard_warmup_frame(&js, &ctx, err);
			continue;
		}
		/* the reference runs beside the scoring of the frame before; no method is timed before that
		 * scoring has ended (aa_scoring_wait) */
		if (rc == 0)
			rc = render_reference(&js, ordinal, ordinal > 0 && still, &ctx, err);
		if (rc == 0)
			rc = aa_scoring_wait(js.scoring, err);
		if (rc == 0) {
			js.scored = aa_scoring_next(js.scoring);
			js.scored->ordinal = ordinal;
			js.scored->frame = ctx.frame;
			memcpy(js.scored->full.pixels, js.full.pixels, (size_t)js.full.width * js.full.height * 4 * sizeof(float));
			memcpy(js.scored->ref8.pixels, js.ref8.pixels, (size_t)js.ref8.width * js.ref8.height * 4);
			if (spec->explain_key)
				snprintf(js.scored->key_text, sizeof js.scored->key_text, "%s", js.store.explanation);
		}
		/* Methods interleave frame by frame, each round in an order rotated by one, so that no method
		 * always runs first after the reference (or after any other); round 0 is scored, the rest
		 * re-time (timing.repeat). */
		const int count = spec->method_count, repeat = spec->timing_repeat;
		for (int round = 0; rc == 0 && round < repeat; round++) {
			const int first = (int)(((long)(spec->order_ordinal + ordinal) * repeat + round) % count);
			for (int position = 0; rc == 0 && position < count; position++) {
				const int i = (first + position) % count;
				if (round > 0) {
					rc = retime_method(&js, i, &ctx, round, position, err);
				} else {
					rc = render_method(&js, i, &ctx, position, err);
					js.scored->order[position] = i;
				}
			}
		}
		if (rc == 0) /* scored, and its events emitted, while the next frame's reference is made */
			rc = aa_scoring_submit(js.scoring, js.scored, err);
	}
	if (rc == 0 && js.scoring)
		rc = aa_scoring_wait(js.scoring, err);
	aa_scoring_destroy(js.scoring);
	js.scoring = NULL;
	js.result->wall_seconds = (aa_now_ms() - t_start) / 1000.0;
	if (rc == 0) {
		ev = (struct aa_event){.type = AA_EVENT_JOB_FINISHED, .result = js.result};
		rc = emit(on_event, user, &ev, err);
	}
	job_state_free(&js);
	if (rc != 0) {
		aa_job_result_free(js.result);
		free(js.result);
		return -1;
	}
	*result = js.result;
	return 0;
}

void aa_job_result_free(struct aa_job_result *r)
{
	if (!r)
		return;
	for (int i = 0; i < r->method_count && i < AA_MAX_METHODS; i++) {
		free(r->methods[i].frames);
		r->methods[i].frames = NULL;
		r->methods[i].frame_count = 0;
		free(r->methods[i].timed);
		r->methods[i].timed = NULL;
		r->methods[i].timed_count = 0;
	}
	free(r->reference.frames);
	r->reference.frames = NULL;
	r->reference.frame_count = 0;
}
