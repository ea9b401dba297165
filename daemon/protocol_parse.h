/* One protocol request line (docs/protocol.md) checked as a pure function over bytes: JSON, the envelope
 * (op, tag) and the announced payload size. No socket, no daemon state, so the fuzz target
 * (tests/fuzz/fuzz_protocol.c) calls exactly what aalabd calls. */
#ifndef AALABD_PROTOCOL_PARSE_H
#define AALABD_PROTOCOL_PARSE_H

#include <stdbool.h>
#include <stddef.h>

#include <jansson.h>

enum protocol_line_kind { LINE_BLANK, LINE_REQUEST, LINE_ERROR };

struct protocol_line {
	enum protocol_line_kind kind;
	json_t *msg;          /* LINE_REQUEST: the request object (the caller's to release) */
	const char *op;       /* LINE_REQUEST: its op, inside msg */
	json_t *tag;          /* the request's tag when it is valid (inside msg), else NULL */
	size_t payload;       /* LINE_REQUEST: bytes announced to follow the line */
	/* LINE_ERROR: the error reply, and what becomes of the bytes after the line */
	const char *code, *path;
	char message[300];
	bool close;           /* the stream cannot be resynchronised: end the connection after the reply */
	size_t discard;       /* payload bytes to skip before the next request line */
	json_t *error_msg;    /* LINE_ERROR: the parsed line that holds tag (released with it), or NULL */
};

/* Parses one line (without its newline; a trailing CR is ignored). A line of only spaces and tabs is
 * LINE_BLANK. max_payload is max-request-bytes. */
void protocol_parse_line(const char *line, size_t len, size_t max_payload, struct protocol_line *out);
/* Releases what protocol_parse_line left in out (msg or error_msg). */
void protocol_line_release(struct protocol_line *out);

#endif
