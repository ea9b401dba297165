/* A job's references through the store (reference_store.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <jansson.h>

#include "reference/reference_store.h"

static void warn(struct aa_reference_store *s, const char *message)
{
	struct aa_reference_cache_result *r = s->result;
	if (r->warning_count < AA_REFERENCE_CACHE_WARNINGS)
		snprintf(r->warnings[r->warning_count++], sizeof r->warnings[0], "%.255s", message);
}

void aa_reference_store_job(struct aa_reference_store *s, struct aa_reference_cache *cache, bool verify, bool explain,
			    struct aa_reference_cache_result *result, const char *pattern, const char *scene_file,
			    const char *path, int width, int height, int samples, bool auto_samples)
{
	memset(s, 0, sizeof *s);
	s->cache = cache;
	s->verify = verify;
	s->explain = explain;
	s->result = result;
	s->pattern = pattern;
	memset(result, 0, sizeof *result);
	result->used = cache != NULL;
	/* the job of one frame that renders an entry again (aalab cache verify), as JSON without its frame */
	json_t *j = json_pack("{s:s, s:s, s:i, s:i, s:i, s:b}", "scene", scene_file, "path", path, "width", width,
			      "height", height, "samples", samples, "auto", auto_samples);
	char *text = j ? json_dumps(j, JSON_COMPACT | JSON_SORT_KEYS) : NULL;
	if (text && strlen(text) < sizeof s->recipe_head)
		snprintf(s->recipe_head, sizeof s->recipe_head, "%.*s", (int)strlen(text) - 1, text); /* no '}' */
	free(text);
	json_decref(j);
}

void aa_reference_store_frame(struct aa_reference_store *s, const struct aa_reference *ref,
			      const struct aa_frame_ctx *ctx)
{
	if (!s->cache)
		return;
	s->keyed = aa_reference_key_inputs_of(ref, ctx, s->pattern, &s->in) && s->recipe_head[0];
	s->frame = ctx->frame;
	s->loaded = s->rendered = 0;
	s->explanation[0] = 0;
}

/* The key of the frame's entry holding the sums up to n (fixed: n is N). */
static void key_of(struct aa_reference_store *s, const struct aa_reference *ref, bool auto_samples, int n,
		   struct aa_reference_key *key)
{
	aa_reference_key_levels(&s->in, ref, auto_samples, n);
	aa_reference_key_make(&s->in, key);
}

static void explain(struct aa_reference_store *s, const struct aa_reference_key *key, const char *outcome)
{
	if (!s->explain)
		return;
	char *buf = NULL;
	size_t size = 0;
	FILE *f = open_memstream(&buf, &size);
	if (!f)
		return;
	fprintf(f, "frame %d: reference key %.16s: %s\n", s->frame, key->hex, outcome);
	aa_reference_key_print(key, f);
	fclose(f);
	size_t len = strlen(s->explanation);
	snprintf(s->explanation + len, sizeof s->explanation - len, "%s", buf);
	free(buf);
}

/* 1: the entry, 0: none (or verify), -1 damaged (reported, removed). */
static int lookup(struct aa_reference_store *s, const struct aa_reference_key *key, struct aa_reference_entry *e)
{
	char warning[256] = "";
	const uint64_t before = aa_reference_cache_stats(s->cache).bytes_read;
	const int rc = aa_reference_cache_get(s->cache, key->sha256, e, warning, sizeof warning);
	s->result->bytes_read += aa_reference_cache_stats(s->cache).bytes_read - before;
	if (rc < 0) {
		s->result->discarded++;
		warn(s, warning);
	}
	if (rc > 0 && (e->width != s->in.width || e->height != s->in.height)) {
		aa_reference_entry_free(e);
		return 0;
	}
	return rc;
}

static void store(struct aa_reference_store *s, const struct aa_reference_key *key, struct aa_reference_entry *e)
{
	snprintf(e->recipe, sizeof e->recipe, "%s,\"frame\":%d,\"level\":%d}", s->recipe_head, s->frame,
		 e->samples[e->plane_count - 1]);
	struct aa_error err = {0};
	const struct aa_reference_cache_stats before = aa_reference_cache_stats(s->cache);
	if (aa_reference_cache_put(s->cache, key->sha256, e, &err)) {
		/* once per job and message: a full disk would say so every frame */
		for (int i = 0; i < s->result->warning_count; i++)
			if (!strcmp(s->result->warnings[i], err.message))
				return;
		warn(s, err.message);
	}
	s->result->bytes_written += aa_reference_cache_stats(s->cache).bytes_written - before.bytes_written;
}

/* verify: the render against the stored entry, bit for bit. */
static void compare(struct aa_reference_store *s, const struct aa_reference_key *key, const struct aa_reference_entry *now)
{
	struct aa_reference_entry e;
	if (lookup(s, key, &e) <= 0)
		return;
	bool same = e.plane_count == now->plane_count;
	const size_t bytes = (size_t)now->width * now->height * 16;
	for (int i = 0; same && i < e.plane_count; i++)
		same = e.samples[i] == now->samples[i] && memcmp(e.planes[i], now->planes[i], bytes) == 0;
	s->result->verified++;
	memcpy(s->result->verified_key, key->hex, sizeof s->result->verified_key);
	if (!same) {
		s->result->mismatched++;
		char message[256];
		snprintf(message, sizeof message, "reference cache: entry %.16s (frame %d) differs from its render: a "
			 "part of what decides the pixels is missing from the key", key->hex, s->frame);
		warn(s, message);
	}
	aa_reference_entry_free(&e);
}

static void read_cost(struct aa_reference_store *s, const struct aa_reference_entry *e, double *gpu_ms, double *cpu_ms)
{
	*gpu_ms = e->gpu_ms;
	*cpu_ms = e->cpu_ms;
}

int aa_reference_store_load(struct aa_reference_store *s, const struct aa_reference *ref, struct aa_image_rgbaf *full,
			    struct aa_image_rgbaf *half, double *gpu_ms, double *cpu_ms)
{
	if (!s->cache || !s->keyed || s->verify)
		return 0;
	struct aa_reference_key key;
	struct aa_reference_entry e;
	key_of(s, ref, false, ref->samples, &key);
	const int rc = lookup(s, &key, &e);
	explain(s, &key, rc > 0 ? "in the store" : "not stored: rendered");
	if (rc <= 0 || e.plane_count != 2 || e.samples[0] != ref->samples / 2 || e.samples[1] != ref->samples) {
		if (rc > 0)
			aa_reference_entry_free(&e);
		return 0;
	}
	aa_reference_average(e.planes[0], e.samples[0], half);
	aa_reference_average(e.planes[1], e.samples[1], full);
	read_cost(s, &e, gpu_ms, cpu_ms);
	aa_reference_entry_free(&e);
	s->loaded++;
	return 1;
}

void aa_reference_store_save(struct aa_reference_store *s, const struct aa_reference *ref, double gpu_ms, double cpu_ms)
{
	if (!s->cache || !s->keyed)
		return;
	s->rendered++;
	struct aa_reference_key key;
	key_of(s, ref, false, ref->samples, &key);
	struct aa_reference_entry e = {.width = s->in.width, .height = s->in.height, .plane_count = 2,
				       .samples = {ref->samples / 2, ref->samples},
				       .planes = {ref->readback_half.mapped, ref->readback.mapped},
				       .gpu_ms = gpu_ms, .cpu_ms = cpu_ms};
	if (s->verify) {
		explain(s, &key, "rendered to verify");
		compare(s, &key, &e);
	} else {
		store(s, &key, &e);
	}
}

int aa_reference_store_load_level(struct aa_reference_store *s, const struct aa_reference *ref, int n, float **sum,
				  float **half_sum, double *gpu_ms, double *cpu_ms)
{
	*sum = *half_sum = NULL;
	if (!s->cache || !s->keyed || s->verify)
		return 0;
	struct aa_reference_key key;
	struct aa_reference_entry e;
	key_of(s, ref, true, n, &key);
	const bool first = s->in.level_count == 2;
	const int rc = lookup(s, &key, &e);
	char what[64];
	snprintf(what, sizeof what, "level %d %s", n, rc > 0 ? "in the store" : "not stored: rendered");
	explain(s, &key, what);
	if (rc <= 0 || e.plane_count != (first ? 2 : 1) || e.samples[e.plane_count - 1] != n) {
		if (rc > 0)
			aa_reference_entry_free(&e);
		return 0;
	}
	read_cost(s, &e, gpu_ms, cpu_ms);
	*sum = e.planes[e.plane_count - 1];
	*half_sum = first ? e.planes[0] : NULL;
	s->loaded++;
	return 1;
}

void aa_reference_store_save_level(struct aa_reference_store *s, const struct aa_reference *ref, int n, double gpu_ms,
				   double cpu_ms)
{
	if (!s->cache || !s->keyed)
		return;
	s->rendered++;
	struct aa_reference_key key;
	key_of(s, ref, true, n, &key);
	const bool first = s->in.level_count == 2;
	struct aa_reference_entry e = {.width = s->in.width, .height = s->in.height, .plane_count = first ? 2 : 1,
				       .gpu_ms = gpu_ms, .cpu_ms = cpu_ms};
	e.samples[0] = first ? s->in.levels[0] : n;
	e.planes[0] = first ? ref->readback_half.mapped : ref->readback.mapped;
	e.samples[1] = n;
	e.planes[1] = ref->readback.mapped;
	if (s->verify) {
		explain(s, &key, "rendered to verify");
		compare(s, &key, &e);
	} else {
		store(s, &key, &e);
	}
}

int aa_reference_resume(struct aa_reference *ref, const float *sum, int n, struct aa_error *err)
{
	if (n < 2 || n > ref->samples)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "reference: resuming at %d samples of %d", n, ref->samples);
	VkCommandBuffer cmd;
	if (aa_sample_accumulator_load(&ref->sum, sum, err) || aa_gpu_begin(ref->r->gpu, &cmd, err))
		return -1;
	aa_renderer_record_shadow(ref->r, cmd); /* the renders that go on from it need this frame's */
	return aa_gpu_submit_wait(ref->r->gpu, cmd, err);
}

void aa_reference_store_frame_done(struct aa_reference_store *s, char *outcome, size_t size)
{
	if (!s->cache) {
		snprintf(outcome, size, "%s", "");
		return;
	}
	struct aa_reference_cache_result *r = s->result;
	if (!s->keyed) {
		r->unkeyed++;
		snprintf(outcome, size, "%s", "");
	} else if (s->rendered == 0) {
		r->hits++;
		snprintf(outcome, size, "hit");
	} else {
		r->misses++;
		r->continued += s->loaded > 0;
		snprintf(outcome, size, "%s", s->loaded > 0 ? "continued" : "miss");
	}
}
