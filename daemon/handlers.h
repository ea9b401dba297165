/* The one table through which the transport calls the handlers: the only way a request, an HTTP route or
 * a watch stream reaches code above transport. The handlers fill it in (protocol.c, daemon_handlers). */
#ifndef AALABD_HANDLERS_H
#define AALABD_HANDLERS_H

#include <stddef.h>

#include <jansson.h>

struct conn;
struct http_response;

struct conn_handlers {
	/* one protocol request whose envelope protocol_parse_line checked, with its payload if it announced
	 * one; steals msg */
	void (*on_request)(struct conn *c, json_t *msg, const char *op, const char *payload, size_t payload_size);
	/* one authorized GET or HEAD: fills r (http_conn.h); target may be changed in place */
	void (*on_http_request)(struct conn *c, char *target, struct http_response *r);
	/* a connection with a watch has room for more output */
	void (*on_writable)(struct conn *c);
	/* the connection closed (once): its watch, if any, ends */
	void (*on_close)(struct conn *c);
};

#endif
