/* HTTP connections: the HTTP/1.1 subset for dashboards (GET and HEAD, keep-alive, no request bodies).
 * Frames requests (http_parse.c), checks the bearer token and writes responses; what a path answers is
 * the handlers' (on_http_request). */
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "http_conn.h"
#include "http_parse.h"
#include "transport.h"

static const char *reason(int status)
{
	switch (status) {
	case 200: return "OK";
	case 400: return "Bad Request";
	case 401: return "Unauthorized";
	case 404: return "Not Found";
	case 405: return "Method Not Allowed";
	case 409: return "Conflict";
	case 500: return "Internal Server Error";
	case 414: return "URI Too Long";
	case 505: return "HTTP Version Not Supported";
	case 431: return "Request Header Fields Too Large";
	case 503: return "Service Unavailable";
	default: return "Error";
	}
}

void http_text(struct http_response *r, int status, const char *msg)
{
	r->status = status;
	r->type = "text/plain; charset=utf-8";
	r->body = strdup(msg);
	r->size = r->body ? strlen(r->body) : 0;
}

void http_json(struct http_response *r, json_t *o)
{
	r->status = 200;
	r->type = "application/json";
	r->body = json_dumps(o, JSON_COMPACT);
	r->size = r->body ? strlen(r->body) : 0;
	json_decref(o);
}

int read_whole_file(const char *path, size_t max, char **data, size_t *size)
{
	int fd = open(path, O_RDONLY | O_CLOEXEC);
	struct stat st;
	if (fd < 0)
		return -1;
	if (fstat(fd, &st) < 0 || !S_ISREG(st.st_mode) || (size_t)st.st_size > max) {
		close(fd);
		return -1;
	}
	char *buf = malloc((size_t)st.st_size + 1);
	size_t got = 0;
	while (buf && got < (size_t)st.st_size) {
		ssize_t n = read(fd, buf + got, (size_t)st.st_size - got);
		if (n <= 0)
			break;
		got += (size_t)n;
	}
	close(fd);
	if (!buf || got != (size_t)st.st_size) {
		free(buf);
		return -1;
	}
	*data = buf;
	*size = got;
	return 0;
}

void http_file(struct http_response *r, const char *path, const char *type)
{
	if (read_whole_file(path, 1u << 30, &r->body, &r->size)) {
		http_text(r, 404, "not found\n");
		return;
	}
	r->status = 200;
	r->type = type;
}

const char *file_content_type(const char *rel)
{
	size_t n = strlen(rel);
	if (n > 5 && !strcmp(rel + n - 5, ".json"))
		return "application/json";
	if (n > 6 && !strcmp(rel + n - 6, ".jsonl"))
		return "application/jsonl";
	if (n > 5 && !strcmp(rel + n - 5, ".html"))
		return "text/html; charset=utf-8";
	if (n > 4 && !strcmp(rel + n - 4, ".png"))
		return "image/png";
	if (n > 4 && !strcmp(rel + n - 4, ".exr"))
		return "image/x-exr";
	if (n > 3 && !strcmp(rel + n - 3, ".js"))
		return "text/javascript; charset=utf-8";
	if (n > 4 && !strcmp(rel + n - 4, ".css"))
		return "text/css; charset=utf-8";
	return "application/octet-stream";
}

static void respond(struct conn *c, struct http_response *r, bool head, bool keep_alive)
{
	char hdr[1024];
	int n = snprintf(hdr, sizeof hdr, "HTTP/1.1 %d %s\r\nServer: aalabd/" PACKAGE_VERSION "\r\n"
			 "Content-Type: %s\r\nContent-Length: %zu\r\nCache-Control: no-store\r\n%sConnection: %s\r\n\r\n",
			 r->status, reason(r->status), r->type ? r->type : "text/plain", r->size,
			 r->extra ? r->extra : "", keep_alive ? "keep-alive" : "close");
	conn_send(c, hdr, (size_t)n);
	if (!head && r->body)
		conn_send(c, r->body, r->size);
	free(r->body);
	if (!keep_alive)
		conn_close_after_flush(c);
}

static void refuse_request(struct conn *c, int status, const char *why)
{
	struct http_response r = {0};
	char msg[300];
	snprintf(msg, sizeof msg, "%s\n", why);
	http_text(&r, status, msg);
	respond(c, &r, false, false);
}

/* Handles every complete request in the input buffer; a malformed one is answered and ends the
 * connection as soon as its bad line is in (http_parse.c). */
void http_input(struct conn *c)
{
	struct transport *t = c->t;
	int handled = 0;
	c->backlog = false;
	while (!c->closed && !c->close_after_flush && c->in_len > 0) {
		if (conn_turn_over(c, handled++, c->turn_ms)) { /* the rest in a later turn (conns_pump_input) */
			c->backlog = true;
			return;
		}
		struct http_request req;
		const char *why;
		long taken = http_parse_request(c->in, c->in_len, &req, &why);
		if (taken == 0)
			return;
		t->stats.http_requests_total++;
		if (taken < 0) {
			c->in_len = 0;
			refuse_request(c, (int)-taken, why);
			return;
		}
		memmove(c->in, c->in + taken, c->in_len - (size_t)taken);
		c->in_len -= (size_t)taken;
		bool head = !strcmp(req.method, "HEAD");
		bool authorized = !t->token[0] || !c->via_tcp || (req.bearer[0] && token_equal(req.bearer, t->token));
		struct http_response r = {0};
		if (req.has_body) {
			refuse_request(c, 400, "bad request: GET or HEAD with no body");
			return;
		} else if (strcmp(req.method, "GET") && !head) {
			http_text(&r, 405, "only GET and HEAD\n");
			r.extra = "Allow: GET, HEAD\r\n";
		} else if (!authorized && strcmp(req.target, "/healthz")) {
			http_text(&r, 401, "send Authorization: Bearer TOKEN\n");
			r.extra = "WWW-Authenticate: Bearer\r\n";
		} else {
			t->handlers->on_http_request(c, req.target, &r);
		}
		respond(c, &r, head, req.keep_alive);
	}
}
