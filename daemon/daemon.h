/* aalabd's shared state: the configuration, the listeners, the client connections and the job store.
 * The event loop thread owns connections and listeners; the job store is shared with the GPU worker
 * under store.lock (jobs.h). The store owns every job: a job pointer outlives an unlock only while its
 * user holds the job (job_hold/job_release); the full rule, and who the holders are, is in jobs.h beside
 * struct job, where every user of a job reads it. */
#ifndef AALABD_DAEMON_H
#define AALABD_DAEMON_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include <jansson.h>

#include "loop.h"

#define AALABD_PROTOCOL_VERSION 1

struct config {
	char socket_path[108];
	char state_dir[1024];
	char tcp[300];            /* HOST:PORT or "" */
	char token_file[1024];
	char http[300];
	char web_dir[1024];
	char config_file[1024];
	char device[128];
	size_t max_request_bytes;   /* one JSON line, and one announced payload */
	int max_connections;          /* per listener: HTTP cannot take the protocol socket's slots */
	int max_connections_per_peer; /* per listener and peer (uid on the Unix socket, address on TCP) */
	int hello_timeout_s;          /* a TCP client that has not shown its token by then is dropped */
	int max_jobs_per_client;    /* queued + running */
	int max_queued_jobs;
	double max_job_budget;      /* width x height x frames x (reference samples + methods) */
	int idle_timeout_s;         /* no request and no watch */
	int slow_client_timeout_s;  /* output pending and none of it written */
	int request_timeout_s;      /* a started line or payload not completed */
	size_t client_buffer_bytes; /* output kept per client; beyond it frames are dropped from the stream */
	int retention_jobs;         /* finished jobs kept */
	int max_job_interruptions;  /* crashes in a row during one job before it is failed (0: never) */
	int render_nice;            /* nice levels the rendering threads run below the protocol loop */
	uint64_t retention_bytes;   /* bytes of finished jobs kept */
	uint64_t scene_cache_bytes;
	char reference_cache[1024];  /* the store of references: a folder, "off", or "" for STATE_DIR/references */
	uint64_t reference_cache_bytes;
	int drain_timeout_s;        /* SIGTERM: how long the running job may take to finish */
	bool allow_user_methods;    /* jobs may bring their own shaders; GPU work runs in a worker process */
	int job_time_limit_s;       /* the worker process is killed when a job runs longer (0: no limit) */
	int verbose;
};

void config_defaults(struct config *c);
/* Reads "key = value" lines; errors name the file, the line and the key. */
int config_load(struct config *c, const char *path, char *err, size_t err_size);
/* Applies the reloadable settings (limits, timeouts, retention, cache budget) of `from` to `to`. */
/* The folder of the store of references the configuration names ("" when it is off). */
void config_reference_cache_dir(const struct config *c, char *out, size_t size);
void config_apply_reload(struct config *to, const struct config *from);
int config_set(struct config *c, const char *name, const char *value, char *err, size_t err_size);
bool config_has_key(const char *name); /* a key of the file, and so an option --KEY VALUE */

enum conn_kind { CONN_PROTOCOL, CONN_HTTP };

struct job;
struct listener;

struct conn {
	struct daemon *d;
	int fd;
	enum conn_kind kind;
	struct listener *listener; /* NULL once the daemon stops listening (draining) */
	bool via_tcp;             /* the bearer token must be shown in hello */
	bool authed;
	char peer[64];            /* "uid:1000" or "tcp:127.0.0.1" (jobs-per-client) */
	char *in;                 /* bytes read and not consumed */
	size_t in_len, in_cap;
	size_t payload_expected;  /* bytes of an announced payload still to come */
	size_t discard;           /* bytes of a refused payload still to skip */
	bool discard_line;        /* skipping the rest of an over-long line */
	json_t *pending;          /* the request that announced the payload */
	char *out;                /* bytes queued to send: out[out_head .. out_len) */
	size_t out_head, out_len, out_cap;
	double accepted_ms, last_input_ms, last_output_ms, partial_since_ms;
	bool close_after_flush, closed, eof;
	/* the one watch this connection may run; the connection holds the job while it watches (jobs.h) */
	struct job *watch_job;
	bool backlog;             /* whole requests left in the input for a later turn (conns_pump_input) */
	double turn_ms;           /* when its last turn of requests began: the longest waiting goes first */
	unsigned long watch_next_seq;
	json_t *watch_tag;
	int watch_frames;         /* FRAMES_NONE / FRAMES_PNG / FRAMES_RGBA8 / FRAMES_RGBA16F */
	unsigned long frames_dropped;
	int http_requests;
	struct conn *next;
};

struct listener {
	struct daemon *d;
	int fd;
	enum conn_kind kind;
	bool tcp;
	bool from_systemd;
	int conn_count;           /* open connections accepted here (max-connections) */
	char name[300];
};

struct stats {
	uint64_t connections_total, requests_total, errors_total, http_requests_total;
	uint64_t frames_dropped_total;
};

struct daemon {
	struct config cfg;
	struct loop *loop;
	struct store *store;
	struct listener listeners[8];
	int listener_count;
	struct conn *conns;
	int conn_count;
	char token[256];
	bool draining;
	double drain_started_ms;
	double started_ms;
	struct stats stats;
};

/* conn.c */
void conn_accept(struct loop *loop, int fd, int events, void *data);
void conn_send(struct conn *c, const void *data, size_t size);
/* A connection's turn of the loop: at most REQUESTS_PER_TURN requests and TURN_MS of handling them (at
 * least one request); then the others, and poll, come before its next ones, so that a client that
 * pipelines costly requests cannot hold the loop for all of them at once. */
#define REQUESTS_PER_TURN 16
#define TURN_MS 2.0
/* Whether c has had its turn after handled requests begun at started_ms, or its replies wait over
 * client-buffer-bytes (a client that does not read is paused: its further requests wait in its input,
 * and past slow-client-timeout it is dropped). The input functions then set c->backlog. */
bool conn_turn_over(const struct conn *c, int handled, double started_ms);
/* Goes on with the requests that connections left for a later turn (each takes at most
 * REQUESTS_PER_TURN a turn, and none while its replies wait over client-buffer-bytes). */
void conns_pump_input(struct daemon *d);
void conn_send_json(struct conn *c, json_t *msg); /* steals msg */
void conn_close(struct conn *c);
/* The connection ends once its queued output is sent (and its watch, if any, has ended): at once when
 * nothing is queued. Every path that decides to end a connection goes through here. */
void conn_close_after_flush(struct conn *c);
void conns_sweep(struct daemon *d); /* frees closed connections */
void conn_finish_watch(struct conn *c); /* closes a half-closed connection once its watch ended */
void conns_tick(struct daemon *d);
void conns_pump_watches(struct daemon *d);
size_t conn_pending(const struct conn *c);

/* protocol.c */
/* Runs one request whose envelope protocol_parse_line checked; steals msg. */
void protocol_request(struct conn *c, json_t *msg, const char *op, const char *payload, size_t payload_size);
void protocol_error(struct conn *c, json_t *tag, const char *code, const char *path, const char *fmt, ...)
	__attribute__((format(printf, 5, 6)));
void protocol_pump_watch(struct conn *c);
bool token_equal(const char *given, const char *want); /* constant time in the given token */

enum { FRAMES_NONE, FRAMES_PNG, FRAMES_RGBA8, FRAMES_RGBA16F };

/* stream.c: watch streams and stored files */
void op_get(struct conn *c, json_t *msg, json_t *tag);
void stream_cache_clear(void); /* frees the frames kept for watchers (at exit) */
/* Checks a file name inside a job directory (results.json, report.html, events.jsonl, scene.json,
 * frames|diff/NAME/NNNN.png) and writes its path; -1 if it is not one of those. */
int job_file_path(const char *jobs_dir, const char *id, const char *rel, char *out, size_t size);
/* Reads a whole file of at most max bytes (malloc'ed). */
int read_whole_file(const char *path, size_t max, char **data, size_t *size);
const char *file_content_type(const char *rel);

/* http.c */
void http_input(struct conn *c);

/* listen.c */
int listen_unix(const char *path, char *err, size_t err_size);
int listen_tcp(const char *host_port, char *err, size_t err_size);
/* Checks that HOST:PORT parses and resolves, without listening (aalabd --check). */
int check_tcp_address(const char *what, const char *host_port, char *err, size_t err_size);
int listen_systemd(struct daemon *d, char *err, size_t err_size);
void sd_notifyf(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* WATCHDOG_USEC halved in ms, or 0 when systemd does not watch this process. */
int sd_watchdog_interval_ms(void);
bool address_is_loopback(const char *host_port);

void daemon_log(struct daemon *d, int level, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

#endif
