/* The GPU worker thread: takes queued jobs one at a time and runs each, rendering it here with the engine
 * it owns (worker_render.c) or, with user methods allowed, in the worker process it owns
 * (worker_process.c); the job's bookkeeping is worker_run.c's either way. The event loop never waits for it. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "run/farm.h"
#include "jobs.h"
#include "methods/user_method.h"
#include "render_priority.h"
#include "worker_job.h"
#include "worker_process.h"
#include "loop.h"
#include "results/results.h"
#include "methods/methods.h"
#include "report/report.h"
#include "run/job_spec.h"

static int thread_event(void *ctx, json_t *ev)
{
	return worker_publish(ctx, ev);
}

static int thread_progress(void *ctx, int done, int total)
{
	return worker_progress(ctx, done, total);
}

static bool has_user_methods(const struct aa_job_spec *spec)
{
	for (int i = 0; i < spec->method_count; i++)
		if (aa_method_is_user(spec->methods[i].method))
			return true;
	return false;
}

static void run_job(struct store *s, struct job *job)
{
	struct worker_run run;
	worker_run_begin(s, job, &run);
	struct worker_outcome out = {0};
	if (has_user_methods(&job->spec)) {
		/* only a worker process runs a user's shaders: a job stored while they were allowed, and run after
		 * a restart without allow-user-methods, fails rather than runs them here */
		out.rc = -1;
		aa_error_set(&out.err, AA_ERR_INVALID, "job.methods", "user methods are off on this daemon now "
			     "(allow-user-methods, aalabd(8))");
	} else {
		struct worker_sink sink = {.event = thread_event, .progress = thread_progress, .ctx = &run};
		worker_render(s->engine, s->scenes, &job->spec, job->inline_scene, run.dir, &sink, &out);
	}
	pthread_mutex_lock(&s->lock);
	s->gpu_scenes = aa_engine_upload_stats(s->engine);
	aa_engine_reference_cache_stats(s->engine, &s->references);
	pthread_mutex_unlock(&s->lock);
	worker_run_end(&run, &out);
}

static struct job *next_queued(struct store *s)
{
	for (struct job *j = s->jobs; j; j = j->next)
		if (j->state == JOB_QUEUED && !j->requeue)
			return j;
	return NULL;
}

static void *worker_main(void *arg)
{
	struct store *s = arg;
	render_priority_apply(s->render_nice_value); /* it compiles pipelines and computes the metrics */
	pthread_mutex_lock(&s->lock);
	for (;;) {
		struct job *job = NULL;
		while (!s->worker_stop && !(job = next_queued(s)))
			pthread_cond_wait(&s->work, &s->lock);
		if (s->worker_stop)
			break;
		job->state = JOB_RUNNING;
		job->started_at = worker_now_s();
		job->done = 0;
		job->run++;
		store_reserve_space(s); /* given up when the last job filled the disk */
		for (unsigned long i = 0; i < job->event_count; i++)
			free(job->events[i]);
		job->event_count = 0;
		job->log_complete = false;
		job_hold(job); /* until worker_run_end: nothing may free it while it runs (jobs.h) */
		s->running = job;
		atomic_store(&s->interrupt, 0);
		store_save(s, job);
		pthread_mutex_unlock(&s->lock);
		loop_wake(s->loop);
		if (s->use_process)
			worker_process_run_job(s, job);
		else
			run_job(s, job);
		job = NULL; /* let go of in worker_run_end */
		pthread_mutex_lock(&s->lock);
	}
	pthread_mutex_unlock(&s->lock);
	if (s->use_process)
		worker_process_stop(s);
	pthread_mutex_lock(&s->lock);
	s->worker_exited = true;
	pthread_mutex_unlock(&s->lock);
	loop_wake(s->loop);
	return NULL;
}

int worker_start(struct store *s)
{
	return pthread_create(&s->thread, NULL, worker_main, s) == 0 ? 0 : -1;
}

void worker_request_stop(struct store *s, bool cancel_running)
{
	pthread_mutex_lock(&s->lock);
	s->worker_stop = true;
	if (cancel_running && s->running) {
		s->running->cancel = true;
		s->running->requeue = true;
		atomic_store(&s->interrupt, 1);
	}
	pthread_cond_signal(&s->work);
	pthread_mutex_unlock(&s->lock);
}

void worker_join(struct store *s)
{
	pthread_join(s->thread, NULL);
}
