/* The job store: jobs in memory and on disk (STATE_DIR/jobs/ID/job.json written with write, fsync,
 * rename), recovery after a crash, event logs and retention. */
#include <dirent.h>
#include <errno.h>
#include <ftw.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "run/farm.h"
#include "jobs.h"
#include "methods/user_method.h"
#include "results/results.h"
#include "util/file_io.h"
#include "run/job_spec.h"

const char *job_state_name(enum job_state s)
{
	switch (s) {
	case JOB_QUEUED: return "queued";
	case JOB_RUNNING: return "running";
	case JOB_DONE: return "done";
	case JOB_FAILED: return "failed";
	case JOB_CANCELLED: return "cancelled";
	}
	return "unknown";
}

bool job_state_final(enum job_state s)
{
	return s == JOB_DONE || s == JOB_FAILED || s == JOB_CANCELLED;
}

bool job_state_known(const char *name)
{
	for (int s = JOB_QUEUED; s <= JOB_CANCELLED; s++)
		if (strcmp(name, job_state_name(s)) == 0)
			return true;
	return false;
}

static int state_from_name(const char *name)
{
	for (int s = JOB_QUEUED; s <= JOB_CANCELLED; s++)
		if (strcmp(name, job_state_name(s)) == 0)
			return s;
	return -1;
}

static double now_s(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_REALTIME, &ts);
	return ts.tv_sec + ts.tv_nsec / 1e9;
}

void job_dir(const struct store *s, const struct job *job, char *out, size_t size)
{
	snprintf(out, size, "%s/%s", s->dir, job->id);
}

static void job_free(struct job *job)
{
	aa_job_spec_release(&job->spec);
	json_decref(job->spec_json);
	json_decref(job->summary);
	json_decref(job->compare);
	for (unsigned long i = 0; i < job->event_count; i++)
		free(job->events[i]);
	free(job->events);
	free(job);
}

json_t *job_to_json(const struct job *job)
{
	json_t *o = json_pack("{ss ss sO ss sf si si si}", "id", job->id, "state", job_state_name(job->state),
			      "spec", job->spec_json, "client", job->client, "submitted_at", job->submitted_at,
			      "done", job->done, "total", job->total, "events", (json_int_t)job->event_count);
	if (job->started_at > 0)
		json_object_set_new(o, "started_at", json_real(job->started_at));
	if (job->finished_at > 0)
		json_object_set_new(o, "finished_at", json_real(job->finished_at));
	if (job->inline_scene)
		json_object_set_new(o, "inline_scene", json_true());
	if (job->run > 0)
		json_object_set_new(o, "run", json_integer((json_int_t)job->run));
	if (job->interruptions > 0)
		json_object_set_new(o, "interruptions", json_integer(job->interruptions));
	char hash[80]; /* what a job without a suite name is plotted and compared by (/v1/series) */
	aa_job_hash(&job->spec, hash, sizeof hash);
	json_object_set_new(o, "job_hash", json_string(hash));
	if (job->state == JOB_FAILED)
		json_object_set_new(o, "error", json_pack("{ss ss ss}", "code", aa_error_code_name(job->error.code),
							  "message", job->error.message, "path", job->error.path));
	if (job->summary)
		json_object_set(o, "summary", job->summary);
	if (job->compare)
		json_object_set(o, "compare", job->compare);
	if (job_state_final(job->state))
		json_object_set_new(o, "bytes", json_integer((json_int_t)job->bytes));
	return o;
}

#define RESERVE_BYTES (256 * 1024)

void store_reserve_space(struct store *s)
{
	if (s->reserve_held || !s->reserve_path[0])
		return;
	FILE *f = fopen(s->reserve_path, "wb");
	bool ok = f != NULL;
	static const char zeros[4096];
	for (int i = 0; ok && i < RESERVE_BYTES / (int)sizeof zeros; i++)
		ok = fwrite(zeros, 1, sizeof zeros, f) == sizeof zeros;
	ok = f && fflush(f) == 0 && fsync(fileno(f)) == 0 && ok;
	if (f)
		fclose(f);
	if (!ok) {
		unlink(s->reserve_path); /* the disk is full now; the next job tries again */
		return;
	}
	s->reserve_held = true;
}

static int save_once(struct store *s, struct job *job, struct aa_error *err)
{
	char dir[1200];
	job_dir(s, job, dir, sizeof dir);
	json_t *o = job_to_json(job);
	json_object_del(o, "events");
	char *text = json_dumps(o, JSON_INDENT(1) | JSON_SORT_KEYS);
	json_decref(o);
	if (!text)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	int rc = aa_results_write_file_atomic(dir, "job.json", text, strlen(text), err);
	free(text);
	return rc;
}

int store_save(struct store *s, struct job *job)
{
	struct aa_error err = {0};
	int rc = save_once(s, job, &err);
	if (rc && s->reserve_held && job_state_final(job->state)) {
		/* most likely a full disk: the reserve exists so that a job's state can still be written */
		unlink(s->reserve_path);
		s->reserve_held = false;
		fprintf(stderr, "aalabd: cannot save job %s (%s); using the reserved space\n", job->id, err.message);
		memset(&err, 0, sizeof err);
		rc = save_once(s, job, &err);
	}
	if (rc)
		fprintf(stderr, "aalabd: cannot save job %s: %s\n", job->id, err.message);
	return rc;
}

int store_rewrite_events(struct store *s, struct job *job)
{
	char dir[1200];
	job_dir(s, job, dir, sizeof dir);
	size_t size = 0;
	for (unsigned long i = 0; i < job->event_count; i++)
		size += strlen(job->events[i]) + 1;
	char *text = malloc(size + 1), *p = text;
	if (!text)
		return -1;
	for (unsigned long i = 0; i < job->event_count; i++) {
		size_t n = strlen(job->events[i]);
		memcpy(p, job->events[i], n);
		p[n] = '\n';
		p += n + 1;
	}
	struct aa_error err = {0};
	int rc = aa_results_write_file_atomic(dir, "events.jsonl", text, size, &err);
	free(text);
	if (rc)
		fprintf(stderr, "aalabd: cannot write the event log of job %s: %s\n", job->id, err.message);
	return rc;
}

static void store_insert(struct store *s, struct job *job)
{
	/* ids grow with time, so the list stays oldest first */
	struct job **p = &s->jobs;
	while (*p && strcmp((*p)->id, job->id) < 0)
		p = &(*p)->next;
	job->next = *p;
	*p = job;
}

static int remove_entry(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
	(void)st; (void)flag; (void)ftw;
	return remove(path) < 0 && errno != ENOENT ? -1 : 0;
}

static void remove_tree(const char *dir)
{
	nftw(dir, remove_entry, 16, FTW_DEPTH | FTW_PHYS);
}

static int add_size(const char *path, const struct stat *st, int flag, struct FTW *ftw);
static uint64_t tree_bytes_acc;
static int add_size(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
	(void)path; (void)ftw;
	if (flag == FTW_F)
		tree_bytes_acc += (uint64_t)st->st_size;
	return 0;
}

/* Only the worker thread measures trees (when a job finishes), so the accumulator needs no lock. */
static uint64_t tree_bytes(const char *dir)
{
	tree_bytes_acc = 0;
	nftw(dir, add_size, 16, FTW_PHYS);
	return tree_bytes_acc;
}

/* The temporary files of writes that a crash cut short, in a job's folder (its subfolders go with
 * clear_results when the job runs again). */
static void remove_stale_temps(const char *dir)
{
	DIR *d = opendir(dir);
	if (!d)
		return;
	struct dirent *de;
	while ((de = readdir(d)))
		if (de->d_name[0] == '.')
			aa_file_remove_stale_temp(dir, de->d_name);
	closedir(d);
}

/* Clears what a run leaves in a job directory, before a job runs (again) from the start; a failed run
 * keeps its event log (it says why). */
static void clear_results(const char *dir, bool keep_events)
{
	const char *const parts[] = {"frames", "diff", "flip", "linear", "exr", "cases", "results.json", "report.html",
				     "events.jsonl", "viewer", NULL}; /* cases/: a suite's case folders */
	char path[1400];
	for (int i = 0; parts[i]; i++) {
		if (keep_events && !strcmp(parts[i], "events.jsonl"))
			continue;
		snprintf(path, sizeof path, "%s/%s", dir, parts[i]);
		remove_tree(path);
	}
}

static struct job *load_job(struct store *s, const char *id)
{
	char path[1400];
	snprintf(path, sizeof path, "%s/%s/job.json", s->dir, id);
	json_error_t jerr;
	json_t *o = json_load_file(path, 0, &jerr);
	if (!o) {
		fprintf(stderr, "aalabd: skipping %s: %s\n", path, jerr.text);
		return NULL;
	}
	struct job *job = calloc(1, sizeof *job);
	const char *state = json_string_value(json_object_get(o, "state"));
	const char *client = json_string_value(json_object_get(o, "client"));
	json_t *spec = json_object_get(o, "spec");
	int st = state ? state_from_name(state) : -1;
	struct aa_error err = {0};
	/* a job's user methods are read from the files sent with it, never from elsewhere on this disk */
	char files_path[1400];
	snprintf(files_path, sizeof files_path, "%s/%s/method-files.json", s->dir, id);
	json_t *files = json_load_file(files_path, 0, NULL);
	if (!json_is_object(files)) {
		json_decref(files);
		files = json_object();
	}
	struct aa_file_source src;
	aa_file_source_json(files, &src);
	int bad_spec = !job || st < 0 || !json_is_object(spec) || aa_job_spec_from_json_files(spec, &src, &job->spec, &err);
	json_decref(files);
	if (bad_spec) {
		fprintf(stderr, "aalabd: skipping %s: %s\n", path, err.message[0] ? err.message : "bad state or spec");
		free(job);
		json_decref(o);
		return NULL;
	}
	snprintf(job->id, sizeof job->id, "%s", id);
	snprintf(job->client, sizeof job->client, "%s", client ? client : "");
	job->state = st;
	job->spec_json = json_incref(spec);
	job->submitted_at = json_number_value(json_object_get(o, "submitted_at"));
	job->started_at = json_number_value(json_object_get(o, "started_at"));
	job->finished_at = json_number_value(json_object_get(o, "finished_at"));
	job->done = (int)json_integer_value(json_object_get(o, "done"));
	job->total = (int)json_integer_value(json_object_get(o, "total"));
	job->bytes = (uint64_t)json_integer_value(json_object_get(o, "bytes"));
	job->inline_scene = json_is_true(json_object_get(o, "inline_scene"));
	job->interruptions = (int)json_integer_value(json_object_get(o, "interruptions"));
	job->run = (unsigned long)json_integer_value(json_object_get(o, "run"));
	json_t *e = json_object_get(o, "error");
	if (e) {
		const char *code = json_string_value(json_object_get(e, "code"));
		job->error.code = AA_ERR_INTERNAL;
		for (int c = AA_ERR_INVALID; c <= AA_ERR_INTERNAL; c++)
			if (code && !strcmp(code, aa_error_code_name(c)))
				job->error.code = c;
		snprintf(job->error.message, sizeof job->error.message, "%s",
			 json_string_value(json_object_get(e, "message")) ? json_string_value(json_object_get(e, "message")) : "");
		snprintf(job->error.path, sizeof job->error.path, "%s",
			 json_string_value(json_object_get(e, "path")) ? json_string_value(json_object_get(e, "path")) : "");
	}
	json_t *summary = json_object_get(o, "summary"), *compare = json_object_get(o, "compare");
	if (summary)
		job->summary = json_incref(summary);
	if (json_is_object(compare))
		job->compare = json_incref(compare);
	json_decref(o);
	if (job->state == JOB_RUNNING) {
		/* the daemon died during this job: run it again from the start, unless it has done so before
		 * often enough to suspect the job itself (a poison job) */
		char dir[1200];
		job_dir(s, job, dir, sizeof dir);
		job->interruptions++;
		if (s->max_interruptions > 0 && job->interruptions >= s->max_interruptions) {
			clear_results(dir, true);
			job->state = JOB_FAILED;
			job->finished_at = now_s();
			aa_error_set(&job->error, AA_ERR_INTERNAL, "", "the daemon stopped during this job %d times in a "
				     "row (a crash, kill -9 or power loss); not run again (max-job-interruptions %d)",
				     job->interruptions, s->max_interruptions);
			fprintf(stderr, "aalabd: job %s was interrupted %d times in a row; it is failed\n", job->id,
				job->interruptions);
			/* its log ends where the crash cut it: close it with the failure, as a run would */
			store_load_events(s, job);
			json_t *ev = json_pack("{ss ss sI sI s{ss ss ss}}", "event", "job_failed", "job", job->id, "seq",
					       (json_int_t)job->event_count + 1, "run", (json_int_t)job->run, "error",
					       "code", aa_error_code_name(job->error.code), "message", job->error.message,
					       "path", "");
			char *line = json_dumps(ev, JSON_COMPACT);
			json_decref(ev);
			if (line)
				store_append_event(s, job, line);
			store_rewrite_events(s, job);
			job->log_complete = true;
			job->bytes = tree_bytes(dir);
		} else {
			clear_results(dir, false);
			job->state = JOB_QUEUED;
			job->started_at = 0;
			job->done = 0;
			fprintf(stderr, "aalabd: job %s was interrupted; it will run again\n", job->id);
		}
		store_save(s, job);
	}
	if (job->state == JOB_QUEUED)
		job->events_loaded = true; /* nothing to load: the run starts a new log */
	return job;
}

static int mkdir_p(const char *dir)
{
	char tmp[1024];
	snprintf(tmp, sizeof tmp, "%s", dir);
	for (char *p = tmp + 1; *p; p++)
		if (*p == '/') {
			*p = 0;
			if (mkdir(tmp, 0750) != 0 && errno != EEXIST)
				return -1;
			*p = '/';
		}
	return mkdir(tmp, 0750) != 0 && errno != EEXIST ? -1 : 0;
}

int store_lock_state_dir(const char *state_dir, bool hold, int *fd, char *err, size_t err_size)
{
	char path[1100];
	*fd = -1;
	if ((size_t)snprintf(path, sizeof path, "%s/aalabd.lock", state_dir) >= sizeof path) {
		snprintf(err, err_size, "state-dir: '%s' is too long", state_dir);
		return -1;
	}
	if (hold && mkdir_p(state_dir)) {
		snprintf(err, err_size, "state-dir: cannot create '%s': %s", state_dir, strerror(errno));
		return -1;
	}
	/* O_NONBLOCK and O_NOFOLLOW: a FIFO or a link put there must not block or redirect the daemon */
	int lock = open(path, (hold ? O_RDWR | O_CREAT : O_RDONLY) | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK, 0600);
	if (lock < 0 && !hold && errno == ENOENT)
		return 0; /* no daemon has used the folder yet */
	struct stat st;
	if (lock < 0 || fstat(lock, &st) != 0 || !S_ISREG(st.st_mode)) {
		snprintf(err, err_size, "state-dir: cannot use the lock file '%s': %s", path,
			 lock < 0 ? strerror(errno) : "not a regular file");
		if (lock >= 0)
			close(lock);
		return -1;
	}
	if (flock(lock, LOCK_EX | LOCK_NB) != 0) {
		int e = errno;
		char pid[32] = "";
		ssize_t n = pread(lock, pid, sizeof pid - 1, 0);
		pid[n > 0 ? n : 0] = 0;
		pid[strspn(pid, "0123456789")] = 0;
		close(lock);
		if (e == EWOULDBLOCK)
			snprintf(err, err_size, "state-dir: '%s' is in use by another aalabd (PID %s, which holds %s); give "
				 "each daemon a state folder of its own", state_dir, pid[0] ? pid : "unknown", path);
		else
			snprintf(err, err_size, "state-dir: cannot lock '%s': %s", path, strerror(e));
		return -1;
	}
	if (!hold) {
		close(lock);
		return 0;
	}
	char pid[32];
	int len = snprintf(pid, sizeof pid, "%ld\n", (long)getpid());
	if (ftruncate(lock, 0) != 0 || pwrite(lock, pid, (size_t)len, 0) != len) {
		snprintf(err, err_size, "state-dir: cannot write '%s': %s", path, strerror(errno));
		close(lock);
		return -1;
	}
	*fd = lock;
	return 0;
}

int store_open(struct store *s, const char *state_dir, char *err, size_t err_size)
{
	pthread_mutex_init(&s->lock, NULL);
	pthread_cond_init(&s->work, NULL);
	s->next_id = 1;
	if ((size_t)snprintf(s->dir, sizeof s->dir, "%s/jobs", state_dir) >= sizeof s->dir - 20) {
		snprintf(err, err_size, "state-dir: '%s' is too long", state_dir);
		return -1;
	}
	if (mkdir_p(s->dir)) {
		snprintf(err, err_size, "state-dir: cannot create '%s': %s", s->dir, strerror(errno));
		return -1;
	}
	snprintf(s->reserve_path, sizeof s->reserve_path, "%s/reserve", state_dir);
	store_reserve_space(s);
	DIR *d = opendir(s->dir);
	if (!d) {
		snprintf(err, err_size, "state-dir: cannot read '%s': %s", s->dir, strerror(errno));
		return -1;
	}
	struct dirent *de;
	while ((de = readdir(d))) {
		if (strspn(de->d_name, "0123456789") != strlen(de->d_name) || strlen(de->d_name) >= 16)
			continue;
		unsigned long n = strtoul(de->d_name, NULL, 10);
		if (n >= s->next_id)
			s->next_id = n + 1;
		char job_path[1400];
		snprintf(job_path, sizeof job_path, "%s/%s", s->dir, de->d_name);
		remove_stale_temps(job_path);
		struct job *job = load_job(s, de->d_name);
		if (job)
			store_insert(s, job);
	}
	closedir(d);
	return 0;
}

void store_close(struct store *s)
{
	while (s->jobs) {
		struct job *j = s->jobs;
		s->jobs = j->next;
		job_free(j);
	}
	pthread_mutex_destroy(&s->lock);
	pthread_cond_destroy(&s->work);
}

struct job *store_find(struct store *s, const char *id)
{
	for (struct job *j = s->jobs; j; j = j->next)
		if (strcmp(j->id, id) == 0)
			return j;
	return NULL;
}

int store_count_active(struct store *s, const char *client)
{
	int n = 0;
	for (struct job *j = s->jobs; j; j = j->next)
		n += !job_state_final(j->state) && (!client || strcmp(j->client, client) == 0);
	return n;
}

int store_count_state(struct store *s, enum job_state st)
{
	int n = 0;
	for (struct job *j = s->jobs; j; j = j->next)
		n += j->state == st;
	return n;
}

struct job *store_submit(struct store *s, const struct aa_job_spec *spec, const char *client,
			 const char *scene_text, size_t scene_size, const json_t *method_files, struct aa_error *err)
{
	struct job *job = calloc(1, sizeof *job);
	if (!job) {
		aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
		return NULL;
	}
	job->spec = *spec;
	aa_job_spec_retain(&job->spec);
	job->spec_json = aa_job_spec_to_json(spec);
	snprintf(job->client, sizeof job->client, "%s", client);
	job->submitted_at = now_s();
	job->total = (int)aa_suite_total_units(spec);
	job->events_loaded = true;
	pthread_mutex_lock(&s->lock);
	snprintf(job->id, sizeof job->id, "%06lu", s->next_id++);
	char dir[1200];
	job_dir(s, job, dir, sizeof dir);
	job->inline_scene = scene_text != NULL;
	struct aa_error werr = {0};
	char *files_text = method_files ? json_dumps(method_files, JSON_COMPACT) : NULL;
	if (mkdir(dir, 0750) < 0 ||
	    (scene_text && aa_results_write_file_atomic(dir, "scene.json", scene_text, scene_size, &werr)) ||
	    (method_files && (!files_text || aa_results_write_file_atomic(dir, "method-files.json", files_text,
									   strlen(files_text), &werr))) ||
	    store_save(s, job)) {
		free(files_text);
		aa_error_set(err, AA_ERR_IO, "", "cannot write the job to %s: %s", dir, strerror(errno));
		pthread_mutex_unlock(&s->lock);
		remove_tree(dir);
		job_free(job);
		return NULL;
	}
	free(files_text);
	store_insert(s, job);
	pthread_cond_signal(&s->work);
	pthread_mutex_unlock(&s->lock);
	return job;
}

int store_cancel(struct store *s, struct job *job, struct aa_error *err)
{
	if (job_state_final(job->state))
		return aa_error_set(err, AA_ERR_INVALID, "job", "job %s is already %s", job->id,
				    job_state_name(job->state));
	job->cancel = true;
	if (job == s->running)
		atomic_store(&s->interrupt, 1); /* the engine stops at its next piece of GPU work */
	if (job->state == JOB_QUEUED) {
		job->state = JOB_CANCELLED;
		job->finished_at = now_s();
		store_append_event(s, job, NULL);
		job->log_complete = true;
		store_save(s, job);
	}
	return 0;
}

void store_append_event(struct store *s, struct job *job, char *line)
{
	(void)s;
	if (!line) {
		/* the final event of a job cancelled before it ran */
		json_t *e = json_pack("{ss ss sI sI ss}", "event", "job_cancelled", "job", job->id, "seq",
				      (json_int_t)job->event_count + 1, "run", (json_int_t)job->run, "state", "cancelled");
		line = json_dumps(e, JSON_COMPACT);
		json_decref(e);
		if (!line)
			return;
	}
	if (job->event_count == job->event_cap) {
		unsigned long cap = job->event_cap ? job->event_cap * 2 : 32;
		char **ev = realloc(job->events, cap * sizeof *ev);
		if (!ev) {
			free(line);
			return;
		}
		job->events = ev;
		job->event_cap = cap;
	}
	job->events[job->event_count++] = line;
}

void store_load_events(struct store *s, struct job *job)
{
	if (job->events_loaded)
		return;
	job->events_loaded = true;
	char path[1400];
	snprintf(path, sizeof path, "%s/%s/events.jsonl", s->dir, job->id);
	FILE *f = fopen(path, "r");
	if (!f)
		return;
	char *line = NULL;
	size_t cap = 0;
	ssize_t n;
	while ((n = getline(&line, &cap, f)) > 0) {
		if (line[n - 1] != '\n')
			break; /* the last line of a log cut short by a crash */
		line[n - 1] = 0;
		store_append_event(s, job, strdup(line));
	}
	free(line);
	fclose(f);
	job->log_complete = job_state_final(job->state);
}

static void delete_job(struct store *s, struct job *victim)
{
	char dir[1200];
	job_dir(s, victim, dir, sizeof dir);
	remove_tree(dir);
	for (struct job **p = &s->jobs; *p; p = &(*p)->next)
		if (*p == victim) {
			*p = victim->next;
			break;
		}
	job_free(victim);
}

void job_hold(struct job *job)
{
	job->holds++;
}

void job_release(struct store *s, struct job *job)
{
	job->holds--;
	if (job_state_final(job->state))
		store_apply_retention(s); /* a job kept past the limits only because it was held goes now */
}

void store_apply_retention(struct store *s)
{
	for (;;) {
		int finished = 0;
		uint64_t bytes = 0;
		struct job *oldest = NULL;
		for (struct job *j = s->jobs; j; j = j->next)
			if (job_state_final(j->state)) {
				finished++;
				bytes += j->bytes;
				if (!oldest && j->holds == 0)
					oldest = j;
			}
		bool over = (s->retention_jobs > 0 && finished > s->retention_jobs) ||
			    (s->retention_bytes > 0 && bytes > s->retention_bytes && finished > 1);
		if (!over || !oldest)
			return;
		delete_job(s, oldest);
	}
}

uint64_t store_measure(struct store *s, struct job *job)
{
	char dir[1200];
	job_dir(s, job, dir, sizeof dir);
	return tree_bytes(dir);
}

void store_clear_results(struct store *s, struct job *job)
{
	char dir[1200];
	job_dir(s, job, dir, sizeof dir);
	clear_results(dir, false);
}

void store_remove_partial(struct store *s, struct job *job)
{
	char dir[1200];
	job_dir(s, job, dir, sizeof dir);
	clear_results(dir, true);
}
