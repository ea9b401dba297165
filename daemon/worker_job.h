/* What the worker thread (worker.c) and the worker process (worker_process.c) share, below both: rendering
 * a job (worker_render.c) and the job's bookkeeping in the store (worker_run.c). */
#ifndef AALABD_WORKER_JOB_H
#define AALABD_WORKER_JOB_H

#include <stdbool.h>
#include <stdio.h>
#include <time.h>

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

/* Wall-clock seconds: job times (started_at, finished_at) and GPU busy time. */
static inline double worker_now_s(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_REALTIME, &ts);
	return ts.tv_sec + ts.tv_nsec / 1e9;
}

#endif
