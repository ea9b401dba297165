/* Request lines: JSON first, then the payload size (so that a refused request's payload can be skipped),
 * then the envelope every op shares. */
#include <stdio.h>
#include <string.h>

#include "protocol_parse.h"

static void fail(struct protocol_line *out, const char *code, const char *path, const char *message)
{
	out->kind = LINE_ERROR;
	out->code = code;
	out->path = path;
	snprintf(out->message, sizeof out->message, "%s", message);
}

void protocol_line_release(struct protocol_line *out)
{
	json_decref(out->msg);
	json_decref(out->error_msg);
	out->msg = out->error_msg = NULL;
}

void protocol_parse_line(const char *line, size_t len, size_t max_payload, struct protocol_line *out)
{
	memset(out, 0, sizeof *out);
	if (len > 0 && line[len - 1] == '\r')
		len--;
	size_t blank = 0;
	while (blank < len && (line[blank] == ' ' || line[blank] == '\t'))
		blank++;
	if (blank == len) {
		out->kind = LINE_BLANK;
		return;
	}
	json_error_t jerr;
	json_t *msg = json_loadb(line, len, JSON_REJECT_DUPLICATES | JSON_DECODE_ANY, &jerr);
	if (!msg) {
		char m[300];
		snprintf(m, sizeof m, "not JSON: %s (column %d)", jerr.text, jerr.column);
		fail(out, "bad_json", "", m);
		return;
	}
	out->error_msg = msg; /* errors below may quote its tag; a good request moves it to out->msg */
	if (!json_is_object(msg)) {
		fail(out, "bad_request", "", "a request is a JSON object: {\"op\": ..., ...}");
		return;
	}
	json_t *tag = json_object_get(msg, "tag");
	bool tag_ok = !tag || json_is_integer(tag) || (json_is_string(tag) && strlen(json_string_value(tag)) <= 64);
	out->tag = tag_ok ? tag : NULL;
	json_t *p = json_object_get(msg, "payload");
	if (p) {
		if (!json_is_integer(p) || json_integer_value(p) < 0) {
			fail(out, "bad_request", "payload", "payload is the number of bytes that follow the line");
			out->close = true;
			return;
		}
		json_int_t n = json_integer_value(p);
		if ((unsigned long long)n > max_payload) {
			char m[300];
			snprintf(m, sizeof m, "payload of %lld bytes is over the limit of %zu (max-request-bytes)",
				 (long long)n, max_payload);
			fail(out, "too_large", "payload", m);
			out->discard = (size_t)n;
			return;
		}
		out->payload = (size_t)n;
	}
	/* from here on the payload is skipped with the error: the next line starts after it */
	out->discard = out->payload;
	json_t *op = json_object_get(msg, "op");
	if (!tag_ok)
		fail(out, "bad_request", "tag", "a tag is an integer or a string of at most 64 bytes");
	else if (!op)
		fail(out, "bad_request", "op", "missing: what to do (hello, submit, watch, ...)");
	else if (!json_is_string(op))
		fail(out, "bad_request", "op", "expected a string");
	else if (out->payload && strcmp(json_string_value(op), "submit") != 0)
		fail(out, "bad_request", "payload", "only submit takes a payload");
	else {
		out->kind = LINE_REQUEST;
		out->op = json_string_value(op);
		out->msg = msg;
		out->error_msg = NULL;
		out->discard = 0;
	}
}
