/* Files an outside input names, opened without blocking and only when regular (file_open.h). */
#include <errno.h>
#include <fcntl.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "util/file_open.h"

static const char *kind_name(mode_t mode)
{
	if (S_ISFIFO(mode))
		return "a FIFO";
	if (S_ISSOCK(mode))
		return "a socket";
	if (S_ISCHR(mode))
		return "a character device";
	if (S_ISBLK(mode))
		return "a block device";
	if (S_ISDIR(mode))
		return "a folder";
	return "not a regular file";
}

int aa_file_open_regular(const char *path, const char *field, struct aa_error *err)
{
	const char *f = field ? field : "";
	const char *sep = f[0] ? ": " : "";
	/* O_NONBLOCK: opening a FIFO with no writer returns at once instead of waiting for one */
	int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
	if (fd < 0) {
		int e = errno;
		if (e == ENXIO || e == EOPNOTSUPP) /* a socket, or a device without a driver */
			return aa_error_set(err, AA_ERR_INVALID, f, "%s%s'%s' is not a regular file", f, sep, path);
		return aa_error_set(err, e == ENOENT ? AA_ERR_NOT_FOUND : AA_ERR_IO, f, "%s%scannot open '%s': %s", f,
				    sep, path, strerror(e));
	}
	struct stat st;
	if (fstat(fd, &st) < 0) {
		int e = errno;
		close(fd);
		return aa_error_set(err, AA_ERR_IO, f, "%s%scannot read '%s': %s", f, sep, path, strerror(e));
	}
	if (!S_ISREG(st.st_mode)) {
		close(fd);
		const char *kind = kind_name(st.st_mode);
		return aa_error_set(err, AA_ERR_INVALID, f, "%s%s'%s' is %s%s", f, sep, path, kind,
				    strcmp(kind, "not a regular file") ? ", not a regular file" : "");
	}
	int flags = fcntl(fd, F_GETFL);
	if (flags >= 0)
		fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
	return fd;
}

FILE *aa_file_fopen_regular(const char *path, const char *field, struct aa_error *err)
{
	int fd = aa_file_open_regular(path, field, err);
	if (fd < 0)
		return NULL;
	FILE *f = fdopen(fd, "rb");
	if (!f) {
		int e = errno;
		close(fd);
		aa_error_set(err, AA_ERR_IO, field ? field : "", "cannot read '%s': %s", path, strerror(e));
	}
	return f;
}
