/* Client connections: accepting, reading into a bounded input buffer, splitting it into JSON lines (and
 * announced binary payloads), queueing output, and the timeouts that drop idle, stalled or slow clients.
 * HTTP connections share the buffers and hand their input to http_conn.c. What a request means is the
 * handlers': every call up goes through c->t->handlers (handlers.h). */
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <arpa/inet.h>
#include <netinet/in.h>
#include <unistd.h>

#include "transport.h"

static void conn_io(struct loop *loop, int fd, int events, void *data);

void protocol_error(struct conn *c, json_t *tag, const char *code, const char *path, const char *fmt, ...)
{
	char msg[1024];
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(msg, sizeof msg, fmt, ap);
	va_end(ap);
	json_t *o = json_pack("{sb s{ss ss ss}}", "ok", 0, "error", "code", code, "message", msg, "path", path);
	if (tag)
		json_object_set(o, "tag", tag);
	c->t->stats.errors_total++;
	conn_send_json(c, o);
}

bool token_equal(const char *given, const char *want)
{
	size_t n = given ? strlen(given) : 0, m = strlen(want);
	unsigned diff = n != m;
	for (size_t i = 0; i < m; i++) /* no early exit: the time taken says nothing about the token */
		diff |= (unsigned)(want[i] ^ (i < n ? given[i] : 0));
	return diff == 0;
}

size_t conn_pending(const struct conn *c)
{
	return c->out_len - c->out_head;
}

/* Names the peer for the per-peer limits and jobs-per-client: its uid on a Unix socket (whatever the
 * listener, systemd may pass either kind), its address on TCP. */
static void peer_name(struct conn *c)
{
	struct sockaddr_storage ss;
	socklen_t len = sizeof ss;
	if (getsockname(c->fd, (struct sockaddr *)&ss, &len) == 0 && ss.ss_family == AF_UNIX) {
		struct ucred cred;
		len = sizeof cred;
		if (getsockopt(c->fd, SOL_SOCKET, SO_PEERCRED, &cred, &len) == 0)
			snprintf(c->peer, sizeof c->peer, "uid:%u", (unsigned)cred.uid);
		else
			snprintf(c->peer, sizeof c->peer, "unix");
		return;
	}
	len = sizeof ss;
	char host[INET6_ADDRSTRLEN] = "?";
	if (getpeername(c->fd, (struct sockaddr *)&ss, &len) == 0) {
		if (ss.ss_family == AF_INET)
			inet_ntop(AF_INET, &((struct sockaddr_in *)&ss)->sin_addr, host, sizeof host);
		else if (ss.ss_family == AF_INET6)
			inet_ntop(AF_INET6, &((struct sockaddr_in6 *)&ss)->sin6_addr, host, sizeof host);
	}
	snprintf(c->peer, sizeof c->peer, "tcp:%s", host);
}

/* Open connections of one peer on one listener. */
static int peer_connections(struct transport *t, const struct listener *l, const char *peer)
{
	int n = 0;
	for (struct conn *c = t->conns; c; c = c->next)
		n += !c->closed && c->listener == l && !strcmp(c->peer, peer);
	return n;
}

/* A refused connection gets one line saying why (an error line, or a 503) and is closed. */
static void refuse(const struct listener *l, int fd, const char *why)
{
	char msg[512];
	int n = l->kind == CONN_HTTP
		? snprintf(msg, sizeof msg, "HTTP/1.1 503 Service Unavailable\r\nContent-Type: text/plain\r\n"
			   "Content-Length: %zu\r\nConnection: close\r\n\r\n%s\n", strlen(why) + 1, why)
		: snprintf(msg, sizeof msg, "{\"ok\":false,\"error\":{\"code\":\"limit\",\"message\":\"%s\","
			   "\"path\":\"\"}}\n", why);
	ssize_t w = send(fd, msg, (size_t)n, MSG_NOSIGNAL | MSG_DONTWAIT);
	(void)w;
	close(fd);
}

void conn_accept(struct loop *loop, int fd, int events, void *data)
{
	(void)events;
	struct listener *l = data;
	struct transport *t = l->t;
	for (;;) {
		int cfd = accept4(fd, NULL, NULL, SOCK_NONBLOCK | SOCK_CLOEXEC);
		if (cfd < 0)
			return; /* EAGAIN, or a transient error (EMFILE): the next poll tries again */
		/* Each listener has its own budget (dashboards cannot take the protocol socket's slots) and each
		 * peer its own share of it (one careless client cannot take everyone's). */
		if (l->conn_count >= t->cfg->max_connections) {
			refuse(l, cfd, "too many connections; try again later");
			continue;
		}
		struct conn *c = calloc(1, sizeof *c);
		if (!c) {
			close(cfd);
			continue;
		}
		c->fd = cfd;
		peer_name(c);
		if (peer_connections(t, l, c->peer) >= t->cfg->max_connections_per_peer) {
			char why[160];
			snprintf(why, sizeof why, "too many connections from %s (max-connections-per-peer %d); "
				 "try again later", c->peer, t->cfg->max_connections_per_peer);
			refuse(l, cfd, why);
			free(c);
			continue;
		}
		c->t = t;
		c->kind = l->kind;
		c->input = l->input;
		c->listener = l;
		c->via_tcp = l->tcp;
		c->authed = !l->tcp || !t->token[0];
		c->accepted_ms = c->last_input_ms = c->last_output_ms = loop_now_ms();
		c->next = t->conns;
		t->conns = c;
		t->conn_count++;
		l->conn_count++;
		t->stats.connections_total++;
		loop_watch(loop, cfd, LOOP_READ, conn_io, c);
	}
}

void conn_close(struct conn *c)
{
	if (c->closed)
		return;
	c->closed = true;
	loop_unwatch(c->t->loop, c->fd);
	/* Input left unread would make close() send a reset, which can discard the reply still on its way
	 * to the client: read what has arrived, then send FIN. */
	char drain[4096];
	for (int i = 0; i < 16 && recv(c->fd, drain, sizeof drain, MSG_DONTWAIT) > 0; i++)
		;
	shutdown(c->fd, SHUT_WR);
	close(c->fd);
	c->fd = -1;
	c->t->handlers->on_close(c); /* ends its watch, if any */
}

void conns_sweep(struct transport *t)
{
	for (struct conn **p = &t->conns; *p;) {
		struct conn *c = *p;
		if (!c->closed) {
			p = &c->next;
			continue;
		}
		*p = c->next;
		t->conn_count--;
		if (c->listener)
			c->listener->conn_count--;
		json_decref(c->pending);
		free(c->in);
		free(c->out);
		free(c);
	}
}

void conn_close_after_flush(struct conn *c)
{
	c->close_after_flush = true;
	if (!c->closed && !conn_pending(c) && !c->watch)
		conn_close(c);
}

/* A connection's further requests wait unread while more than this of its replies is unsent, so a client
 * that does not read is paused after a few replies and costs the others nothing more; client-buffer-bytes,
 * larger, bounds what a watch stream keeps queued. */
#define REPLY_BACKLOG_BYTES ((size_t)64 << 10)

static bool takes_requests(const struct conn *c)
{
	size_t limit = c->t->cfg->client_buffer_bytes < REPLY_BACKLOG_BYTES ? c->t->cfg->client_buffer_bytes
									    : REPLY_BACKLOG_BYTES;
	return conn_pending(c) <= limit;
}

/* Reads only while the client can take replies; never after its end of input (poll would report it
 * again and again). A connection that is to close and has nothing left to send closes here: watching
 * nothing, it would hold its slot until the idle timeout. */
static void update_interest(struct conn *c)
{
	if (c->closed)
		return;
	if (c->close_after_flush && !conn_pending(c) && !c->watch) {
		conn_close(c);
		return;
	}
	int mask = conn_pending(c) ? LOOP_WRITE : 0;
	if (!c->eof && !c->close_after_flush && !c->backlog && takes_requests(c))
		mask |= LOOP_READ;
	loop_watch(c->t->loop, c->fd, mask, conn_io, c);
}

void conn_finish_watch(struct conn *c)
{
	if (!c->closed && c->close_after_flush && !conn_pending(c))
		conn_close(c);
}

static void flush(struct conn *c)
{
	while (!c->closed && conn_pending(c)) {
		ssize_t n = send(c->fd, c->out + c->out_head, conn_pending(c), MSG_NOSIGNAL);
		if (n < 0 && errno == EINTR)
			continue;
		if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK))
			break;
		if (n <= 0) {
			conn_close(c);
			return;
		}
		c->out_head += (size_t)n;
		c->last_output_ms = loop_now_ms();
	}
	if (c->out_head == c->out_len)
		c->out_head = c->out_len = 0;
	if (!conn_pending(c) && c->close_after_flush && !c->watch) {
		conn_close(c);
		return;
	}
	if (c->backlog && takes_requests(c))
		loop_wake(c->t->loop); /* a paused client read its replies: its requests go on */
	update_interest(c);
}

void conn_send(struct conn *c, const void *data, size_t size)
{
	if (c->closed)
		return;
	/* Watch streams stop at client_buffer_bytes (stream.c) and requests pause well below it (takes_requests),
	 * so only a client that keeps asking without reading anything gets this far. */
	if (conn_pending(c) > 0 && conn_pending(c) + size > 4 * c->t->cfg->client_buffer_bytes + (1u << 20)) {
		fprintf(stderr, "aalabd: dropping %s: it does not read its replies\n", c->peer);
		conn_close(c);
		return;
	}
	if (!conn_pending(c))
		c->last_output_ms = loop_now_ms(); /* the slow-client clock starts when output starts waiting */
	if (c->out_head > 0 && c->out_head >= c->out_cap / 2) {
		memmove(c->out, c->out + c->out_head, conn_pending(c));
		c->out_len -= c->out_head;
		c->out_head = 0;
	}
	if (c->out_len + size > c->out_cap) {
		size_t cap = c->out_cap ? c->out_cap : 4096;
		while (cap < c->out_len + size)
			cap *= 2;
		char *out = realloc(c->out, cap);
		if (!out) {
			conn_close(c);
			return;
		}
		c->out = out;
		c->out_cap = cap;
	}
	memcpy(c->out + c->out_len, data, size);
	c->out_len += size;
	flush(c);
}

void conn_send_json(struct conn *c, json_t *msg)
{
	char *text = json_dumps(msg, JSON_COMPACT);
	json_decref(msg);
	if (!text)
		return;
	size_t n = strlen(text);
	text[n] = '\n'; /* replaces the terminator: the line is sent with its newline in one piece */
	conn_send(c, text, n + 1);
	free(text);
}

bool conn_turn_over(const struct conn *c, int handled, double started_ms)
{
	return !takes_requests(c) ||
	       (handled > 0 && (handled >= REQUESTS_PER_TURN || loop_now_ms() - started_ms > TURN_MS));
}

static void handle_input(struct conn *c)
{
	c->turn_ms = loop_now_ms();
	c->input(c);
	/* more to do, and room for its replies: a later turn of the loop goes on (conns_pump_input) */
	if (!c->closed && c->backlog && takes_requests(c))
		loop_wake(c->t->loop);
}

static bool waits_for_turn(const struct conn *c)
{
	return !c->closed && c->backlog && !c->close_after_flush && takes_requests(c);
}

void conns_pump_input(struct transport *t)
{
	/* turns in the order they have waited, for at most TURN_MS in all: then poll again (clients with new
	 * input come first) and the rest in the next call */
	const double start = loop_now_ms();
	for (;;) {
		struct conn *next = NULL;
		for (struct conn *c = t->conns; c; c = c->next)
			if (waits_for_turn(c) && (!next || c->turn_ms < next->turn_ms))
				next = c;
		if (!next)
			break;
		if (loop_now_ms() - start > TURN_MS) {
			loop_wake(t->loop);
			break;
		}
		handle_input(next);
		update_interest(next);
	}
	conns_sweep(t);
}

static void conn_read(struct conn *c)
{
	struct transport *t = c->t;
	for (;;) {
		if (c->in_cap - c->in_len < 16384) {
			size_t cap = c->in_cap ? c->in_cap * 2 : 16384;
			/* the buffer never holds more than one request line (or payload) plus one read */
			size_t limit = t->cfg->max_request_bytes * 2 + 65536;
			if (cap > limit)
				cap = limit;
			if (cap > c->in_cap) {
				char *in = realloc(c->in, cap);
				if (!in) {
					conn_close(c);
					return;
				}
				c->in = in;
				c->in_cap = cap;
			}
		}
		size_t room = c->in_cap - c->in_len;
		if (room == 0)
			break;
		ssize_t n = recv(c->fd, c->in + c->in_len, room, 0);
		if (n < 0 && errno == EINTR)
			continue;
		if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK))
			break;
		if (n <= 0) {
			/* end of input: a request cut short gets its error; the connection closes once its replies
			 * (and a running watch) are sent */
			if (c->pending && c->kind == CONN_PROTOCOL)
				protocol_error(c, NULL, "truncated", "payload", "the connection ended %zu bytes into a "
					       "payload of %zu", c->in_len, c->payload_expected);
			else if (c->in_len > 0 && !c->discard && !c->discard_line && c->kind == CONN_PROTOCOL)
				protocol_error(c, NULL, "truncated", "", "the connection ended inside a request line "
					       "(every request ends with a newline)");
			c->in_len = 0;
			c->eof = true;
			conn_close_after_flush(c);
			update_interest(c);
			return;
		}
		c->in_len += (size_t)n;
		c->last_input_ms = loop_now_ms();
		handle_input(c);
		if (c->closed || c->close_after_flush)
			return;
		/* a client that pipelines requests without reading replies is paused, not buffered without end;
		 * one with requests left for a later turn reads no more until they are handled */
		if (c->backlog || !takes_requests(c))
			break;
	}
	if ((c->in_len > 0 || c->pending) && c->partial_since_ms == 0)
		c->partial_since_ms = loop_now_ms();
	else if (c->in_len == 0 && !c->pending)
		c->partial_since_ms = 0;
}

static void conn_io(struct loop *loop, int fd, int events, void *data)
{
	(void)loop;
	(void)fd;
	struct conn *c = data;
	if (events & LOOP_WRITE) {
		flush(c);
		if (!c->closed && c->watch && conn_pending(c) < c->t->cfg->client_buffer_bytes / 2)
			c->t->handlers->on_writable(c);
	}
	if (!c->closed && (events & LOOP_READ) && !c->close_after_flush && !c->eof)
		conn_read(c);
	update_interest(c);
	conns_sweep(c->t);
}

void conns_pump_watches(struct transport *t)
{
	for (struct conn *c = t->conns; c; c = c->next)
		if (!c->closed && c->watch)
			c->t->handlers->on_writable(c);
	conns_sweep(t);
}

void conns_tick(struct transport *t)
{
	double now = loop_now_ms();
	const struct config *cfg = t->cfg;
	for (struct conn *c = t->conns; c; c = c->next) {
		if (c->closed)
			continue;
		if (conn_pending(c) && now - c->last_output_ms > cfg->slow_client_timeout_s * 1000.0) {
			fprintf(stderr, "aalabd: dropping %s: nothing read for %d s (slow-client-timeout)\n", c->peer,
				cfg->slow_client_timeout_s);
			conn_close(c);
		} else if ((c->in_len > 0 || c->pending) && !c->close_after_flush && c->partial_since_ms > 0 &&
			   now - c->partial_since_ms > cfg->request_timeout_s * 1000.0) {
			if (c->kind == CONN_PROTOCOL)
				protocol_error(c, NULL, "timeout", c->pending ? "payload" : "",
					       "request not completed within %d s (request-timeout)", cfg->request_timeout_s);
			c->in_len = 0;
			conn_close_after_flush(c);
			update_interest(c);
		} else if (c->kind == CONN_PROTOCOL && !c->authed && !c->close_after_flush &&
			   now - c->accepted_ms > cfg->hello_timeout_s * 1000.0) {
			protocol_error(c, NULL, "timeout", "token", "no hello with the token within %d s (hello-timeout)",
				       cfg->hello_timeout_s);
			conn_close_after_flush(c);
			update_interest(c);
		} else if (!c->watch && !conn_pending(c) && now - c->last_input_ms > cfg->idle_timeout_s * 1000.0) {
			conn_close(c);
		}
	}
	conns_sweep(t);
}
