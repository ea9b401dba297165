/* aalabd's shared state as the handlers see it: the configuration, the transport (transport.h) and the
 * job store (jobs.h). The event loop thread owns the transport; the store is shared with the GPU worker
 * under store.lock: the rule for holding a job pointer across an unlock is in jobs.h beside struct job. */
#ifndef AALABD_DAEMON_H
#define AALABD_DAEMON_H

#include <stdbool.h>
#include <stddef.h>

#include "config.h"
#include "transport.h"

#define AALABD_PROTOCOL_VERSION 1

struct store;

struct daemon {
	struct config cfg;
	struct transport t;       /* t.cfg is &cfg */
	struct store *store;
	bool draining;
	double drain_started_ms;
	double started_ms;
};

/* The daemon a connection belongs to: every connection's transport is a daemon's t. */
static inline struct daemon *conn_daemon(const struct conn *c)
{
	return (struct daemon *)((char *)c->t - offsetof(struct daemon, t));
}

/* protocol.c: the protocol ops, and the table the transport calls (handlers.h) */
extern const struct conn_handlers daemon_handlers;

/* http_routes.c */
void http_route(struct conn *c, char *target, struct http_response *r);


#endif
