/* The engine: one Vulkan device for the process, shared by every job. */
#include <malloc.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "run/engine.h"
#include "run/engine_internal.h"
#include "render/renderer.h"

int aa_engine_create(const struct aa_engine_options *opts, struct aa_engine **out, struct aa_error *err)
{
	/* lavapipe returns its per-frame working memory to the kernel and faults it in again every frame
	 * unless trimming is raised (lavapipe-costs.md, trap 2): up to 2x slower, not repeatably. */
	mallopt(M_TRIM_THRESHOLD, 512 * 1024 * 1024);
	/* Large buffers (metrics planes, readbacks, PNG rows) are allocated and freed every frame; above the
	 * mmap threshold each is a fresh mapping, faulted in page by page (README job: 66k faults -> 38k). */
	mallopt(M_MMAP_THRESHOLD, 256 * 1024 * 1024);
	struct aa_engine *e = calloc(1, sizeof *e);
	if (!e)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	bool validation = (opts && opts->validation) || aa_env_flag("AALAB_VALIDATION");
	if (aa_gpu_create(&e->gpu, opts ? opts->device : NULL, validation, err)) {
		free(e);
		return -1;
	}
	e->upload_budget = 256ull << 20;
	*out = e;
	return 0;
}

void aa_engine_destroy(struct aa_engine *e)
{
	if (!e)
		return;
	aa_renderer_destroy(e->kept_renderer);
	aa_reference_cache_close(e->reference_cache);
	for (int i = 0; i < AA_UPLOAD_CACHE_SLOTS; i++)
		aa_scene_upload_destroy(e->uploads[i]);
	aa_gpu_destroy(&e->gpu);
	free(e);
}

int aa_engine_validation_errors(const struct aa_engine *e)
{
	return e->gpu.validation_errors;
}

const char *aa_engine_device_name(const struct aa_engine *e)
{
	return e->gpu.properties.deviceName;
}

int aa_engine_set_reference_cache(struct aa_engine *e, const char *dir, uint64_t max_bytes, struct aa_error *err)
{
	struct aa_reference_cache *c = NULL;
	if (dir && aa_reference_cache_open(dir, max_bytes, &c, err))
		return -1;
	aa_reference_cache_close(e->reference_cache);
	e->reference_cache = c;
	return 0;
}

bool aa_engine_reference_cache_stats(struct aa_engine *e, struct aa_reference_cache_stats *out)
{
	memset(out, 0, sizeof *out);
	if (!e->reference_cache)
		return false;
	*out = aa_reference_cache_stats(e->reference_cache);
	return true;
}

void aa_engine_set_interrupt(struct aa_engine *e, const atomic_int *flag)
{
	e->gpu.interrupt = flag;
}

void aa_engine_set_upload_budget(struct aa_engine *e, uint64_t bytes)
{
	e->upload_budget = bytes;
}

struct aa_upload_stats aa_engine_upload_stats(const struct aa_engine *e)
{
	struct aa_upload_stats s = e->upload_stats;
	s.bytes = 0;
	s.scenes = 0;
	for (int i = 0; i < AA_UPLOAD_CACHE_SLOTS; i++)
		if (e->uploads[i]) {
			s.bytes += e->uploads[i]->bytes;
			s.scenes++;
		}
	return s;
}

/* Destroys an uploaded scene, and the kept renderer that draws it. */
static void upload_destroy(struct aa_engine *e, struct aa_scene_upload *up)
{
	if (e->kept_renderer && e->kept_renderer->upload == up) {
		aa_renderer_destroy(e->kept_renderer);
		e->kept_renderer = NULL;
	}
	aa_scene_upload_destroy(up);
}

/* Drops least recently used scenes, never `keep`, until the cache fits its budget and has a free slot. */
static void evict(struct aa_engine *e, const struct aa_scene_upload *keep, int *free_slot)
{
	for (;;) {
		struct aa_upload_stats now = aa_engine_upload_stats(e);
		int oldest = -1, empty = -1;
		for (int i = 0; i < AA_UPLOAD_CACHE_SLOTS; i++) {
			if (!e->uploads[i])
				empty = empty < 0 ? i : empty;
			else if (e->uploads[i] != keep &&
				 (oldest < 0 || e->uploads[i]->last_used < e->uploads[oldest]->last_used))
				oldest = i;
		}
		if ((now.bytes <= e->upload_budget && (empty >= 0 || !free_slot)) || oldest < 0) {
			if (free_slot)
				*free_slot = empty;
			return;
		}
		upload_destroy(e, e->uploads[oldest]);
		e->uploads[oldest] = NULL;
		e->upload_stats.evictions++;
	}
}

struct aa_scene_upload *aa_engine_scene_upload(struct aa_engine *e, const struct aa_scene *scene,
					       struct aa_error *err)
{
	for (int i = 0; i < AA_UPLOAD_CACHE_SLOTS; i++)
		if (e->uploads[i] && e->uploads[i]->scene_uid == scene->uid) {
			e->uploads[i]->last_used = ++e->upload_clock;
			e->upload_stats.hits++;
			evict(e, e->uploads[i], NULL); /* the budget may have shrunk */
			return e->uploads[i];
		}
	e->upload_stats.misses++;
	int slot = -1;
	evict(e, NULL, &slot);
	struct aa_scene_upload *up;
	if (aa_scene_upload_create(&e->gpu, scene, &up, err))
		return NULL;
	up->last_used = ++e->upload_clock;
	if (slot < 0) { /* every slot holds a scene: drop the oldest */
		int oldest = 0;
		for (int i = 1; i < AA_UPLOAD_CACHE_SLOTS; i++)
			if (e->uploads[i]->last_used < e->uploads[oldest]->last_used)
				oldest = i;
		upload_destroy(e, e->uploads[oldest]);
		e->upload_stats.evictions++;
		slot = oldest;
	}
	e->uploads[slot] = up;
	evict(e, up, NULL); /* a scene larger than the budget still serves this job */
	return up;
}

int aa_engine_renderer(struct aa_engine *e, const struct aa_scene *scene, const struct aa_scene_upload *upload,
		       const struct aa_frame_plan *plan, int width, int height, struct aa_renderer **out,
		       struct aa_error *err)
{
	struct aa_renderer *r = e->kept_renderer;
	e->kept_renderer = NULL;
	if (r && aa_renderer_fits(r, scene, upload, plan, width, height)) {
		aa_renderer_reuse(r, scene, plan);
		*out = r;
		return 0;
	}
	aa_renderer_destroy(r);
	return aa_renderer_create(&e->gpu, scene, upload, plan, width, height, out, err);
}

void aa_engine_renderer_release(struct aa_engine *e, struct aa_renderer *r)
{
	if (!r)
		return;
	aa_renderer_destroy(e->kept_renderer);
	e->kept_renderer = r;
}
