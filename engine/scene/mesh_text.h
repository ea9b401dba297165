/* What the readers of mesh_text_check.c share: the text being read, line by line, and its numbers.
 * Private to mesh_text_*.c. */
#ifndef AA_MESH_TEXT_H
#define AA_MESH_TEXT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "scene/mesh_text_check.h"

#define POSITION_MAX 1e7 /* as every number in a scene file */
#define MAX_TOKENS 1024  /* values on one line */

struct mesh_text {
	const char *p, *end; /* what is left to read */
	int line;            /* the line last read, 1-based */
	size_t max_line;
	bool ascii_only; /* bytes from 0x80 up refused (OFF, PLY, STL); OBJ and .mtl names may be UTF-8 */
	char *why;
	size_t why_size;
	/* the line last read, split at spaces and tabs */
	bool crlf; /* it ended with a carriage return and a line feed */
	size_t len;
	int n;
	const char *tok[MAX_TOKENS];
	size_t tlen[MAX_TOKENS];
};

/* "line N: " and the message into t->why; -1. */
int mt_fail_at(struct mesh_text *t, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* The message alone (it names its place itself); -1. */
int mt_fail_plain(struct mesh_text *t, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* The next line into t's tokens: 1, 0 at the end of the data, -1 (refused) on a byte that is not text,
 * a carriage return not before a line feed, or a line over max_line. */
int mt_next_line(struct mesh_text *t);
/* Tokens from the first that starts with '#' on are a comment. */
void mt_drop_comment(struct mesh_text *t);
/* Token i is `word`. */
bool mt_is(const struct mesh_text *t, int i, const char *word);
/* Token i for messages, cut short. */
const char *mt_shown(const struct mesh_text *t, int i, char *buf, size_t size);
/* A plain decimal number (no nan, inf, hex or trailing text). */
bool mt_parse_number(const char *s, size_t n, double *out);
/* Token i as a number a float holds; `what` names the value in the message. */
int mt_number(struct mesh_text *t, int i, const char *what, double *out);
/* Three numbers from token i: a position, finite and within 1e7 of the origin. */
int mt_position(struct mesh_text *t, int i, const char *what, uint64_t vertex);
/* Digits only, at most max. */
bool mt_parse_count(const char *s, size_t n, uint64_t max, uint64_t *out);
int mt_count(struct mesh_text *t, int i, const char *what, uint64_t max, uint64_t *out);

/* One reader per format (mesh_text_obj.c, mesh_text_off.c, mesh_text_ply.c, mesh_text_stl.c). */
int mt_check_obj(struct mesh_text *t, aa_mesh_library_fn library, void *ctx);
int mt_check_mtl(struct mesh_text *t);
int mt_check_off(struct mesh_text *t);
int mt_check_ply(struct mesh_text *t);
int mt_check_stl(struct mesh_text *t);

#endif
