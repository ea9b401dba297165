/* One run of a job in the store, however it renders: its directory cleared and event log opened at the
 * start, each event numbered, logged and the event loop woken, and at the end its state, final event,
 * size, job.json and retention. Used by the worker thread for both ways of rendering. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "run/farm.h"
#include "jobs.h"
#include "methods/user_method.h"
#include "worker_job.h"
#include "loop.h"
#include "results/results.h"
#include "methods/methods.h"
#include "report/report.h"
#include "run/job_spec.h"

/* Gives the event its sequence number, logs it and wakes the event loop. Returns non-zero when the job
 * must stop. */
int worker_publish(struct worker_run *run, json_t *ev)
{
	struct store *s = run->s;
	json_object_set_new(ev, "job", json_string(run->job->id));
	pthread_mutex_lock(&s->lock);
	json_object_set_new(ev, "seq", json_integer((json_int_t)run->job->event_count + 1));
	/* seq starts again at 1 when a job runs again (after a crash): run tells a resuming client */
	json_object_set_new(ev, "run", json_integer((json_int_t)run->job->run));
	const char *type = json_string_value(json_object_get(ev, "event"));
	if (type && !strcmp(type, "method_frame"))
		s->frames_rendered++;
	json_t *done = json_object_get(ev, "done");
	if (json_is_integer(done) && json_integer_value(done) > run->job->done) /* status never says less */
		run->job->done = (int)json_integer_value(done);
	char *line = json_dumps(ev, JSON_COMPACT);
	if (line && run->log)
		fprintf(run->log, "%s\n", line);
	if (line)
		store_append_event(s, run->job, line);
	int stop = run->job->cancel;
	pthread_mutex_unlock(&s->lock);
	json_decref(ev);
	loop_wake(s->loop);
	return stop;
}

int worker_progress(struct worker_run *run, int done, int total)
{
	struct store *s = run->s;
	pthread_mutex_lock(&s->lock);
	if (done > run->job->done)
		run->job->done = done;
	run->job->total = total;
	int stop = run->job->cancel;
	pthread_mutex_unlock(&s->lock);
	return stop;
}

void worker_run_begin(struct store *s, struct job *job, struct worker_run *run)
{
	memset(run, 0, sizeof *run);
	run->s = s;
	run->job = job;
	job_dir(s, job, run->dir, sizeof run->dir);
	store_clear_results(s, job);
	char path[1400];
	snprintf(path, sizeof path, "%s/events.jsonl", run->dir);
	run->log = fopen(path, "w");
}

/* The job's end, however it ran: its state, the final event, its size, job.json and retention. The
 * state changes last, with job.json saved and retention applied in the same locked step: a client that
 * sees the job finished (status, list, watch_end) finds its job.json, log and the store as they stay. */
/* A job's error never shows the state folder (an io error quotes the file it could not write): each
 * occurrence of it becomes "STATE_DIR", as aalabd(8) names it. */
static void hide_state_dir(char *msg, size_t size, const char *state_dir)
{
	const size_t n = strlen(state_dir);
	char *at, *from = msg;
	if (n == 0)
		return;
	while ((at = strstr(from, state_dir))) {
		static const char name[] = "STATE_DIR";
		const size_t tail = strlen(at + n) + 1;
		if ((size_t)(at - msg) + sizeof name - 1 + tail > size)
			break;
		memmove(at + sizeof name - 1, at + n, tail);
		memcpy(at, name, sizeof name - 1);
		from = at + sizeof name - 1;
	}
}

void worker_run_end(struct worker_run *run, struct worker_outcome *out)
{
	struct store *s = run->s;
	struct job *job = run->job;
	const int rc = out->rc;
	struct aa_error err = out->err;
	hide_state_dir(err.message, sizeof err.message, s->state_dir);
	json_t *summary = out->summary;
	out->summary = NULL;
	/* the verdict against the job's baseline (results.json is written by now, in this process or the
	 * worker process), ready before anyone can see the job done */
	json_t *verdict = rc == 0 ? farm_judge_baseline(s, job) : NULL;
	bool failed = rc && !(err.code == AA_ERR_CANCELLED && !out->failed_writes);
	pthread_mutex_lock(&s->lock);
	bool requeue = job->requeue && rc && err.code == AA_ERR_CANCELLED;
	pthread_mutex_unlock(&s->lock);
	/* half a result is no result (it also frees the space it took); an interrupted job runs again from
	 * its start, so its frames so far go too */
	if (failed || requeue)
		store_remove_partial(s, job);
	if (run->log)
		fflush(run->log);
	/* measured before the state changes, so that status never shows a finished job with bytes 0; the
	 * final event's line is added when it is measured again below */
	uint64_t bytes_so_far = store_measure(s, job);
	pthread_mutex_lock(&s->lock);
	job->bytes = bytes_so_far;
	json_t *ev;
	enum job_state final_state;
	if (rc == 0) {
		final_state = JOB_DONE;
		job->summary = json_incref(summary);
		ev = json_pack("{ss so ss}", "event", "job_finished", "summary", summary, "results", "results.json");
		if (verdict) {
			job->compare = json_incref(verdict);
			json_object_set_new(ev, "compare", verdict);
		}
	} else if (err.code == AA_ERR_CANCELLED && !out->failed_writes) {
		json_decref(summary);
		json_decref(verdict);
		final_state = requeue ? JOB_QUEUED : JOB_CANCELLED;
		ev = json_pack("{ss ss}", "event", "job_cancelled", "state", requeue ? "queued" : "cancelled");
	} else {
		json_decref(summary);
		final_state = JOB_FAILED;
		job->error = err;
		ev = json_pack("{ss s{ss ss ss}}", "event", "job_failed", "error", "code", aa_error_code_name(err.code),
			       "message", err.message, "path", err.path);
	}
	if (requeue) {
		job->started_at = 0; /* the next start runs it again from the beginning */
		job->done = 0;
	} else {
		job->finished_at = worker_now_s();
	}
	s->gpu_busy_seconds += out->busy;
	s->jobs_finished += !requeue;
	pthread_mutex_unlock(&s->lock);
	worker_publish(run, ev);
	bool log_ok = run->log != NULL;
	if (run->log) {
		log_ok = !ferror(run->log) && fflush(run->log) == 0 && fsync(fileno(run->log)) == 0;
		log_ok &= fclose(run->log) == 0;
		run->log = NULL;
	}
	pthread_mutex_lock(&s->lock);
	if (!log_ok) /* the disk filled up under the log: write it again now that partial output is gone */
		store_rewrite_events(s, job);
	pthread_mutex_unlock(&s->lock);
	uint64_t bytes = store_measure(s, job);
	pthread_mutex_lock(&s->lock);
	job->bytes = bytes;
	if (!requeue)
		job->interruptions = 0;
	job->state = final_state;
	job->log_complete = true;
	store_save(s, job);
	/* the worker lets go of the job (jobs.h): retention may delete it right here */
	s->running = NULL;
	job_release(s, job);
	run->job = NULL;
	pthread_mutex_unlock(&s->lock);
	loop_wake(s->loop);
}
