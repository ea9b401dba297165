/* The engine's private state, shared by engine.c and job_run.c. */
#ifndef AA_ENGINE_INTERNAL_H
#define AA_ENGINE_INTERNAL_H

#include "run/engine.h"
#include "gpu/gpu.h"
#include "render/scene_upload.h"
#include "reference/reference_cache.h"

#define AA_UPLOAD_CACHE_SLOTS 16

struct aa_engine {
	struct aa_gpu gpu;
	/* scenes on the GPU, by scene uid, least recently used evicted past the byte budget */
	struct aa_scene_upload *uploads[AA_UPLOAD_CACHE_SLOTS];
	uint64_t upload_budget, upload_clock;
	struct aa_upload_stats upload_stats;
	struct aa_renderer *kept_renderer; /* the last job's, with its compiled pipelines (engine.c) */
	struct aa_reference_cache *reference_cache; /* the store of references jobs use, or NULL */
};

/* The GPU copy of a scene: from the cache, or uploaded now (and cached). Owned by the engine. */
struct aa_scene_upload *aa_engine_scene_upload(struct aa_engine *e, const struct aa_scene *scene,
					       struct aa_error *err);

struct aa_frame_plan;
struct aa_renderer;
/* A renderer for a job: the last job's when it fits (same uploaded scene, plan and size: its pipelines
 * are compiled already), else a new one. Give it back with aa_engine_renderer_release after the job. */
int aa_engine_renderer(struct aa_engine *e, const struct aa_scene *scene, const struct aa_scene_upload *upload,
		       const struct aa_frame_plan *plan, int width, int height, struct aa_renderer **out,
		       struct aa_error *err);
/* Keeps r for the next job (the one kept before is destroyed). Every method and reference using r must be
 * destroyed first. */
void aa_engine_renderer_release(struct aa_engine *e, struct aa_renderer *r);

#endif
