/* The GPU worker's two halves: rendering a job (in the worker thread, or in the worker process when user
 * methods are allowed) and the job's bookkeeping in the store (always in the worker thread). */
#ifndef AALABD_WORKER_H
#define AALABD_WORKER_H

#include <stdbool.h>
#include <stdio.h>

#include "jobs.h"

/* Where a rendering job's events go. Both return non-zero when the job must stop (it was cancelled). */
struct worker_sink {
	int (*event)(void *ctx, json_t *ev); /* steals ev: job_started, reference_frame, method_frame */
	int (*progress)(void *ctx, int done, int total);
	void *ctx;
};

/* What rendering a job came to. */
struct worker_outcome {
	int rc;                   /* 0: done, results.json and report.html written */
	struct aa_error err;
	int failed_writes;        /* images that could not be written (a full disk) */
	json_t *summary;          /* rc 0: per-method cost and accuracy */
	double busy;              /* seconds of GPU work */
};

/* Renders spec into dir (frames, results.json, report.html) with the engine and scene cache given. */
void worker_render(struct aa_engine *engine, struct scene_cache *scenes, const struct aa_job_spec *spec,
		   bool inline_scene, const char *dir, const struct worker_sink *sink, struct worker_outcome *out);

/* One run of a job in the store: its directory cleared and its event log opened at the start; its state,
 * final event, size and job.json at the end. */
struct worker_run {
	struct store *s;
	struct job *job;
	char dir[1200];
	FILE *log;                /* events.jsonl */
};
void worker_run_begin(struct store *s, struct job *job, struct worker_run *run);
/* Gives ev the job's id and next sequence number, logs it and wakes the event loop (steals ev). */
int worker_publish(struct worker_run *run, json_t *ev);
int worker_progress(struct worker_run *run, int done, int total);
/* Takes out->summary. The worker's hold on the job ends here (jobs.h): run->job is NULL afterwards and
 * the job may already be deleted by retention. */
void worker_run_end(struct worker_run *run, struct worker_outcome *out);

/* worker_process.c: the worker process (allow-user-methods). */
/* Starts it and waits until it has opened the device (aalabd's start-up); -1 with a message in err. */
int worker_process_start(struct store *s, char *err, size_t err_size);
/* Runs one job in it (the worker thread), stopping it at the job's time limit or when it dies. */
void worker_process_run_job(struct store *s, struct job *job);
/* Ends it (the worker thread, at shutdown). */
void worker_process_stop(struct store *s);
/* The process's main: `aalabd --worker-process FD [--state-dir DIR] [--device SEL] [--scene-cache-bytes N]`. */
int worker_process_main(int argc, char **argv);

/* render_priority.c: the rendering threads' nice value, render_nice above the calling thread's (at most 19);
 * setting it on the calling thread; the engine created on a thread at that value, so that the device's
 * threads start there (aalabd(8), render-nice). */
int render_nice_value(int render_nice);
void render_priority_apply(int nice_value);
int render_engine_create(const struct aa_engine_options *options, int nice_value, struct aa_engine **engine,
			 struct aa_error *err);

#endif
