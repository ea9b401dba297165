/* The aalab engine API: an engine holds the Vulkan device and a scene cache; jobs run through it and
 * report what happens as events (docs/architecture.md, "One job"). */
#ifndef AA_H
#define AA_H

#include <stdatomic.h>
#include <stdbool.h>

#include "util/env_flag.h"
#include "util/error.h"
#include "types/job.h"
#include "scene/scene.h"
#include "reference/reference_cache.h"

struct aa_engine;

struct aa_engine_options {
	const char *device;   /* substring of the device name or index ("0"); NULL: $AALAB_DEVICE or first */
	bool validation;      /* enable VK_LAYER_KHRONOS_validation if installed ($AALAB_VALIDATION on too) */
	int verbose;
};


int aa_engine_create(const struct aa_engine_options *opts, struct aa_engine **out, struct aa_error *err);
void aa_engine_destroy(struct aa_engine *engine);
/* Number of validation-layer errors reported so far (tests fail on any). */
int aa_engine_validation_errors(const struct aa_engine *engine);
const char *aa_engine_device_name(const struct aa_engine *engine);

/* Scenes uploaded to the GPU are kept for later jobs on the same loaded scene (aalabd's scene cache keeps
 * scenes loaded), least recently used first out past a byte budget (default 256 MiB). */
struct aa_upload_stats {
	uint64_t hits, misses, evictions;
	uint64_t bytes;   /* GPU memory the cached scenes hold now */
	int scenes;       /* scenes cached now */
};
void aa_engine_set_upload_budget(struct aa_engine *engine, uint64_t bytes);
/* A flag another thread (or a signal handler) sets to stop the running job: the job checks it between
 * the bounded pieces of its GPU work and ends with AA_ERR_CANCELLED (docs/aalabd.8, STOPPING A JOB).
 * NULL: none. The caller clears it before each job. */
void aa_engine_set_interrupt(struct aa_engine *engine, const atomic_int *flag);
struct aa_upload_stats aa_engine_upload_stats(const struct aa_engine *engine);

/* The store of references (engine/reference/reference_cache.h, docs/reference-cache.md) that jobs read
 * and write: a folder (created), at most max_bytes (0: the default); NULL dir: none (the default). An
 * error names the field "reference-cache". */
int aa_engine_set_reference_cache(struct aa_engine *engine, const char *dir, uint64_t max_bytes,
				  struct aa_error *err);
/* The store's counts since it was set; false without one. */
bool aa_engine_reference_cache_stats(struct aa_engine *engine, struct aa_reference_cache_stats *out);

/* Frees what a result holds (its frames and timed renders), not the struct itself. */
void aa_job_result_free(struct aa_job_result *r);

/* Runs a job to completion (or cancellation by the callback). On success *result holds everything the
 * results writer needs; free it with aa_job_result_free + free. */
int aa_job_run(struct aa_engine *engine, const struct aa_job_spec *spec, aa_event_fn on_event, void *user,
	       struct aa_job_result **result, struct aa_error *err);

/* The same with a scene built in code (2D test patterns): spec->scene is only a label, the scene is
 * borrowed, not freed. */
int aa_job_run_scene(struct aa_engine *engine, const struct aa_job_spec *spec, const struct aa_scene *scene,
		     aa_event_fn on_event, void *user, struct aa_job_result **result, struct aa_error *err);

#endif
