/* The HTTP/1.1 request-head parser (RFC 9112) of the dashboard subset, as a pure function over bytes:
 * no socket, no daemon state, so the fuzz target (tests/fuzz/fuzz_http.c) calls exactly what aalabd calls. */
#ifndef AALABD_HTTP_PARSE_H
#define AALABD_HTTP_PARSE_H

#include <stdbool.h>
#include <stddef.h>

#define HTTP_MAX_HEAD 16384   /* request line and header fields */
#define HTTP_MAX_TARGET 2048

struct http_request {
	char method[16];
	char target[HTTP_MAX_TARGET + 1];
	int minor_version;            /* HTTP/1.0 or HTTP/1.1 */
	bool keep_alive;
	bool has_body;                /* Content-Length other than 0, or Transfer-Encoding */
	char bearer[300];             /* the token of "Authorization: Bearer TOKEN", or "" */
};

/* Parses the request head at the start of buf. Returns the bytes it takes (the head and its empty line),
 * 0 while more bytes are needed, or -STATUS (-400, -414, -431, -505) with *why saying what is wrong. Lines
 * end in CRLF or a bare LF (RFC 9112 2.2 lets a recipient take LF alone); a bare CR, a header line without
 * a colon or with space before it, obsolete line folding, a missing or repeated Host on HTTP/1.1 and
 * control bytes are refused, each as soon as its line is complete. */
long http_parse_request(const char *buf, size_t len, struct http_request *req, const char **why);

#endif
