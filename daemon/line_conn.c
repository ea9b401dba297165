/* Protocol connections: their input split into requests, a JSON line (protocol_parse.c) and the binary
 * payload it announced, each handed to the handlers (on_request); errors in the framing answered here. */
#include <string.h>

#include "protocol_parse.h"
#include "transport.h"

/* Splits the input into requests: a JSON line, then the payload it announced, if any. What is handled
 * is taken off the input once, at the end (one memmove a turn, not one a request). */
void line_input(struct conn *c)
{
	struct transport *t = c->t;
	size_t off = 0;
	int handled = 0;
	c->backlog = false;
	while (!c->closed && c->in_len > off) {
		char *in = c->in + off;
		const size_t in_len = c->in_len - off;
		if (c->discard) {
			size_t n = c->discard < in_len ? c->discard : in_len;
			off += n;
			c->discard -= n;
			continue;
		}
		if (conn_turn_over(c, handled, c->turn_ms)) {
			c->backlog = memchr(in, '\n', in_len) != NULL || (c->pending && in_len >= c->payload_expected);
			break;
		}
		if (c->pending) {
			if (in_len < c->payload_expected)
				break;
			json_t *msg = c->pending;
			size_t size = c->payload_expected;
			c->pending = NULL;
			c->payload_expected = 0;
			handled++;
			c->t->handlers->on_request(c, msg, json_string_value(json_object_get(msg, "op")), in, size);
			off += size;
			continue;
		}
		char *nl = memchr(in, '\n', in_len);
		if (!nl) {
			if (in_len > t->cfg->max_request_bytes) {
				if (!c->discard_line)
					protocol_error(c, NULL, "too_large", "", "request line longer than %zu bytes "
						       "(max-request-bytes)", t->cfg->max_request_bytes);
				c->discard_line = true;
				c->in_len = off; /* the rest goes */
			}
			break;
		}
		size_t len = (size_t)(nl - in);
		if (c->discard_line) { /* the tail of a refused line */
			c->discard_line = false;
			off += len + 1;
			continue;
		}
		handled++;
		if (len > t->cfg->max_request_bytes) {
			protocol_error(c, NULL, "too_large", "", "request line longer than %zu bytes (max-request-bytes)",
				       t->cfg->max_request_bytes);
			off += len + 1;
			continue;
		}
		struct protocol_line pl;
		protocol_parse_line(in, len, t->cfg->max_request_bytes, &pl);
		off += len + 1;
		if (pl.kind == LINE_BLANK)
			continue;
		t->stats.requests_total++;
		if (pl.kind == LINE_ERROR) {
			protocol_error(c, pl.tag, pl.code, pl.path, "%s", pl.message);
			protocol_line_release(&pl);
			c->discard = pl.discard; /* a refused request's payload is skipped */
			if (pl.close)
				conn_close_after_flush(c);
			continue;
		}
		if (pl.payload > 0) {
			c->pending = pl.msg;
			c->payload_expected = pl.payload;
			continue;
		}
		c->t->handlers->on_request(c, pl.msg, pl.op, NULL, 0);
	}
	if (!c->closed && off > 0) {
		memmove(c->in, c->in + off, c->in_len - off);
		c->in_len -= off;
	}
}
