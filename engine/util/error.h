/* Errors that carry a message a user can act on and the path of the bad field. */
#ifndef AA_ERROR_H
#define AA_ERROR_H

#include <stddef.h>

enum aa_error_code {
	AA_OK = 0,
	AA_ERR_INVALID = 1,   /* bad input: request, scene file, parameter, image */
	AA_ERR_NOT_FOUND = 2, /* named scene, method, file or job does not exist */
	AA_ERR_IO = 3,        /* reading or writing a file failed */
	AA_ERR_GPU = 4,       /* Vulkan failed or the device lacks something needed */
	AA_ERR_LIMIT = 5,     /* a configured limit was exceeded */
	AA_ERR_CANCELLED = 6,
	AA_ERR_INTERNAL = 7,
};

struct aa_error {
	enum aa_error_code code;
	char path[256];    /* the field at fault, e.g. "methods[1].params.samples", or "" */
	char message[768]; /* what is wrong, in words a user can act on */
};

/* Sets err (if not NULL) and returns -1, so callers can `return aa_error_set(...)`. */
int aa_error_set(struct aa_error *err, enum aa_error_code code, const char *path,
		 const char *fmt, ...) __attribute__((format(printf, 4, 5)));
/* Prefixes the existing message with "prefix: ". */
void aa_error_prefix(struct aa_error *err, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
const char *aa_error_code_name(enum aa_error_code code);

#endif
