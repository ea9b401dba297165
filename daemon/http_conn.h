/* HTTP responses, for the handlers that answer routes (http_conn.c). */
#ifndef AALABD_HTTP_CONN_H
#define AALABD_HTTP_CONN_H

#include <stddef.h>

#include <jansson.h>

struct http_response {
	int status;
	const char *type;
	char *body;          /* malloc'ed */
	size_t size;
	const char *extra;   /* more header lines, each ending in \r\n */
};

void http_text(struct http_response *r, int status, const char *msg);
void http_json(struct http_response *r, json_t *o); /* steals o */
/* The file's contents (404 when it cannot be read). */
void http_file(struct http_response *r, const char *path, const char *type);
/* Reads a whole file of at most max bytes (malloc'ed). */
int read_whole_file(const char *path, size_t max, char **data, size_t *size);
const char *file_content_type(const char *rel);

#endif
