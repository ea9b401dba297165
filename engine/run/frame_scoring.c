/* The scorer of a job's frames (frame_scoring.h): one thread that takes the frames in order, scores
 * their methods (two at once, on a helper thread, when a frame has more than one) and emits their
 * events; two frames in flight, one being filled while the other is scored. */
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "run/frame_scoring.h"
#include "util/env_flag.h"

struct method_images {
	struct aa_image_rgba8 out8, diff8, flip8, prev8;
};

struct aa_scoring {
	const struct aa_job_spec *spec;
	struct aa_job_result *result;
	aa_event_fn on_event;
	void *user;
	bool inline_scoring;
	int done, total;                  /* progress units emitted, and of the job */
	struct aa_scoring_frame frames[2];
	int next;                         /* the slot aa_scoring_next gives */
	struct method_images m[AA_MAX_METHODS];
	struct aa_image_rgba8 prev_ref8;  /* the previous frame's reference: flicker */
	/* the thread and what it shares with the rendering thread, under lock */
	pthread_t thread;
	bool started, stop;
	pthread_mutex_t lock;
	pthread_cond_t changed;
	struct aa_scoring_frame *queue[2];
	int queued, busy;                 /* frames waiting, and the one being scored (0 or 1) */
	bool failed;
	struct aa_error err;
	/* a frame's methods, shared out between the thread and its helper */
	struct aa_scoring_frame *scoring;
	struct aa_flip_reference *flip_ref; /* the frame's FLIP reference side, made once, read by both; its
					     * memory is kept from frame to frame */
	int next_method;
	struct aa_error method_err[AA_MAX_METHODS];
};

long aa_count_nonfinite(const struct aa_image_rgbaf *img)
{
	long n = 0;
	size_t count = (size_t)img->width * img->height * 4;
	for (size_t i = 0; i < count; i++)
		n += !isfinite(img->pixels[i]);
	return n;
}

/* Finite R, G or B values below -1/1024: negative light, which no display or later pass expects. */
static long count_out_of_range(const struct aa_image_rgbaf *img)
{
	long n = 0;
	size_t count = (size_t)img->width * img->height;
	for (size_t i = 0; i < count; i++)
		for (int c = 0; c < 3; c++)
			n += img->pixels[i * 4 + c] < -1.0f / 1024.0f;
	return n;
}

/* |test - ref| x 4 per channel, as seed 002 shows errors. */
static void diff_image(const struct aa_image_rgba8 *ref, const struct aa_image_rgba8 *test,
		       struct aa_image_rgba8 *out)
{
	size_t n = (size_t)ref->width * ref->height;
	for (size_t i = 0; i < n; i++) {
		for (int c = 0; c < 3; c++) {
			int d = abs((int)test->pixels[i * 4 + c] - (int)ref->pixels[i * 4 + c]) * 4;
			out->pixels[i * 4 + c] = (uint8_t)(d > 255 ? 255 : d);
		}
		out->pixels[i * 4 + 3] = 255;
	}
}

/* Method i of frame f against its reference: the scored render's metrics and images. */
static int score_method(struct aa_scoring *sc, const struct aa_scoring_frame *f, int i, struct aa_error *err)
{
	struct aa_frame_result *fr = &sc->result->methods[i].frames[f->ordinal];
	struct method_images *m = &sc->m[i];
	const struct aa_image_rgbaf *output = &f->outputs[i];
	fr->nonfinite = aa_count_nonfinite(output);
	aa_image_encode_srgb8(output, &m->out8);
	if (aa_metrics_compare(&f->ref8, &m->out8, &fr->metrics, err) ||
	    aa_metrics_perceptual_shared(sc->flip_ref, &f->ref8, &m->out8, &fr->metrics, &m->flip8, err))
		return -1;
	fr->over_threshold = aa_metrics_count_over(&f->ref8, &m->out8, sc->spec->over_threshold);
	diff_image(&f->ref8, &m->out8, &m->diff8);
	fr->out_of_range = count_out_of_range(output);
	fr->flicker = NAN;
	fr->change = fr->ref_change = NAN;
	if (sc->spec->frames > 1) {
		if (f->ordinal > 0) {
			fr->flicker = aa_metrics_flicker(&m->out8, &m->prev8, &f->ref8, &sc->prev_ref8);
			fr->change = aa_metrics_mean_change(&m->out8, &m->prev8);
			fr->ref_change = aa_metrics_mean_change(&f->ref8, &sc->prev_ref8);
		}
		memcpy(m->prev8.pixels, m->out8.pixels, (size_t)m->out8.width * m->out8.height * 4);
	}
	return 0;
}

/* Takes the frame's methods one by one until none is left (the thread and its helper both run it). */
static void score_methods(struct aa_scoring *sc)
{
	for (;;) {
		pthread_mutex_lock(&sc->lock);
		const int k = sc->next_method++;
		pthread_mutex_unlock(&sc->lock);
		if (k >= sc->spec->method_count)
			return;
		const int i = sc->scoring->order[k];
		if (score_method(sc, sc->scoring, i, &sc->method_err[i]) && !sc->method_err[i].message[0])
			aa_error_set(&sc->method_err[i], AA_ERR_INTERNAL, "", "scoring failed");
	}
}

static void *helper_main(void *arg)
{
	score_methods(arg);
	return NULL;
}

static int emit(struct aa_scoring *sc, struct aa_event *ev, struct aa_error *err)
{
	ev->result = sc->result;
	if (sc->on_event && sc->on_event(ev, sc->user))
		return aa_error_set(err, AA_ERR_CANCELLED, "", "the job was cancelled");
	return 0;
}

static int progress(struct aa_scoring *sc, struct aa_error *err)
{
	struct aa_event ev = {.type = AA_EVENT_PROGRESS, .done = ++sc->done, .total = sc->total};
	return emit(sc, &ev, err);
}

/* Scores frame f and emits its events in the order the rendering used to: the reference and its
 * progress, each method's frame and progress in render order, then the progress of the re-timings. */
static int score_frame(struct aa_scoring *sc, struct aa_scoring_frame *f, struct aa_error *err)
{
	const int count = sc->spec->method_count;
	sc->scoring = f;
	sc->next_method = 0;
	memset(sc->method_err, 0, sizeof sc->method_err);
	/* The reference's side of FLIP is the same for every method: made here, before the helper starts. */
	if (aa_flip_reference_rgba8(&f->ref8, NULL, &sc->flip_ref, err))
		return -1;
	pthread_t helper;
	const bool helped = !sc->inline_scoring && count > 1 && pthread_create(&helper, NULL, helper_main, sc) == 0;
	score_methods(sc);
	if (helped)
		pthread_join(helper, NULL);
	for (int k = 0; k < count; k++) {
		const int i = f->order[k];
		if (sc->method_err[i].message[0]) {
			*err = sc->method_err[i];
			aa_error_prefix(err, "%s", sc->spec->methods[i].label);
			return -1;
		}
	}
	struct aa_event ev = {.type = AA_EVENT_REFERENCE_KEY, .frame = f->frame, .frame_ordinal = f->ordinal,
			      .text = f->key_text};
	if (f->key_text[0] && emit(sc, &ev, err))
		return -1;
	ev = (struct aa_event){.type = AA_EVENT_REFERENCE_FRAME, .frame = f->frame, .frame_ordinal = f->ordinal,
			       .image = &f->ref8, .linear = &f->full};
	if (emit(sc, &ev, err) || progress(sc, err))
		return -1;
	for (int k = 0; k < count; k++) {
		const int i = f->order[k];
		sc->result->methods[i].frame_count = f->ordinal + 1;
		struct method_images *m = &sc->m[i];
		ev = (struct aa_event){.type = AA_EVENT_METHOD_FRAME, .frame = f->frame, .frame_ordinal = f->ordinal,
				       .method_index = i, .image = &m->out8, .linear = &f->outputs[i], .diff = &m->diff8,
				       .flip_map = &m->flip8};
		if (emit(sc, &ev, err) || progress(sc, err))
			return -1;
	}
	for (int k = 0; k < count * (sc->spec->timing_repeat - 1); k++)
		if (progress(sc, err))
			return -1;
	if (sc->prev_ref8.pixels)
		memcpy(sc->prev_ref8.pixels, f->ref8.pixels, (size_t)f->ref8.width * f->ref8.height * 4);
	return 0;
}

static void *scorer_main(void *arg)
{
	struct aa_scoring *sc = arg;
	pthread_mutex_lock(&sc->lock);
	for (;;) {
		while (!sc->queued && !sc->stop)
			pthread_cond_wait(&sc->changed, &sc->lock);
		if (!sc->queued)
			break;
		struct aa_scoring_frame *f = sc->queue[0];
		sc->queue[0] = sc->queue[1];
		sc->queued--;
		sc->busy = 1;
		const bool skip = sc->failed;
		pthread_mutex_unlock(&sc->lock);
		struct aa_error err = {0};
		const int rc = skip ? 0 : score_frame(sc, f, &err);
		pthread_mutex_lock(&sc->lock);
		if (rc && !sc->failed) {
			sc->failed = true;
			sc->err = err;
		}
		sc->busy = 0;
		pthread_cond_broadcast(&sc->changed);
	}
	pthread_mutex_unlock(&sc->lock);
	return NULL;
}

int aa_scoring_create(const struct aa_job_spec *spec, struct aa_job_result *result, aa_event_fn on_event,
		      void *user, bool inline_scoring, struct aa_scoring **out, struct aa_error *err)
{
	*out = NULL;
	struct aa_scoring *sc = calloc(1, sizeof *sc);
	if (!sc)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	sc->spec = spec;
	sc->result = result;
	sc->on_event = on_event;
	sc->user = user;
	const char *mode = getenv("AALAB_SCORING");
	sc->inline_scoring = inline_scoring || (mode && strcmp(mode, "inline") == 0);
	sc->total = spec->frames * (1 + spec->method_count * spec->timing_repeat);
	pthread_mutex_init(&sc->lock, NULL);
	pthread_cond_init(&sc->changed, NULL);
	*out = sc;
	const int w = spec->width, h = spec->height;
	bool ok = spec->frames <= 1 || aa_image_rgba8_alloc(&sc->prev_ref8, w, h) == 0;
	for (int s = 0; ok && s < 2; s++) {
		ok = aa_image_rgbaf_alloc(&sc->frames[s].full, w, h) == 0 && aa_image_rgba8_alloc(&sc->frames[s].ref8, w, h) == 0;
		for (int i = 0; ok && i < spec->method_count; i++)
			ok = aa_image_rgbaf_alloc(&sc->frames[s].outputs[i], w, h) == 0;
	}
	for (int i = 0; ok && i < spec->method_count; i++) {
		struct method_images *m = &sc->m[i];
		ok = aa_image_rgba8_alloc(&m->out8, w, h) == 0 && aa_image_rgba8_alloc(&m->diff8, w, h) == 0 &&
		     aa_image_rgba8_alloc(&m->flip8, w, h) == 0 &&
		     (spec->frames <= 1 || aa_image_rgba8_alloc(&m->prev8, w, h) == 0);
	}
	if (!ok)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory for %dx%d images", w, h);
	if (!sc->inline_scoring && pthread_create(&sc->thread, NULL, scorer_main, sc) != 0)
		sc->inline_scoring = true; /* score here rather than not at all */
	sc->started = !sc->inline_scoring;
	return 0;
}

void aa_scoring_destroy(struct aa_scoring *sc)
{
	if (!sc)
		return;
	if (sc->started) {
		pthread_mutex_lock(&sc->lock);
		sc->stop = true;
		sc->failed = true; /* what is still queued is dropped */
		pthread_cond_broadcast(&sc->changed);
		pthread_mutex_unlock(&sc->lock);
		pthread_join(sc->thread, NULL);
	}
	pthread_mutex_destroy(&sc->lock);
	pthread_cond_destroy(&sc->changed);
	for (int s = 0; s < 2; s++) {
		aa_image_rgbaf_free(&sc->frames[s].full);
		aa_image_rgba8_free(&sc->frames[s].ref8);
		for (int i = 0; i < AA_MAX_METHODS; i++)
			aa_image_rgbaf_free(&sc->frames[s].outputs[i]);
	}
	for (int i = 0; i < AA_MAX_METHODS; i++) {
		aa_image_rgba8_free(&sc->m[i].out8);
		aa_image_rgba8_free(&sc->m[i].diff8);
		aa_image_rgba8_free(&sc->m[i].flip8);
		aa_image_rgba8_free(&sc->m[i].prev8);
	}
	aa_image_rgba8_free(&sc->prev_ref8);
	aa_flip_reference_free(sc->flip_ref);
	free(sc);
}

struct aa_scoring_frame *aa_scoring_next(struct aa_scoring *sc)
{
	struct aa_scoring_frame *f = &sc->frames[sc->next];
	/* two slots: the one handed over before the last is scored by now (aa_scoring_submit waits) */
	f->key_text[0] = 0;
	return f;
}

int aa_scoring_submit(struct aa_scoring *sc, struct aa_scoring_frame *f, struct aa_error *err)
{
	sc->next = 1 - sc->next;
	if (sc->inline_scoring) {
		if (!sc->failed && score_frame(sc, f, &sc->err))
			sc->failed = true;
		if (sc->failed)
			*err = sc->err;
		return sc->failed ? -1 : 0;
	}
	pthread_mutex_lock(&sc->lock);
	/* at most one frame waits: the slot the next aa_scoring_next gives must be free */
	while (sc->queued + sc->busy >= 2 && !sc->failed)
		pthread_cond_wait(&sc->changed, &sc->lock);
	sc->queue[sc->queued++] = f;
	pthread_cond_broadcast(&sc->changed);
	const bool failed = sc->failed;
	if (failed)
		*err = sc->err;
	pthread_mutex_unlock(&sc->lock);
	return failed ? -1 : 0;
}

int aa_scoring_wait(struct aa_scoring *sc, struct aa_error *err)
{
	if (!sc->inline_scoring) {
		pthread_mutex_lock(&sc->lock);
		while ((sc->queued || sc->busy) && !sc->failed)
			pthread_cond_wait(&sc->changed, &sc->lock);
		pthread_mutex_unlock(&sc->lock);
	}
	if (sc->failed)
		*err = sc->err;
	return sc->failed ? -1 : 0;
}
