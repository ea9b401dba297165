/* The HTTP/1.1 request-head parser: one pass over complete lines, refusing at the first bad one. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "http_parse.h"

/* tchar of RFC 9110 5.6.2: the characters of a method or a field name */
static bool is_tchar(unsigned char c)
{
	return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
	       (c && strchr("!#$%&'*+-.^_`|~", c));
}

/* Field values and targets: visible ASCII, obs-text, and (values only) space and tab. */
static bool is_value_byte(unsigned char c, bool allow_space)
{
	return (c > 0x20 && c != 0x7f) || (allow_space && (c == ' ' || c == '\t'));
}

static long refuse(const char **why, int status, const char *msg)
{
	*why = msg;
	return -status;
}

/* Does the comma-separated list `value` hold the token `want` (any case)? */
static bool list_has(const char *value, size_t n, const char *want)
{
	size_t w = strlen(want), i = 0;
	while (i < n) {
		while (i < n && (value[i] == ' ' || value[i] == '\t' || value[i] == ','))
			i++;
		size_t start = i;
		while (i < n && value[i] != ',')
			i++;
		size_t end = i;
		while (end > start && (value[end - 1] == ' ' || value[end - 1] == '\t'))
			end--;
		if (end - start == w && !strncasecmp(value + start, want, w))
			return true;
	}
	return false;
}

static long request_line(const char *line, size_t n, struct http_request *req, const char **why)
{
	const char *sp1 = memchr(line, ' ', n);
	if (!sp1 || sp1 == line || (size_t)(sp1 - line) >= sizeof req->method)
		return refuse(why, 400, "bad request line: expected METHOD /target HTTP/1.1");
	for (const char *p = line; p < sp1; p++)
		if (!is_tchar((unsigned char)*p))
			return refuse(why, 400, "bad request line: the method is not a token");
	const char *target = sp1 + 1, *end = line + n;
	const char *sp2 = memchr(target, ' ', (size_t)(end - target));
	if (!sp2)
		return refuse(why, 400, "bad request line: expected METHOD /target HTTP/1.1");
	size_t tlen = (size_t)(sp2 - target);
	if (tlen > HTTP_MAX_TARGET)
		return refuse(why, 414, "request target too long");
	if (tlen == 0 || target[0] != '/')
		return refuse(why, 400, "bad request line: the target must start with /");
	for (size_t i = 0; i < tlen; i++)
		if (!is_value_byte((unsigned char)target[i], false))
			return refuse(why, 400, "bad request line: control bytes or spaces in the target");
	const char *version = sp2 + 1;
	size_t vlen = (size_t)(end - version);
	if (vlen != 8 || strncmp(version, "HTTP/", 5) || version[6] != '.' || version[5] < '0' || version[5] > '9' ||
	    version[7] < '0' || version[7] > '9')
		return refuse(why, 400, "bad request line: expected HTTP/1.1 or HTTP/1.0 at its end");
	if (version[5] != '1')
		return refuse(why, 505, "only HTTP/1.x");
	memcpy(req->method, line, (size_t)(sp1 - line));
	req->method[sp1 - line] = 0;
	memcpy(req->target, target, tlen);
	req->target[tlen] = 0;
	req->minor_version = version[7] - '0';
	req->keep_alive = req->minor_version >= 1;
	return 0;
}

static long header_line(const char *line, size_t n, struct http_request *req, int *hosts, const char **why)
{
	if (line[0] == ' ' || line[0] == '\t')
		return refuse(why, 400, "obsolete line folding (a header line starting with a space) is not accepted");
	const char *colon = memchr(line, ':', n);
	if (!colon)
		return refuse(why, 400, "a header line without a colon");
	if (colon == line)
		return refuse(why, 400, "a header line with an empty field name");
	for (const char *p = line; p < colon; p++)
		if (!is_tchar((unsigned char)*p))
			return refuse(why, 400, "a header field name with a space or a byte that is not a token");
	size_t name_len = (size_t)(colon - line);
	const char *value = colon + 1, *end = line + n;
	while (value < end && (*value == ' ' || *value == '\t'))
		value++;
	while (end > value && (end[-1] == ' ' || end[-1] == '\t'))
		end--;
	for (const char *p = value; p < end; p++)
		if (!is_value_byte((unsigned char)*p, true))
			return refuse(why, 400, "control bytes in a header field value");
	size_t vlen = (size_t)(end - value);
#define NAME_IS(s) (name_len == sizeof s - 1 && !strncasecmp(line, s, name_len))
	if (NAME_IS("Host")) {
		(*hosts)++;
	} else if (NAME_IS("Connection")) {
		if (list_has(value, vlen, "close"))
			req->keep_alive = false;
		else if (req->minor_version == 0 && list_has(value, vlen, "keep-alive"))
			req->keep_alive = true;
	} else if (NAME_IS("Content-Length")) {
		if (vlen == 0 || strspn(value, "0123456789") < vlen)
			return refuse(why, 400, "Content-Length is not a number");
		if (strspn(value, "0") < vlen)
			req->has_body = true;
	} else if (NAME_IS("Transfer-Encoding")) {
		req->has_body = true;
	} else if (NAME_IS("Authorization")) {
		if (vlen > 7 && !strncasecmp(value, "Bearer ", 7) && vlen - 7 < sizeof req->bearer) {
			memcpy(req->bearer, value + 7, vlen - 7);
			req->bearer[vlen - 7] = 0;
		}
	}
#undef NAME_IS
	return 0;
}

long http_parse_request(const char *buf, size_t len, struct http_request *req, const char **why)
{
	memset(req, 0, sizeof *req);
	*why = "";
	size_t pos = 0;
	/* RFC 9112 2.2: empty lines before the request line are ignored */
	while (pos < len && (buf[pos] == '\n' || (buf[pos] == '\r' && pos + 1 < len && buf[pos + 1] == '\n')))
		pos += buf[pos] == '\r' ? 2 : 1;
	bool first = true;
	int hosts = 0;
	for (;;) {
		if (pos > HTTP_MAX_HEAD)
			return refuse(why, 431, "request header too large");
		const char *nl = memchr(buf + pos, '\n', len - pos);
		if (!nl) {
			/* no complete line yet: still check what has come, so that garbage is refused at once */
			size_t have = len - pos;
			if (pos + have > HTTP_MAX_HEAD)
				return refuse(why, first ? 414 : 431, first ? "request line too long" : "request header too large");
			if (memchr(buf + pos, 0, have))
				return refuse(why, 400, "a NUL byte in the request");
			return 0;
		}
		size_t n = (size_t)(nl - (buf + pos));
		const char *line = buf + pos;
		if (n > 0 && line[n - 1] == '\r')
			n--;
		if (memchr(line, '\r', n))
			return refuse(why, 400, "a bare CR in the request head");
		if (memchr(line, 0, n))
			return refuse(why, 400, "a NUL byte in the request");
		pos = (size_t)(nl - buf) + 1;
		if (first) {
			long rc = request_line(line, n, req, why);
			if (rc)
				return rc;
			first = false;
			continue;
		}
		if (n == 0)
			break;
		long rc = header_line(line, n, req, &hosts, why);
		if (rc)
			return rc;
	}
	if (pos > HTTP_MAX_HEAD)
		return refuse(why, 431, "request header too large");
	if (req->minor_version >= 1 && hosts == 0)
		return refuse(why, 400, "HTTP/1.1 requires a Host header");
	if (hosts > 1)
		return refuse(why, 400, "more than one Host header");
	return (long)pos;
}
