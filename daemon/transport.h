/* The transport layer: listeners, client connections with their bounded buffers, line/payload and HTTP
 * framing, timeouts. It knows nothing of jobs: what a request means is the handlers' (handlers.h), which
 * it calls through the one table transport->handlers. The event loop thread owns all of it. */
#ifndef AALABD_TRANSPORT_H
#define AALABD_TRANSPORT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include <jansson.h>

#include "config.h"
#include "handlers.h"
#include "loop.h"

enum conn_kind { CONN_PROTOCOL, CONN_HTTP };

struct listener;
/* A watch stream is the handlers' (stream.h); transport only asks whether a connection has one: it then
 * stays open until the watch ends and is called (on_writable) when there is room for more. */
struct watch;

struct conn {
	struct transport *t;
	int fd;
	enum conn_kind kind;
	void (*input)(struct conn *c); /* its listener's framing: line_input or http_input */
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
	struct watch *watch;      /* the one watch this connection may run (handlers'), or NULL */
	bool backlog;             /* whole requests left in the input for a later turn (conns_pump_input) */
	double turn_ms;           /* when its last turn of requests began: the longest waiting goes first */
	struct conn *next;
};

struct listener {
	struct transport *t;
	int fd;
	enum conn_kind kind;
	/* splits a connection's input into requests (line_input, http_input): set by whoever opens the
	 * listener, so that conn.c, below both framings, calls neither by name */
	void (*input)(struct conn *c);
	bool tcp;
	bool from_systemd;
	int conn_count;           /* open connections accepted here (max-connections) */
	char name[300];
};

struct stats {
	uint64_t connections_total, requests_total, errors_total, http_requests_total;
	uint64_t frames_dropped_total;
};

struct transport {
	const struct config *cfg;              /* the daemon's, reloaded in place */
	const struct conn_handlers *handlers;
	struct loop *loop;
	struct listener listeners[8];
	int listener_count;
	struct conn *conns;
	int conn_count;
	char token[256];
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
/* Whether c has had its turn after handled requests begun at started_ms, or over 64 KiB of its replies
 * wait unsent (a client that does not read is paused: its further requests wait in its input,
 * and past slow-client-timeout it is dropped). The input functions then set c->backlog. */
bool conn_turn_over(const struct conn *c, int handled, double started_ms);
/* Goes on with the requests that connections left for a later turn (each takes at most
 * REQUESTS_PER_TURN a turn, and none while it is paused). */
void conns_pump_input(struct transport *t);
void conn_send_json(struct conn *c, json_t *msg); /* steals msg */
/* The protocol's error reply {ok:false, error:{code, message, path}, tag}. */
void protocol_error(struct conn *c, json_t *tag, const char *code, const char *path, const char *fmt, ...)
	__attribute__((format(printf, 5, 6)));
bool token_equal(const char *given, const char *want); /* constant time in the given token */
void conn_close(struct conn *c);
/* The connection ends once its queued output is sent (and its watch, if any, has ended): at once when
 * nothing is queued. Every path that decides to end a connection goes through here. */
void conn_close_after_flush(struct conn *c);
void conns_sweep(struct transport *t); /* frees closed connections */
void conn_finish_watch(struct conn *c); /* closes a half-closed connection once its watch ended */
void conns_tick(struct transport *t);
void conns_pump_watches(struct transport *t);
size_t conn_pending(const struct conn *c);

/* line_conn.c: the protocol's framing */
void line_input(struct conn *c);
/* http_conn.c: HTTP's framing */
void http_input(struct conn *c);

/* listen.c */
int listen_unix(const char *path, char *err, size_t err_size);
int listen_tcp(const char *host_port, char *err, size_t err_size);
/* Checks that HOST:PORT parses and resolves, without listening (aalabd --check). */
int check_tcp_address(const char *what, const char *host_port, char *err, size_t err_size);
int listen_systemd(struct transport *t, char *err, size_t err_size);
void sd_notifyf(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* WATCHDOG_USEC halved in ms, or 0 when systemd does not watch this process. */
int sd_watchdog_interval_ms(void);
bool address_is_loopback(const char *host_port);

#endif
