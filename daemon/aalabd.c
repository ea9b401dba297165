/* aalabd: the aalab daemon. Sets up the listeners, the job store and the GPU worker, then runs the event
 * loop until SIGTERM or SIGINT; SIGHUP reloads the configuration file. See aalabd(8). */
#include <arpa/inet.h>
#include <errno.h>
#include <netinet/in.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include "daemon.h"
#include "jobs.h"
#include "reference/reference_cache.h"
#include "render_priority.h"
#include "stream.h"
#include "util/file_open.h"
#include "util/socket_path.h"
#include "worker_process.h"

static volatile sig_atomic_t got_term, got_hup;
static struct loop *signal_loop;

static void on_signal(int sig)
{
	if (sig == SIGHUP)
		got_hup = 1;
	else
		got_term++;
	loop_wake(signal_loop);
}

static const char usage[] =
	"usage: aalabd [--socket PATH] [--state-dir DIR] [--tcp HOST:PORT --token-file FILE] [--http HOST:PORT]\n"
	"              [--config FILE] [--web-dir DIR] [--device SEL] [--OPTION VALUE ...] [--verbose] [--check]\n"
	"\n"
	"Serves aalab jobs over a Unix socket (default $XDG_RUNTIME_DIR/aalabd.sock, without it\n"
	"/tmp/aalabd-UID/aalabd.sock), optionally TCP with a bearer token and HTTP for dashboards. Every key\n"
	"of the configuration file is also an option (--max-connections 64, --retention-jobs 100, ...).\n"
	"--check only checks the configuration.\n"
	"See aalabd(8) and docs/protocol.md.\n";

/* Builds the configuration: defaults, then the file, then the command line (which wins). */
static int read_config(int argc, char **argv, struct config *cfg, char *err, size_t err_size)
{
	config_defaults(cfg);
	const char *file = NULL;
	for (int i = 1; i + 1 < argc; i++)
		if (!strcmp(argv[i], "--config"))
			file = argv[i + 1];
	if (file) {
		snprintf(cfg->config_file, sizeof cfg->config_file, "%s", file);
		if (config_load(cfg, file, err, err_size))
			return -1;
	}
	for (int i = 1; i < argc; i++) {
		const char *a = argv[i];
		if (!strcmp(a, "--verbose") || !strcmp(a, "-v")) {
			cfg->verbose++;
			continue;
		}
		if (!strcmp(a, "--check"))
			continue;
		if (strncmp(a, "--", 2)) {
			snprintf(err, err_size, "unexpected argument '%s' (options start with --, e.g. --socket PATH)", a);
			return -1;
		}
		if (strcmp(a, "--config") && !config_has_key(a + 2)) {
			snprintf(err, err_size, "unknown option '%s'", a);
			return -1;
		}
		if (i + 1 >= argc) {
			snprintf(err, err_size, "option '%s' needs a value", a);
			return -1;
		}
		if (strcmp(a, "--config") && config_set(cfg, a + 2, argv[i + 1], err, err_size))
			return -1;
		i++;
	}
	return 0;
}

/* Reads the bearer token. A token file others can read or write is refused, as ssh refuses a loose key:
 * whoever reads it can submit jobs. On failure the token in use stays as it was (a failed reload must not
 * turn authentication off). */
static int read_token(struct daemon *d, char *err, size_t err_size)
{
	if (!d->cfg.token_file[0]) {
		d->t.token[0] = 0;
		return 0;
	}
	char token[sizeof d->t.token] = "";
	struct stat st;
	struct aa_error aerr = {0};
	/* opened without blocking: a FIFO here must not freeze the loop on a reload (SIGHUP) */
	FILE *f = aa_file_fopen_regular(d->cfg.token_file, "token-file", &aerr);
	if (!f) {
		snprintf(err, err_size, "%s", aerr.message);
		return -1;
	}
	if (fstat(fileno(f), &st) < 0) {
		snprintf(err, err_size, "token-file: cannot read %s: %s", d->cfg.token_file, strerror(errno));
		fclose(f);
		return -1;
	}
	if (st.st_mode & 077) {
		snprintf(err, err_size, "token-file: %.400s is readable or writable by others (mode %03o); it must be a "
			 "file only its owner can read: chmod 600 %.400s", d->cfg.token_file, (unsigned)(st.st_mode & 0777),
			 d->cfg.token_file);
		fclose(f);
		return -1;
	}
	if (st.st_uid != geteuid()) {
		snprintf(err, err_size, "token-file: %.400s belongs to uid %u, not to the daemon's user (uid %u)",
			 d->cfg.token_file, (unsigned)st.st_uid, (unsigned)geteuid());
		fclose(f);
		return -1;
	}
	/* the first line, trimmed; a token longer than the buffer is refused, not cut (a hello must be able to
	 * carry it whole). The line is read in a larger buffer so that the limit counts the token alone. */
	char line[4096];
	size_t n = fread(line, 1, sizeof line - 1, f);
	line[n] = 0;
	bool longer = !memchr(line, '\n', n) && n == sizeof line - 1 && fgetc(f) != EOF;
	fclose(f);
	line[strcspn(line, "\r\n")] = 0;
	char *text = line + strspn(line, " \t");
	size_t len = strlen(text);
	while (len > 0 && (text[len - 1] == ' ' || text[len - 1] == '\t'))
		text[--len] = 0;
	if (longer || len >= sizeof token) {
		snprintf(err, err_size, "token-file: %.400s holds a token longer than %zu characters", d->cfg.token_file,
			 sizeof token - 1);
		return -1;
	}
	memcpy(token, text, len + 1);
	if (strlen(token) < 16) {
		snprintf(err, err_size, "token-file: %s must hold a token of at least 16 characters (spaces around it "
			 "do not count)", d->cfg.token_file);
		return -1;
	}
	memcpy(d->t.token, token, sizeof token);
	return 0;
}

/* Every check start-up makes before it opens anything, so that --check says what start-up would. */
static int check_config(struct daemon *d, char *err, size_t err_size)
{
	const struct config *c = &d->cfg;
	if (c->tcp[0] && !c->token_file[0]) {
		snprintf(err, err_size, "tcp: a token file is required (--token-file)");
		return -1;
	}
	if (c->tcp[0] && check_tcp_address("tcp", c->tcp, err, err_size))
		return -1;
	if (c->http[0] && check_tcp_address("http", c->http, err, err_size))
		return -1;
	if (strlen(c->socket_path) >= sizeof ((struct sockaddr_un *)0)->sun_path) {
		snprintf(err, err_size, "socket: path '%s' is too long", c->socket_path);
		return -1;
	}
	/* the state directory exists and is writable, or the nearest folder above it that exists is */
	char dir[sizeof c->state_dir];
	snprintf(dir, sizeof dir, "%s", c->state_dir);
	struct stat st;
	while (stat(dir, &st) != 0) {
		char *slash = strrchr(dir, '/');
		if (!slash || slash == dir) {
			snprintf(dir, sizeof dir, "%s", slash == dir ? "/" : ".");
			break;
		}
		*slash = 0;
	}
	if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode) || access(dir, W_OK | X_OK) != 0) {
		snprintf(err, err_size, "state-dir: cannot create or write '%.400s' (%.400s is not a writable folder)",
			 c->state_dir, dir);
		return -1;
	}
	return 0;
}

static int add_listener(struct daemon *d, int fd, enum conn_kind kind, bool tcp, const char *name)
{
	struct listener *l = &d->t.listeners[d->t.listener_count++];
	*l = (struct listener){.t = &d->t, .fd = fd, .kind = kind, .tcp = tcp,
				     .input = kind == CONN_HTTP ? http_input : line_input};
	snprintf(l->name, sizeof l->name, "%s", name);
	return 0;
}

static int open_listeners(struct daemon *d, int argc, char **argv, char *err, size_t err_size)
{
	int n = listen_systemd(&d->t, err, err_size);
	if (n < 0)
		return -1;
	for (int i = 0; i < d->t.listener_count; i++)
		d->t.listeners[i].t = &d->t;
	bool socket_flag = false;
	for (int i = 1; i < argc; i++)
		socket_flag |= !strcmp(argv[i], "--socket");
	/* with socket activation, only the sockets systemd passed (unless --socket is given too) */
	if (n == 0 || socket_flag) {
		struct aa_error serr = {0};
		if (aa_socket_dir_check(d->cfg.socket_path, true, &serr)) { /* /tmp/aalabd-UID: 0700, ours */
			snprintf(err, err_size, "%s", serr.message);
			return -1;
		}
		int fd = listen_unix(d->cfg.socket_path, err, err_size);
		if (fd < 0)
			return -1;
		add_listener(d, fd, CONN_PROTOCOL, false, d->cfg.socket_path);
	}
	char why[600];
	if (d->cfg.tcp[0]) {
		int fd = listen_tcp(d->cfg.tcp, why, sizeof why);
		if (fd < 0) {
			snprintf(err, err_size, "tcp: %s", why);
			return -1;
		}
		add_listener(d, fd, CONN_PROTOCOL, true, d->cfg.tcp);
	}
	if (d->cfg.http[0]) {
		int fd = listen_tcp(d->cfg.http, why, sizeof why);
		if (fd < 0) {
			snprintf(err, err_size, "http: %s", why);
			return -1;
		}
		/* a dashboard on loopback needs no token; elsewhere it needs the same bearer token */
		add_listener(d, fd, CONN_HTTP, !address_is_loopback(d->cfg.http), d->cfg.http);
	}
	return 0;
}

static void log_listeners(struct daemon *d)
{
	for (int i = 0; i < d->t.listener_count; i++) {
		struct listener *l = &d->t.listeners[i];
		struct sockaddr_storage ss;
		socklen_t len = sizeof ss;
		char where[320];
		snprintf(where, sizeof where, "%s", l->name);
		if (getsockname(l->fd, (struct sockaddr *)&ss, &len) == 0 && ss.ss_family == AF_INET) {
			struct sockaddr_in *in = (struct sockaddr_in *)&ss;
			char host[32];
			inet_ntop(AF_INET, &in->sin_addr, host, sizeof host);
			snprintf(where, sizeof where, "%s:%u", host, ntohs(in->sin_port));
		}
		/* tests read the port of "--http 127.0.0.1:0" from this line */
		fprintf(stderr, "aalabd: listening (%s) on %s\n", l->kind == CONN_HTTP ? "http" : l->tcp ? "tcp" : "unix",
			where);
	}
}

static void reload(struct daemon *d, int argc, char **argv)
{
	sd_notifyf("RELOADING=1");
	struct config fresh;
	char err[1024];
	if (read_config(argc, argv, &fresh, err, sizeof err)) {
		fprintf(stderr, "aalabd: reload failed, keeping the old configuration: %s\n", err);
	} else {
		config_apply_reload(&d->cfg, &fresh);
		if (read_token(d, err, sizeof err))
			fprintf(stderr, "aalabd: reload: %s; keeping the token in use\n", err);
		pthread_mutex_lock(&d->store->lock);
		d->store->retention_jobs = d->cfg.retention_jobs;
		d->store->retention_bytes = d->cfg.retention_bytes;
		store_apply_retention(d->store);
		pthread_mutex_unlock(&d->store->lock);
		scene_cache_set_budget(d->store->scenes, d->cfg.scene_cache_bytes);
		pthread_mutex_lock(&d->store->lock);
		d->store->job_time_limit_s = d->cfg.job_time_limit_s;
		d->store->process_scene_budget = d->cfg.scene_cache_bytes;
		pthread_mutex_unlock(&d->store->lock);
		fprintf(stderr, "aalabd: configuration reloaded\n");
	}
	sd_notifyf("READY=1");
}

struct runtime {
	struct daemon *d;
	int argc;
	char **argv;
	int watchdog_ms;
	double last_watchdog;
};

static void check_drained(struct daemon *d);

static void on_drain_tick(struct loop *loop, void *data)
{
	(void)loop;
	check_drained(data);
}

static void start_drain(struct daemon *d)
{
	d->draining = true;
	d->drain_started_ms = loop_now_ms();
	sd_notifyf("STOPPING=1\nSTATUS=draining: finishing the running job");
	fprintf(stderr, "aalabd: stopping: no new connections; the running job may take up to %d s\n",
		d->cfg.drain_timeout_s);
	for (int i = 0; i < d->t.listener_count; i++) {
		loop_unwatch(d->t.loop, d->t.listeners[i].fd);
		close(d->t.listeners[i].fd);
		if (!d->t.listeners[i].from_systemd && d->t.listeners[i].kind == CONN_PROTOCOL && !d->t.listeners[i].tcp)
			unlink(d->t.listeners[i].name);
	}
	d->t.listener_count = 0;
	worker_request_stop(d->store, d->cfg.drain_timeout_s == 0);
	/* the drain timeout is met within 0.1 s, not at the next 1 s tick (aalabd(8), STOPPING A JOB) */
	loop_every(d->t.loop, 100, on_drain_tick, d);
}

static void check_drained(struct daemon *d)
{
	pthread_mutex_lock(&d->store->lock);
	bool exited = d->store->worker_exited;
	pthread_mutex_unlock(&d->store->lock);
	if (!exited && loop_now_ms() - d->drain_started_ms > d->cfg.drain_timeout_s * 1000.0)
		worker_request_stop(d->store, true); /* the running job stays queued for the next start */
	bool flushed = true;
	for (struct conn *c = d->t.conns; c; c = c->next)
		flushed &= c->closed || conn_pending(c) == 0;
	/* once the worker is done, replies still queued get a short grace period */
	if (exited && (flushed || loop_now_ms() - d->drain_started_ms > (d->cfg.drain_timeout_s + 2) * 1000.0))
		loop_stop(d->t.loop);
}

static void on_wake(struct loop *loop, void *data)
{
	(void)loop;
	struct runtime *rt = data;
	struct daemon *d = rt->d;
	if (got_term && !d->draining)
		start_drain(d);
	if (got_term > 1) /* a second signal: stop now, the running job re-runs at the next start */
		worker_request_stop(d->store, true);
	if (got_hup) {
		got_hup = 0;
		reload(d, rt->argc, rt->argv);
	}
	conns_pump_watches(&d->t);
	conns_pump_input(&d->t); /* requests left for a later turn (conn.c) */
	if (d->draining)
		check_drained(d);
}

static void on_tick(struct loop *loop, void *data)
{
	(void)loop;
	struct runtime *rt = data;
	conns_tick(&rt->d->t);
	if (rt->watchdog_ms && loop_now_ms() - rt->last_watchdog >= rt->watchdog_ms) {
		sd_notifyf("WATCHDOG=1");
		rt->last_watchdog = loop_now_ms();
	}
	if (rt->d->draining)
		check_drained(rt->d);
}

int main(int argc, char **argv)
{
	/* the worker process (worker_process.c): started by aalabd itself when user methods are allowed */
	if (argc > 1 && !strcmp(argv[1], "--worker-process"))
		return worker_process_main(argc, argv);
	for (int i = 1; i < argc; i++)
		if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
			fputs(usage, stdout);
			return 0;
		} else if (!strcmp(argv[i], "--version")) {
			printf("aalabd %s\n", PACKAGE_VERSION);
			return 0;
		}
	static struct daemon daemon;
	struct daemon *d = &daemon;
	d->t.cfg = &d->cfg;
	d->t.handlers = &daemon_handlers;
	char err[1200];
	if (read_config(argc, argv, &d->cfg, err, sizeof err) || read_token(d, err, sizeof err) ||
	    check_config(d, err, sizeof err)) {
		fprintf(stderr, "aalabd: %s\n%s", err, usage);
		return 2;
	}
	for (int i = 1; i < argc; i++)
		if (!strcmp(argv[i], "--check")) {
			/* a daemon already on the state folder, as start-up would find it */
			int lock_fd;
			if (store_lock_state_dir(d->cfg.state_dir, false, &lock_fd, err, sizeof err)) {
				fprintf(stderr, "aalabd: %s\n", err);
				return 2;
			}
			/* every listener start-up would open, bound and closed again (a port another program holds,
			 * a socket folder that cannot be made) */
			if (open_listeners(d, argc, argv, err, sizeof err)) {
				fprintf(stderr, "aalabd: %s\n", err);
				return 2;
			}
			for (int l = 0; l < d->t.listener_count; l++) {
				close(d->t.listeners[l].fd);
				if (!d->t.listeners[l].from_systemd && d->t.listeners[l].kind == CONN_PROTOCOL && !d->t.listeners[l].tcp)
					unlink(d->t.listeners[l].name);
			}
			d->t.listener_count = 0;
			/* the device start-up would open (--device), opened and closed again */
			struct aa_engine *engine = NULL;
			struct aa_error aerr = {0};
			struct aa_engine_options eo = {.device = d->cfg.device[0] ? d->cfg.device : NULL};
			if (aa_engine_create(&eo, &engine, &aerr)) {
				fprintf(stderr, "aalabd: device: %s\n", aerr.message);
				return 2;
			}
			printf("aalabd: configuration ok (device %s)\n", aa_engine_device_name(engine));
			aa_engine_destroy(engine);
			return 0;
		}
	if (!d->cfg.web_dir[0]) {
		struct stat st;
		const char *src = AA_SOURCE_WEB_DIR "/index.html";
		snprintf(d->cfg.web_dir, sizeof d->cfg.web_dir, "%s",
			 stat(src, &st) == 0 ? AA_SOURCE_WEB_DIR : AA_INSTALLED_WEB_DIR);
	}
	signal(SIGPIPE, SIG_IGN);
	d->t.loop = loop_create();
	signal_loop = d->t.loop;
	d->started_ms = loop_now_ms();
	struct store *store = calloc(1, sizeof *store);
	if (!d->t.loop || !store) {
		fprintf(stderr, "aalabd: out of memory\n");
		return 1;
	}
	d->store = store;
	store->loop = d->t.loop;
	store->retention_jobs = d->cfg.retention_jobs;
	store->retention_bytes = d->cfg.retention_bytes;
	store->max_interruptions = d->cfg.max_job_interruptions;
	store->render_nice_value = render_nice_value(d->cfg.render_nice);
	int status = 1;
	/* one daemon per state folder, before anything in it is read or written; held until exit */
	int lock_fd;
	if (store_lock_state_dir(d->cfg.state_dir, true, &lock_fd, err, sizeof err)) {
		fprintf(stderr, "aalabd: %s\n", err);
		free(store);
		loop_destroy(d->t.loop);
		return 2;
	}
	if (store_open(store, d->cfg.state_dir, err, sizeof err)) {
		fprintf(stderr, "aalabd: %s\n", err);
		free(store);
		loop_destroy(d->t.loop);
		return 1;
	}
	store->scenes = scene_cache_create(d->cfg.scene_cache_bytes);
	store->use_process = d->cfg.allow_user_methods;
	store->job_time_limit_s = d->cfg.job_time_limit_s;
	store->process_scene_budget = d->cfg.scene_cache_bytes;
	_Static_assert(sizeof store->state_dir == sizeof d->cfg.state_dir && sizeof store->device == sizeof d->cfg.device,
		       "the worker process gets the configuration's paths");
	memcpy(store->state_dir, d->cfg.state_dir, sizeof store->state_dir);
	memcpy(store->device, d->cfg.device, sizeof store->device);
	char references[1100];
	config_reference_cache_dir(&d->cfg, references, sizeof references);
	snprintf(store->reference_cache, sizeof store->reference_cache, "%s", references);
	snprintf(store->reference_cache_bytes, sizeof store->reference_cache_bytes, "%llu",
		 (unsigned long long)d->cfg.reference_cache_bytes);
	struct aa_error aerr = {0};
	struct aa_reference_cache *sweep;
	/* the store's temporary files of writers that died (a crash, kill -9) go now, not at its first write */
	if (references[0] && aa_reference_cache_open(references, d->cfg.reference_cache_bytes, &sweep, &aerr) == 0) {
		aa_reference_cache_remove_stale(sweep, &aerr);
		aa_reference_cache_close(sweep);
	}
	struct aa_engine_options eo = {.device = d->cfg.device[0] ? d->cfg.device : NULL};
	if (open_listeners(d, argc, argv, err, sizeof err)) {
		fprintf(stderr, "aalabd: %s\n", err);
		goto out;
	}
	if (store->use_process) {
		/* user shaders may hang or crash the driver: the device is the worker process's, which the worker
		 * thread can kill and start again (aalabd(8), allow-user-methods) */
		if (worker_process_start(store, err, sizeof err)) {
			fprintf(stderr, "aalabd: %s\n", err);
			goto out;
		}
	} else if (render_engine_create(&eo, store->render_nice_value, &store->engine, &aerr)) {
		fprintf(stderr, "aalabd: %s\n", aerr.message);
		goto out;
	} else {
		snprintf(store->device_name, sizeof store->device_name, "%s", aa_engine_device_name(store->engine));
		/* scenes stay uploaded for later jobs within the same budget as the loaded scenes (set once: the
		 * engine belongs to the worker thread from here on) */
		aa_engine_set_upload_budget(store->engine, d->cfg.scene_cache_bytes);
		aa_engine_set_interrupt(store->engine, &store->interrupt); /* cancel and shutdown (worker.c) */
		if (references[0] &&
		    aa_engine_set_reference_cache(store->engine, references, d->cfg.reference_cache_bytes, &aerr)) {
			fprintf(stderr, "aalabd: %s: %s\n", aerr.path, aerr.message);
			goto out;
		}
	}
	if (worker_start(store)) {
		fprintf(stderr, "aalabd: cannot start the GPU worker thread\n");
		goto out;
	}
	struct runtime rt = {.d = d, .argc = argc, .argv = argv, .watchdog_ms = sd_watchdog_interval_ms()};
	for (int i = 0; i < d->t.listener_count; i++)
		loop_watch(d->t.loop, d->t.listeners[i].fd, LOOP_READ, conn_accept, &d->t.listeners[i]);
	loop_on_wake(d->t.loop, on_wake, &rt);
	loop_every(d->t.loop, rt.watchdog_ms && rt.watchdog_ms < 1000 ? rt.watchdog_ms : 1000, on_tick, &rt);
	struct sigaction sa = {.sa_handler = on_signal};
	sigemptyset(&sa.sa_mask);
	sigaction(SIGTERM, &sa, NULL);
	sigaction(SIGINT, &sa, NULL);
	sigaction(SIGHUP, &sa, NULL);
	log_listeners(d);
	pthread_mutex_lock(&store->lock);
	int queued = store_count_state(store, JOB_QUEUED);
	pthread_mutex_unlock(&store->lock);
	fprintf(stderr, "aalabd: ready (device %s, %d jobs queued%s)\n", store->device_name, queued,
		store->use_process ? ", user methods allowed: GPU work in a worker process" : "");
	sd_notifyf("READY=1\nSTATUS=serving; %d jobs queued\nMAINPID=%ld", queued, (long)getpid());
	status = loop_run(d->t.loop) == 0 ? 0 : 1;
	worker_request_stop(store, true);
	worker_join(store);
	fprintf(stderr, "aalabd: stopped\n");
out:
	for (struct conn *c = d->t.conns; c; c = c->next)
		conn_close(c);
	conns_sweep(&d->t);
	stream_cache_clear();
	for (int i = 0; i < d->t.listener_count; i++) {
		close(d->t.listeners[i].fd);
		if (!d->t.listeners[i].from_systemd && d->t.listeners[i].kind == CONN_PROTOCOL && !d->t.listeners[i].tcp)
			unlink(d->t.listeners[i].name);
	}
	if (store->process) /* the worker thread never started: the process is still this thread's */
		worker_process_stop(store);
	aa_engine_destroy(store->engine);
	scene_cache_destroy(store->scenes);
	store_close(store);
	free(store);
	loop_destroy(d->t.loop);
	return status;
}
