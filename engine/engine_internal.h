/* The engine's private state, shared by engine.c and job_run.c. */
#ifndef AA_ENGINE_INTERNAL_H
#define AA_ENGINE_INTERNAL_H

#include "aa.h"
#include "gpu/gpu.h"
#include "scene_upload.h"

#define AA_UPLOAD_CACHE_SLOTS 16

struct aa_engine {
	struct aa_gpu gpu;
	/* scenes on the GPU, by scene uid, least recently used evicted past the byte budget */
	struct aa_scene_upload *uploads[AA_UPLOAD_CACHE_SLOTS];
	uint64_t upload_budget, upload_clock;
	struct aa_upload_stats upload_stats;
};

/* The GPU copy of a scene: from the cache, or uploaded now (and cached). Owned by the engine. */
struct aa_scene_upload *aa_engine_scene_upload(struct aa_engine *e, const struct aa_scene *scene,
					       struct aa_error *err);

#endif
