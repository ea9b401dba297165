/* Whole files: read with a size limit, written atomically (a temporary file beside the target, fsync,
 * rename, fsync of the folder: a reader sees the old file or the new one, never half of one), and the
 * folders above a path made. */
#ifndef AA_FILE_IO_H
#define AA_FILE_IO_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "util/error.h"

/* The file's bytes in *data (malloc'ed, one NUL byte past the end), at most max bytes; more is an
 * AA_ERR_LIMIT error, a missing file AA_ERR_NOT_FOUND. */
int aa_file_read(const char *path, size_t max, uint8_t **data, size_t *size, struct aa_error *err);

/* Writes the parts, in order, as the file dir/name: a temporary file ".NAME.XXXXXX" in dir, fsync,
 * mode 0644, rename over name, fsync of dir. */
struct aa_file_part {
	const void *data;
	size_t size;
};
int aa_file_write_atomic(const char *dir, const char *name, const struct aa_file_part *parts, int count,
			 struct aa_error *err);
/* Whether name has the form of aa_file_write_atomic's temporary files. */
bool aa_file_is_temp_name(const char *name);
/* Removes dir/name when it is such a temporary file left by a writer that died (the writer holds a lock
 * on it until the rename; a crash releases it): 1 removed, 0 not (another name, or a live writer's). */
int aa_file_remove_stale_temp(const char *dir, const char *name);

/* mkdir -p of every folder of path up to its last '/' (path is restored); -1 with err naming it. */
int aa_file_make_parents(char *path, struct aa_error *err);
/* mkdir -p of path itself. */
int aa_file_make_dirs(const char *path, struct aa_error *err);

#endif
