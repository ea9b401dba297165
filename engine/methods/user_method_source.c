/* Where method and shader files come from (struct aa_file_source in user_method.h): the disk, or the
 * files sent with a job to aalabd; both refuse what is not a readable file of at most AA_USER_FILE_MAX
 * bytes. aa_file_join names a file relative to the one that refers to it. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <jansson.h>

#include "util/error.h"
#include "util/file_open.h"
#include "methods/user_method.h"

static int disk_read(void *ctx, const char *name, char **text, size_t *size, struct aa_error *err)
{
	(void)ctx;
	struct aa_error oe = {0};
	FILE *f = aa_file_fopen_regular(name, "", &oe); /* never blocks on a FIFO */
	if (!f)
		return aa_error_set(err, oe.code, "", "%s: %s", name, oe.code == AA_ERR_NOT_FOUND ? "not found" :
				    oe.code == AA_ERR_INVALID ? "not a regular file (a FIFO, socket or device)" : "cannot read");
	struct stat st;
	if (fstat(fileno(f), &st) != 0 || !S_ISREG(st.st_mode)) {
		fclose(f);
		return aa_error_set(err, AA_ERR_IO, "", "%s: not a regular file", name);
	}
	if (st.st_size > AA_USER_FILE_MAX) {
		fclose(f);
		return aa_error_set(err, AA_ERR_LIMIT, "", "%s: %lld bytes; a method or shader file may have at most %d",
				    name, (long long)st.st_size, AA_USER_FILE_MAX);
	}
	char *data = malloc((size_t)st.st_size + 1);
	size_t n = data ? fread(data, 1, (size_t)st.st_size, f) : 0;
	int failed = !data || n != (size_t)st.st_size || ferror(f);
	fclose(f);
	if (failed) {
		free(data);
		return aa_error_set(err, AA_ERR_IO, "", "%s: cannot read the whole file", name);
	}
	data[n] = '\0';
	*text = data;
	*size = n;
	return 0;
}

const struct aa_file_source aa_file_source_disk = {.read = disk_read};

static int json_read(void *ctx, const char *name, char **text, size_t *size, struct aa_error *err)
{
	const json_t *v = json_object_get(ctx, name);
	if (!json_is_string(v))
		return aa_error_set(err, AA_ERR_NOT_FOUND, "", "%s: not among the files sent with the job", name);
	size_t n = json_string_length(v);
	if (n > AA_USER_FILE_MAX)
		return aa_error_set(err, AA_ERR_LIMIT, "", "%s: %zu bytes; a method or shader file may have at most %d",
				    name, n, AA_USER_FILE_MAX);
	*text = malloc(n + 1);
	if (!*text)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	memcpy(*text, json_string_value(v), n);
	(*text)[n] = '\0';
	*size = n;
	return 0;
}

void aa_file_source_json(const struct json_t *files, struct aa_file_source *out)
{
	*out = (struct aa_file_source){.read = json_read, .ctx = (void *)files};
}

void aa_file_join(const char *referrer, const char *name, char *out, size_t size)
{
	const char *slash = strrchr(referrer, '/');
	if (name[0] == '/' || !slash)
		snprintf(out, size, "%s", name);
	else
		snprintf(out, size, "%.*s/%s", (int)(slash - referrer), referrer, name);
}
