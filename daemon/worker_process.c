/* The worker process (aalabd(8), allow-user-methods): with user methods allowed, a user's shader runs on
 * the device, and a shader that never ends or crashes the driver must not take the daemon with it. So
 * the engine lives in a child process (aalabd --worker-process) that the worker thread hands one job at a
 * time over a socket pair, as JSON lines:
 *   thread -> process: {"type": "job", "dir", "spec", "inline_scene", "scene_cache_bytes"}
 *   process -> thread: {"type": "event", "event": {...}} and {"type": "progress", "done", "total"}, each
 *                      answered {"stop": bool} (the job was cancelled); then {"type": "done", ...}
 * The process renders into the job's directory as the thread would; the thread keeps the store, the event
 * log and the bookkeeping (worker_run.c), so the protocol and the store are what they are without it. At the
 * job's time limit, when the process dies, or when a cancelled job does not stop, the thread kills it,
 * fails (or cancels) the job with the reason and starts a fresh process for the next job. */
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <poll.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "config.h"
#include "methods/glsl_compile.h"
#include "methods/user_method.h"
#include "worker_job.h"
#include "worker_process.h"
#include "run/job_spec.h"

#define LINE_MAX_BYTES (16u << 20) /* the process's lines: events and a summary, far below this */
#define START_SECONDS 120          /* opening the device */
#define CANCEL_GRACE_SECONDS 5     /* a cancelled job stops at its next event; a hung one is killed */
#define STOP_SECONDS 10            /* at shutdown, before the process is killed */

struct worker_process {
	pid_t pid;
	int fd;
	char *buf;                /* bytes read and not yet returned as lines */
	size_t len, cap;
	char device[256];
};

static double now_ms(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

/* ---------------------------------------------------------------- JSON lines over the socket pair */

static int send_json(int fd, json_t *msg)
{
	char *text = json_dumps(msg, JSON_COMPACT);
	json_decref(msg);
	if (!text)
		return -1;
	size_t n = strlen(text);
	text[n] = '\n'; /* json_dumps leaves room for the NUL, which the newline takes */
	int rc = 0;
	for (size_t off = 0; off < n + 1 && rc == 0;) {
		ssize_t w = send(fd, text + off, n + 1 - off, MSG_NOSIGNAL);
		if (w < 0 && errno == EINTR)
			continue;
		if (w <= 0)
			rc = -1;
		else
			off += (size_t)w;
	}
	free(text);
	return rc;
}

/* The next line as JSON: 1 and *msg, 0 when timeout_ms passed first (-1: wait for ever), -1 at end of
 * stream, on an error, an over-long line or a line that is not a JSON object. */
static int read_json(struct worker_process *p, json_t **msg, int timeout_ms)
{
	*msg = NULL;
	const double deadline = now_ms() + timeout_ms;
	for (;;) {
		char *nl = p->len ? memchr(p->buf, '\n', p->len) : NULL;
		if (nl) {
			size_t n = (size_t)(nl - p->buf);
			*msg = json_loadb(p->buf, n, 0, NULL);
			memmove(p->buf, nl + 1, p->len - n - 1);
			p->len -= n + 1;
			if (!json_is_object(*msg)) {
				json_decref(*msg);
				*msg = NULL;
				return -1;
			}
			return 1;
		}
		if (p->len >= LINE_MAX_BYTES)
			return -1;
		int wait = -1;
		if (timeout_ms >= 0) {
			double left = deadline - now_ms();
			if (left <= 0)
				return 0;
			wait = (int)left + 1;
		}
		struct pollfd pfd = {p->fd, POLLIN, 0};
		int r = poll(&pfd, 1, wait);
		if (r < 0 && errno == EINTR)
			continue;
		if (r < 0)
			return -1;
		if (r == 0)
			continue; /* the deadline is checked above */
		if (p->cap - p->len < 65536) {
			size_t cap = p->cap ? p->cap * 2 : 131072;
			char *b = realloc(p->buf, cap);
			if (!b)
				return -1;
			p->buf = b;
			p->cap = cap;
		}
		ssize_t got = read(p->fd, p->buf + p->len, p->cap - p->len);
		if (got < 0 && errno == EINTR)
			continue;
		if (got <= 0)
			return -1;
		p->len += (size_t)got;
	}
}

static enum aa_error_code code_from_name(const char *name)
{
	for (int c = AA_ERR_INVALID; c <= AA_ERR_INTERNAL; c++)
		if (name && !strcmp(name, aa_error_code_name(c)))
			return c;
	return AA_ERR_INTERNAL;
}

/* ---------------------------------------------------------------- the process */

/* The files a client sent with the job (method-files.json in its directory), the only place user methods
 * are read from here. */
static json_t *job_method_files(const char *dir)
{
	char path[1400];
	snprintf(path, sizeof path, "%s/method-files.json", dir);
	json_t *files = json_load_file(path, 0, NULL);
	if (!json_is_object(files)) {
		json_decref(files);
		files = json_object();
	}
	return files;
}

struct child {
	struct worker_process io;
	bool parent_gone;
};

/* A cancel or shutdown reaches the process as SIGUSR1 carrying the number of the job it stops (the
 * thread sends it again until the job ends: one that comes before the job is known is dropped); the
 * engine sees the flag between the bounded pieces of its GPU work (aa_engine_set_interrupt). */
static atomic_int child_interrupt, child_job_number;

static void on_stop_signal(int sig, siginfo_t *info, void *context)
{
	(void)sig; (void)context;
	if (info->si_value.sival_int == atomic_load(&child_job_number))
		atomic_store(&child_interrupt, 1);
}

static int child_ask(struct child *c, json_t *msg)
{
	json_t *reply = NULL;
	if (c->parent_gone || send_json(c->io.fd, msg) || read_json(&c->io, &reply, -1) != 1) {
		c->parent_gone = true;
		return 1; /* stop: nobody waits for this job any more */
	}
	int stop = json_is_true(json_object_get(reply, "stop"));
	json_decref(reply);
	return stop;
}

static int child_event(void *ctx, json_t *ev)
{
	return child_ask(ctx, json_pack("{ss so}", "type", "event", "event", ev));
}

static int child_progress(void *ctx, int done, int total)
{
	return child_ask(ctx, json_pack("{ss si si}", "type", "progress", "done", done, "total", total));
}

static json_t *scene_stats_json(struct scene_cache *scenes)
{
	struct scene_cache_stats st;
	scene_cache_stats(scenes, &st);
	return json_pack("{sI sI sI sI sI sI si}", "hits", (json_int_t)st.hits, "misses", (json_int_t)st.misses,
			 "reloads", (json_int_t)st.reloads, "evictions", (json_int_t)st.evictions, "bytes",
			 (json_int_t)st.bytes, "budget", (json_int_t)st.budget, "entries", st.entries);
}

static void child_run(struct child *c, struct aa_engine *engine, struct scene_cache *scenes, json_t *msg)
{
	const char *dir = json_string_value(json_object_get(msg, "dir"));
	json_t *budget = json_object_get(msg, "scene_cache_bytes");
	atomic_store(&child_interrupt, 0);
	atomic_store(&child_job_number, (int)json_integer_value(json_object_get(msg, "number")));
	if (json_is_integer(budget)) {
		scene_cache_set_budget(scenes, (uint64_t)json_integer_value(budget));
		aa_engine_set_upload_budget(engine, (uint64_t)json_integer_value(budget));
	}
	struct worker_outcome out = {0};
	struct aa_job_spec spec;
	json_t *files = job_method_files(dir ? dir : ".");
	struct aa_file_source src;
	aa_file_source_json(files, &src);
	if (!dir || aa_job_spec_from_json_files(json_object_get(msg, "spec"), &src, &spec, &out.err)) {
		out.rc = -1;
		if (!out.err.message[0])
			aa_error_set(&out.err, AA_ERR_INTERNAL, "", "the worker process got a job without a directory");
	} else {
		struct worker_sink sink = {.event = child_event, .progress = child_progress, .ctx = c};
		worker_render(engine, scenes, &spec, json_is_true(json_object_get(msg, "inline_scene")), dir, &sink, &out);
		aa_job_spec_release(&spec);
	}
	json_decref(files);
	struct aa_upload_stats up = aa_engine_upload_stats(engine);
	struct aa_reference_cache_stats refs;
	aa_engine_reference_cache_stats(engine, &refs);
	json_t *done = json_pack("{ss si s{ss ss ss} si sf s{sI sI sI} so s{sI sI sI sI sI sI}}", "type", "done", "rc",
				 out.rc, "error", "code", aa_error_code_name(out.err.code), "message", out.err.message,
				 "path", out.err.path, "failed_writes", out.failed_writes, "busy", out.busy, "gpu_scenes",
				 "hits", (json_int_t)up.hits, "misses", (json_int_t)up.misses, "bytes",
				 (json_int_t)up.bytes, "scene_cache", scene_stats_json(scenes), "references", "hits",
				 (json_int_t)refs.hits, "misses", (json_int_t)refs.misses, "bytes_read",
				 (json_int_t)refs.bytes_read, "bytes_written", (json_int_t)refs.bytes_written, "evictions",
				 (json_int_t)refs.evictions, "discarded", (json_int_t)refs.discarded);
	if (out.summary)
		json_object_set_new(done, "summary", out.summary);
	if (!c->parent_gone && send_json(c->io.fd, done))
		c->parent_gone = true;
}

int worker_process_main(int argc, char **argv)
{
	/* the daemon decides when this process ends (it closes the socket, or kills it): a Ctrl-C or a
	 * SIGTERM to the process group is the daemon's to handle */
	signal(SIGINT, SIG_IGN);
	signal(SIGTERM, SIG_IGN);
	signal(SIGHUP, SIG_IGN);
	signal(SIGPIPE, SIG_IGN);
	struct sigaction stop = {.sa_sigaction = on_stop_signal, .sa_flags = SA_SIGINFO | SA_RESTART};
	sigemptyset(&stop.sa_mask);
	sigaction(SIGUSR1, &stop, NULL);
	struct config cfg;
	config_defaults(&cfg);
	char err[600];
	struct child c = {.io = {.fd = argc > 2 ? atoi(argv[2]) : -1}};
	for (int i = 3; i + 1 < argc; i += 2)
		if (strncmp(argv[i], "--", 2) || config_set(&cfg, argv[i] + 2, argv[i + 1], err, sizeof err)) {
			fprintf(stderr, "aalabd worker process: bad argument %s\n", argv[i]);
			return 2;
		}
	if (c.io.fd < 0)
		return 2;
	struct aa_engine *engine = NULL;
	struct aa_error aerr = {0};
	struct aa_engine_options eo = {.device = cfg.device[0] ? cfg.device : NULL};
	if (aa_engine_create(&eo, &engine, &aerr)) {
		send_json(c.io.fd, json_pack("{ss ss}", "type", "failed", "message", aerr.message));
		close(c.io.fd);
		return 1;
	}
	aa_engine_set_upload_budget(engine, cfg.scene_cache_bytes);
	aa_engine_set_interrupt(engine, &child_interrupt);
	char references[1100];
	config_reference_cache_dir(&cfg, references, sizeof references);
	if (references[0] && aa_engine_set_reference_cache(engine, references, cfg.reference_cache_bytes, &aerr)) {
		send_json(c.io.fd, json_pack("{ss ss}", "type", "failed", "message", aerr.message));
		aa_engine_destroy(engine);
		close(c.io.fd);
		return 1;
	}
	struct scene_cache *scenes = scene_cache_create(cfg.scene_cache_bytes);
	/* compiled user shaders are kept with the daemon's state, not in a user's home */
	char cache[1100];
	snprintf(cache, sizeof cache, "%s/cache", cfg.state_dir);
	aa_glsl_set_cache_dir(cache);
	int status = 0;
	if (!scenes || send_json(c.io.fd, json_pack("{ss ss si}", "type", "ready", "device",
						   aa_engine_device_name(engine), "pid", (int)getpid())))
		status = 1;
	while (status == 0 && !c.parent_gone) {
		json_t *msg;
		if (read_json(&c.io, &msg, -1) != 1)
			break; /* the daemon closed the socket: its shutdown */
		const char *type = json_string_value(json_object_get(msg, "type"));
		if (type && !strcmp(type, "job"))
			child_run(&c, engine, scenes, msg);
		json_decref(msg);
	}
	scene_cache_destroy(scenes);
	aa_engine_destroy(engine);
	free(c.io.buf);
	close(c.io.fd);
	return status;
}

/* ---------------------------------------------------------------- the worker thread's side */

/* Kills the process (if any) and reaps it; says how it ended in why. */
static void process_end(struct store *s, bool kill_it, char *why, size_t why_size)
{
	struct worker_process *p = s->process;
	if (!p || p->pid <= 0) {
		if (why)
			snprintf(why, why_size, "it had not started");
		return;
	}
	if (kill_it)
		kill(p->pid, SIGKILL);
	close(p->fd);
	p->fd = -1;
	int status = 0;
	pid_t r;
	/* closing the socket ends an idle process; one that is not idle was killed above */
	while ((r = waitpid(p->pid, &status, 0)) < 0 && errno == EINTR)
		;
	if (why && r == p->pid && WIFSIGNALED(status))
		snprintf(why, why_size, "signal %d, %s", WTERMSIG(status), strsignal(WTERMSIG(status)));
	else if (why && r == p->pid)
		snprintf(why, why_size, "exit status %d", WEXITSTATUS(status));
	else if (why)
		snprintf(why, why_size, "%s", strerror(errno));
	p->pid = 0;
	p->len = 0;
}

/* Reaps a process that must end now: it did not stop at shutdown, or spoke out of turn. */
static void process_kill(struct store *s)
{
	process_end(s, true, NULL, 0);
}

/* Forks and execs this program as the worker process, then waits for it to open the device. */
static int process_spawn(struct store *s, char *err, size_t err_size)
{
	struct worker_process *p = s->process;
	int sv[2];
	if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sv) != 0) {
		snprintf(err, err_size, "cannot make a socket pair: %s", strerror(errno));
		return -1;
	}
	char budget[32];
	snprintf(budget, sizeof budget, "%llu", (unsigned long long)s->process_scene_budget);
	/* everything the child needs is made before fork: after it, only system calls until exec */
	char *argv[] = {"/proc/self/exe", "--worker-process", "3", "--state-dir", s->state_dir,
			"--scene-cache-bytes", budget, "--reference-cache", s->reference_cache[0] ? s->reference_cache : "off",
			"--reference-cache-size", s->reference_cache_bytes, s->device[0] ? "--device" : NULL, s->device,
			NULL};
	const pid_t parent = getpid();
	double t0 = now_ms();
	pid_t pid = fork();
	if (pid < 0) {
		snprintf(err, err_size, "cannot fork: %s", strerror(errno));
		close(sv[0]);
		close(sv[1]);
		return -1;
	}
	if (pid == 0) {
		/* dies with the daemon, even on kill -9 */
		prctl(PR_SET_PDEATHSIG, SIGKILL);
		if (getppid() != parent)
			_exit(1);
		if (sv[1] == 3)
			fcntl(3, F_SETFD, 0);
		else if (dup2(sv[1], 3) < 0)
			_exit(1);
		close_range(4, ~0U, 0);
		/* the process renders: below the loop, like the worker thread (render_priority.c) */
		(void)setpriority(PRIO_PROCESS, 0, s->render_nice_value);
		execv("/proc/self/exe", argv);
		_exit(127);
	}
	close(sv[1]);
	p->pid = pid;
	p->fd = sv[0];
	p->len = 0;
	json_t *msg = NULL;
	int r = read_json(p, &msg, START_SECONDS * 1000);
	const char *type = r == 1 ? json_string_value(json_object_get(msg, "type")) : NULL;
	if (!type || strcmp(type, "ready") != 0) {
		const char *why = type && !strcmp(type, "failed") ? json_string_value(json_object_get(msg, "message")) : NULL;
		snprintf(err, err_size, "the worker process did not start: %s", why ? why : r == 0 ? "timed out" : "it ended");
		json_decref(msg);
		process_kill(s);
		return -1;
	}
	snprintf(p->device, sizeof p->device, "%s", json_string_value(json_object_get(msg, "device")) ?
						      json_string_value(json_object_get(msg, "device")) : "?");
	json_decref(msg);
	fprintf(stderr, "aalabd: worker process %ld ready in %.2f s\n", (long)pid, (now_ms() - t0) / 1000.0);
	return 0;
}

int worker_process_start(struct store *s, char *err, size_t err_size)
{
	s->process = calloc(1, sizeof *s->process);
	if (!s->process) {
		snprintf(err, err_size, "out of memory");
		return -1;
	}
	s->process->fd = -1;
	if (process_spawn(s, err, err_size))
		return -1;
	snprintf(s->device_name, sizeof s->device_name, "%s", s->process->device);
	return 0;
}

void worker_process_stop(struct store *s)
{
	struct worker_process *p = s->process;
	if (!p)
		return;
	if (p->pid > 0) {
		/* an idle process ends when its socket closes; one that does not is killed */
		shutdown(p->fd, SHUT_RDWR);
		double deadline = now_ms() + STOP_SECONDS * 1000.0;
		int status;
		while (waitpid(p->pid, &status, WNOHANG) == 0 && now_ms() < deadline)
			usleep(20000);
		process_end(s, true, NULL, 0);
	}
	free(p->buf);
	free(p);
	s->process = NULL;
}

static void apply_done(struct store *s, json_t *msg, struct worker_outcome *out)
{
	json_t *e = json_object_get(msg, "error");
	out->rc = (int)json_integer_value(json_object_get(msg, "rc"));
	out->err.code = out->rc ? code_from_name(json_string_value(json_object_get(e, "code"))) : AA_OK;
	snprintf(out->err.message, sizeof out->err.message, "%s",
		 json_string_value(json_object_get(e, "message")) ? json_string_value(json_object_get(e, "message")) : "");
	snprintf(out->err.path, sizeof out->err.path, "%s",
		 json_string_value(json_object_get(e, "path")) ? json_string_value(json_object_get(e, "path")) : "");
	out->failed_writes = (int)json_integer_value(json_object_get(msg, "failed_writes"));
	out->busy = json_number_value(json_object_get(msg, "busy"));
	out->summary = json_incref(json_object_get(msg, "summary"));
	if (out->rc == 0 && !out->summary)
		out->summary = json_array();
	json_t *g = json_object_get(msg, "gpu_scenes"), *c = json_object_get(msg, "scene_cache");
	json_t *r = json_object_get(msg, "references");
	pthread_mutex_lock(&s->lock);
	s->references.hits = (uint64_t)json_integer_value(json_object_get(r, "hits"));
	s->references.misses = (uint64_t)json_integer_value(json_object_get(r, "misses"));
	s->references.bytes_read = (uint64_t)json_integer_value(json_object_get(r, "bytes_read"));
	s->references.bytes_written = (uint64_t)json_integer_value(json_object_get(r, "bytes_written"));
	s->references.evictions = (uint64_t)json_integer_value(json_object_get(r, "evictions"));
	s->references.discarded = (uint64_t)json_integer_value(json_object_get(r, "discarded"));
	s->gpu_scenes.hits = (uint64_t)json_integer_value(json_object_get(g, "hits"));
	s->gpu_scenes.misses = (uint64_t)json_integer_value(json_object_get(g, "misses"));
	s->gpu_scenes.bytes = (uint64_t)json_integer_value(json_object_get(g, "bytes"));
	s->process_scenes.hits = (uint64_t)json_integer_value(json_object_get(c, "hits"));
	s->process_scenes.misses = (uint64_t)json_integer_value(json_object_get(c, "misses"));
	s->process_scenes.reloads = (uint64_t)json_integer_value(json_object_get(c, "reloads"));
	s->process_scenes.evictions = (uint64_t)json_integer_value(json_object_get(c, "evictions"));
	s->process_scenes.bytes = (uint64_t)json_integer_value(json_object_get(c, "bytes"));
	s->process_scenes.budget = (uint64_t)json_integer_value(json_object_get(c, "budget"));
	s->process_scenes.entries = (int)json_integer_value(json_object_get(c, "entries"));
	pthread_mutex_unlock(&s->lock);
}

/* Relays the job's events and progress until the process says it is done; stops it at the time limit,
 * when it dies, when it speaks out of turn, or when a cancelled job does not stop. Returns 0 if the
 * process is still usable. */
static int relay(struct store *s, struct worker_run *run, struct worker_outcome *out)
{
	struct worker_process *p = s->process;
	struct job *job = run->job;
	pthread_mutex_lock(&s->lock);
	const int limit = s->job_time_limit_s;
	const uint64_t budget = s->process_scene_budget;
	static int job_number; /* names the job a stop signal is for (the worker thread's only) */
	job_number = job_number % 1000000000 + 1;
	json_t *msg = json_pack("{ss ss sO sb sI si}", "type", "job", "dir", run->dir, "spec", job->spec_json,
				"inline_scene", job->inline_scene, "scene_cache_bytes", (json_int_t)budget, "number",
				job_number);
	pthread_mutex_unlock(&s->lock);
	const double deadline = limit > 0 ? now_ms() + limit * 1000.0 : 0;
	double cancelled_at = 0;
	char why[200];
	out->rc = -1;
	if (send_json(p->fd, msg)) {
		process_end(s, true, why, sizeof why);
		return aa_error_set(&out->err, AA_ERR_GPU, "", "the GPU worker process had ended (%s); a fresh one "
				    "runs the next job", why);
	}
	for (;;) {
		json_t *m = NULL;
		int r = read_json(p, &m, 250);
		if (r == 1) {
			const char *type = json_string_value(json_object_get(m, "type"));
			if (type && !strcmp(type, "done")) {
				apply_done(s, m, out);
				json_decref(m);
				return 0;
			}
			int stop = 0;
			r = -1; /* anything but these is not this protocol: the process is not to be trusted any more */
			if (type && !strcmp(type, "event") && json_is_object(json_object_get(m, "event"))) {
				stop = worker_publish(run, json_incref(json_object_get(m, "event")));
				r = 1;
			} else if (type && !strcmp(type, "progress")) {
				stop = worker_progress(run, (int)json_integer_value(json_object_get(m, "done")),
						       (int)json_integer_value(json_object_get(m, "total")));
				r = 1;
			}
			json_decref(m);
			/* answered: on to the time limit, checked after every message as after every wait */
			r = r == 1 && send_json(p->fd, json_pack("{sb}", "stop", stop)) == 0 ? 0 : -1;
		}
		if (r < 0) {
			process_end(s, true, why, sizeof why);
			fprintf(stderr, "aalabd: job %s: the worker process died (%s)\n", job->id, why);
			return aa_error_set(&out->err, AA_ERR_GPU, "", "the GPU worker process died during this job (%s): "
					    "a crash in the driver or a shader; a fresh process runs the next job", why);
		}
		if (deadline > 0 && now_ms() >= deadline) {
			process_end(s, true, why, sizeof why);
			fprintf(stderr, "aalabd: job %s ran over its time limit of %d s: worker process killed\n", job->id,
				limit);
			return aa_error_set(&out->err, AA_ERR_LIMIT, "", "the job ran over its time limit of %d s "
					    "(job-time-limit, aalabd(8)): its GPU work was stopped (a shader that never "
					    "ends?) and a fresh worker process runs the next job", limit);
		}
		pthread_mutex_lock(&s->lock);
		bool cancel = job->cancel;
		pthread_mutex_unlock(&s->lock);
		if (cancel && cancelled_at == 0)
			cancelled_at = now_ms();
		if (cancel) /* stops it between two pieces of GPU work; again until it ends (see on_stop_signal) */
			sigqueue(p->pid, SIGUSR1, (union sigval){.sival_int = job_number});
		if (cancel && now_ms() - cancelled_at > CANCEL_GRACE_SECONDS * 1000.0) {
			/* a cancelled job stops at its next event; one stuck in a shader never gets there */
			process_end(s, true, why, sizeof why);
			fprintf(stderr, "aalabd: job %s did not stop when cancelled: worker process killed\n", job->id);
			return aa_error_set(&out->err, AA_ERR_CANCELLED, "", "the job was cancelled");
		}
	}
}

void worker_process_run_job(struct store *s, struct job *job)
{
	struct worker_run run;
	worker_run_begin(s, job, &run);
	struct worker_outcome out = {0};
	char err[700];
	if (s->process->pid <= 0 && process_spawn(s, err, sizeof err)) {
		out.rc = -1;
		aa_error_set(&out.err, AA_ERR_GPU, "", "%s", err);
	} else {
		relay(s, &run, &out);
	}
	worker_run_end(&run, &out);
	/* a process that was stopped is replaced now, while the next job may still be on its way */
	pthread_mutex_lock(&s->lock);
	bool stopping = s->worker_stop;
	pthread_mutex_unlock(&s->lock);
	if (s->process->pid <= 0 && !stopping && process_spawn(s, err, sizeof err))
		fprintf(stderr, "aalabd: %s (tried again at the next job)\n", err);
}
