/* The job store: every job the daemon knows, in memory and on disk under STATE_DIR/jobs/ID/, the queue
 * the GPU worker takes jobs from, and each job's event log (what `watch` streams). One mutex guards all
 * of it; the event loop and the worker each hold it only for short updates. */
#ifndef AALABD_JOBS_H
#define AALABD_JOBS_H

#include <pthread.h>
#include <stdatomic.h>
#include <stdbool.h>
#include <stdint.h>

#include <jansson.h>

#include "run/engine.h"

enum job_state { JOB_QUEUED, JOB_RUNNING, JOB_DONE, JOB_FAILED, JOB_CANCELLED };

struct job {
	char id[16];
	enum job_state state;
	struct aa_job_spec spec;
	json_t *spec_json;        /* canonical spec (aa_job_spec_to_json) */
	char client[64];
	double submitted_at, started_at, finished_at; /* seconds since the epoch, 0 if not yet */
	int done, total;          /* units of work: frames x (1 + methods) */
	struct aa_error error;    /* JOB_FAILED */
	json_t *summary;          /* per-method summary once done */
	json_t *compare;          /* the verdict against the job's baseline once done (farm_jobs.c), or NULL */
	uint64_t bytes;           /* size of the job directory once finished */
	bool cancel;              /* asked to stop (cancel op, or drain timeout when requeue is set) */
	bool requeue;             /* interrupted by shutdown: stays queued on disk */
	bool inline_scene;        /* the scene came with the request: ID/scene.json */
	int interruptions;        /* runs in a row cut short by a crash of the daemon (poison jobs) */
	unsigned long run;        /* runs started (1 on the first): the run epoch in every event */
	/* event log: events[i] has sequence number i + 1 */
	char **events;
	unsigned long event_count, event_cap;
	bool log_complete;        /* the last event (finished, failed, cancelled) is in the log */
	bool events_loaded;       /* events of a job finished before this run were read from events.jsonl */
	int holds;                /* references beyond one locked section (the ownership rule below) */
	struct job *next;         /* store list, oldest first */
};

/* Who owns a job, and how long a pointer to one may be used (every file of the daemon follows this):
 * - The store owns every struct job. Only the store frees one: retention (store_apply_retention, through
 *   job_release) and store_close, always with store.lock held.
 * - A job pointer found under store.lock may be used only until that lock is released, unless its user
 *   holds the job (job_hold). A held job is never freed: retention skips it.
 * - The holders, and nothing else keeps a job pointer across unlocking:
 *     each connection watching the job (conn.watch->job, stream.h), from `watch` until watch_end or its close;
 *     the GPU worker (store.running), from taking the job off the queue until its final state, job.json
 *     and event log are written (worker_run_end).
 * - job_release may free the job (the last holder applies retention): the pointer is dead after it, so
 *   copy what is still needed (the id) first. */
struct store;
void job_hold(struct job *job);                     /* lock held */
void job_release(struct store *s, struct job *job); /* lock held; may free the job */

struct scene_cache;
struct worker_process;
struct scene_cache_stats {
	uint64_t hits, misses, reloads, evictions, bytes, budget;
	int entries;
};

struct store {
	pthread_mutex_t lock;
	pthread_cond_t work;      /* signalled when a job is queued or the worker must stop */
	char dir[1024];           /* STATE_DIR/jobs */
	struct job *jobs;
	unsigned long next_id;
	bool worker_stop;         /* finish the running job, take no new one */
	bool worker_exited;
	struct job *running;      /* held by the worker while it runs the job (job_hold) */
	atomic_int interrupt;     /* the running job must stop: its engine checks between pieces of GPU work */
	struct aa_engine *engine;
	struct scene_cache *scenes;
	struct loop *loop;        /* woken after every change a client may be waiting for */
	int retention_jobs;
	uint64_t retention_bytes;
	int max_interruptions;    /* a job interrupted this many times in a row is failed, not run again */
	char reserve_path[1100];  /* STATE_DIR/reserve: space set aside for terminal job states */
	bool reserve_held;
	pthread_t thread;
	/* metrics */
	uint64_t frames_rendered, jobs_finished;
	double gpu_busy_seconds;
	struct aa_upload_stats gpu_scenes; /* the engine's cache of uploaded scenes, after the last job */
	/* allow-user-methods: the engine lives in a worker process the worker thread can kill (worker_process.h);
	 * engine and scenes above are then unused */
	bool use_process;
	int job_time_limit_s;               /* job-time-limit (reloadable): the process is killed after it */
	uint64_t process_scene_budget;      /* scene-cache-bytes, sent with each job (reloadable) */
	char state_dir[1024], device[128];  /* for the process's command line */
	char device_name[256];              /* what the process opened */
	struct worker_process *process;     /* the worker thread's */
	int render_nice_value;              /* render-nice, as a nice value: the worker thread's and process's */
	struct scene_cache_stats process_scenes; /* the process's scene cache, after its last job */
	/* the store of references (reference-cache): its folder ("" off) and size for the process's command
	 * line, and its counts after the last job (the process's since it started) */
	char reference_cache[1100], reference_cache_bytes[32];
	struct aa_reference_cache_stats references;
};

const char *job_state_name(enum job_state s);
bool job_state_final(enum job_state s);
bool job_state_known(const char *name);

/* Opens STATE_DIR (creating it), reads every job back: queued jobs stay queued, jobs that were running
 * when the daemon died are queued again to re-run from the start. */
int store_open(struct store *s, const char *state_dir, char *err, size_t err_size);
/* One daemon per state folder: an exclusive flock on STATE_DIR/aalabd.lock, which holds the holder's PID.
 * hold: creates the folder and the file and keeps the lock (*fd) for the process's life (the kernel lets it
 * go however the process ends); else (--check) only tries it and lets go. -1 with err naming the folder
 * and the PID that holds it when another process has it. */
int store_lock_state_dir(const char *state_dir, bool hold, int *fd, char *err, size_t err_size);
void store_close(struct store *s);
/* Adds a queued job (persisted before it is visible); the caller holds no lock. The job takes its own
 * references to the spec's user methods; their files (method_files, or NULL) are kept beside job.json
 * as method-files.json, which is where the worker process reads them from. */
struct job *store_submit(struct store *s, const struct aa_job_spec *spec, const char *client,
			 const char *scene_text, size_t scene_size, const json_t *method_files, struct aa_error *err);
struct job *store_find(struct store *s, const char *id); /* with the lock held */
int store_count_active(struct store *s, const char *client); /* queued + running of a client, lock held */
int store_count_state(struct store *s, enum job_state st);   /* lock held */
/* Cancels: a queued job at once, a running job when the worker next checks. Lock held. */
int store_cancel(struct store *s, struct job *job, struct aa_error *err);
/* Writes STATE_DIR/jobs/ID/job.json atomically (lock held). When the disk is full it gives up the
 * reserve file and tries once more, so that a job's terminal state is written even then. */
int store_save(struct store *s, struct job *job);
/* Sets the reserve file (STATE_DIR/reserve) aside again if it was used; lock held. */
void store_reserve_space(struct store *s);
/* Writes the job's event log anew from memory, after appending to it failed (lock held). */
int store_rewrite_events(struct store *s, struct job *job);
/* Appends an event line to the log (lock held; takes ownership of line). */
void store_append_event(struct store *s, struct job *job, char *line);
/* Loads the event log of a job finished before this run from events.jsonl (lock held). */
void store_load_events(struct store *s, struct job *job);
/* Deletes the oldest finished jobs beyond the retention limits that nobody holds (lock held). */
void store_apply_retention(struct store *s);
json_t *job_to_json(const struct job *job); /* lock held */
uint64_t store_measure(struct store *s, struct job *job);    /* bytes of the job directory */
void store_clear_results(struct store *s, struct job *job);  /* before a (re-)run */
void store_remove_partial(struct store *s, struct job *job); /* a failed run's output, not its event log */
void job_dir(const struct store *s, const struct job *job, char *out, size_t size);

/* farm_jobs.c: baselines and verdicts for build farms (docs/protocol.md) */
struct aa_compare_options;
/* Compares job (NEW) with the job its baseline names (BASE), lock not held. *base_id is set once found. */
json_t *farm_compare_with(struct store *s, struct job *job, const char *baseline,
			  const struct aa_compare_options *opts, char *base_id, size_t size, struct aa_error *err);
/* The verdict of a finished job against its baseline: {"baseline", "job", "verdict", ...}, or NULL when the
 * job names none. Called by the worker without the lock, once results.json is written. */
json_t *farm_judge_baseline(struct store *s, struct job *job);
/* Whether a job has every label of the filter and, when suite is not NULL, that suite (lock held). */
bool farm_job_matches(const struct job *job, const struct aa_label *labels, int label_count, const char *suite);
/* The suite a job is compared and plotted with: its suite name, or its job hash when it has none. */
void farm_suite_key(const struct job *job, char *out, size_t size);

/* worker.c: the GPU worker thread */
int worker_start(struct store *s);
/* Asks the worker to stop after the running job; with cancel_running, the running job is interrupted
 * and stays queued for the next start. */
void worker_request_stop(struct store *s, bool cancel_running);
void worker_join(struct store *s);

/* scene_cache.c: loaded scenes kept by a byte budget, least recently used dropped first */
struct scene_cache *scene_cache_create(uint64_t budget_bytes);
void scene_cache_destroy(struct scene_cache *c);
void scene_cache_set_budget(struct scene_cache *c, uint64_t budget_bytes);
/* Returns a scene for file (loading it, or reloading it when the file changed since); the scene stays
 * valid until the next call. */
/* shown: how errors name the file (relative to its scene folder; never a server path). */
const struct aa_scene *scene_cache_get(struct scene_cache *c, const char *file, const char *shown,
				      struct aa_error *err);
void scene_cache_stats(struct scene_cache *c, struct scene_cache_stats *out);

#endif
