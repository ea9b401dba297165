/* Error values: a code, the path of the bad field and a readable message. */
#include "util/error.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

int aa_error_set(struct aa_error *err, enum aa_error_code code, const char *path,
		 const char *fmt, ...)
{
	if (!err)
		return -1;
	err->code = code;
	snprintf(err->path, sizeof err->path, "%s", path ? path : "");
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(err->message, sizeof err->message, fmt, ap);
	va_end(ap);
	return -1;
}

void aa_error_prefix(struct aa_error *err, const char *fmt, ...)
{
	if (!err)
		return;
	char joined[sizeof err->message * 2];
	va_list ap;
	va_start(ap, fmt);
	int n = vsnprintf(joined, sizeof err->message, fmt, ap);
	va_end(ap);
	if (n < 0)
		return;
	size_t len = strlen(joined);
	snprintf(joined + len, sizeof joined - len, ": %s", err->message);
	/* the combined text is cut to the message size, keeping the prefix */
	memcpy(err->message, joined, sizeof err->message - 1);
	err->message[sizeof err->message - 1] = 0;
}

const char *aa_error_code_name(enum aa_error_code code)
{
	switch (code) {
	case AA_OK: return "ok";
	case AA_ERR_INVALID: return "invalid";
	case AA_ERR_NOT_FOUND: return "not_found";
	case AA_ERR_IO: return "io";
	case AA_ERR_GPU: return "gpu";
	case AA_ERR_LIMIT: return "limit";
	case AA_ERR_CANCELLED: return "cancelled";
	case AA_ERR_INTERNAL: return "internal";
	}
	return "unknown";
}
