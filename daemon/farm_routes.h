/* Build farms in aalabd (docs/protocol.md, "Build farms"): the HTTP routes /v1/jobs (with label and suite
 * filters), /v1/jobs/ID/compare and /v1/series. daemon/farm_routes.c. */
#ifndef AALABD_FARM_ROUTES_H
#define AALABD_FARM_ROUTES_H

#include <stdbool.h>

#include <jansson.h>

struct daemon;

struct farm_reply {
	int status;                /* HTTP status */
	json_t *json;              /* the body when status is 200 */
	char text[1024];           /* the body (an error) otherwise */
};

/* Answers path?query when it is a farm route (true), else leaves out untouched (false). */
bool farm_http(struct daemon *d, const char *path, const char *query, struct farm_reply *out);

/* Label and suite filters of a job list, from a protocol request's "labels" object and "suite" string
 * (lock not held); NULL with a message naming the field when they are bad. */
struct farm_filter;
struct farm_filter *farm_filter_from_request(json_t *labels, json_t *suite, char *path, size_t path_size,
					     char *message, size_t message_size);
struct job;
bool farm_filter_matches(const struct farm_filter *f, const struct job *job); /* lock held */
void farm_filter_free(struct farm_filter *f);

#endif
