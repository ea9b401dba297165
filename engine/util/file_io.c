/* Whole files read and written atomically (file_io.h). */
#include <errno.h>
#include <fcntl.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include "util/file_io.h"
#include "util/file_open.h"

int aa_file_read(const char *path, size_t max, uint8_t **data, size_t *size, struct aa_error *err)
{
	*data = NULL;
	*size = 0;
	const int fd = aa_file_open_regular(path, "", err); /* never blocks on a FIFO or a device */
	if (fd < 0)
		return -1;
	struct stat st;
	if (fstat(fd, &st) < 0) {
		const int saved = errno;
		close(fd);
		return aa_error_set(err, AA_ERR_IO, "", "cannot read %s: %s", path, strerror(saved));
	}
	if ((uint64_t)st.st_size > max) {
		close(fd);
		return aa_error_set(err, AA_ERR_LIMIT, "", "%s is %lld bytes, over the limit of %zu", path,
				    (long long)st.st_size, max);
	}
	uint8_t *buf = malloc((size_t)st.st_size + 1);
	if (!buf) {
		close(fd);
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory reading %s", path);
	}
	size_t done = 0;
	int failed = 0;
	while (done < (size_t)st.st_size) {
		const ssize_t r = read(fd, buf + done, (size_t)st.st_size - done);
		if (r < 0 && errno == EINTR)
			continue;
		if (r < 0)
			failed = errno;
		if (r <= 0)
			break; /* or shorter than it was: what was read is the file now */
		done += (size_t)r;
	}
	close(fd);
	if (failed) {
		free(buf);
		return aa_error_set(err, AA_ERR_IO, "", "cannot read %s: %s", path, strerror(failed));
	}
	buf[done] = 0;
	*data = buf;
	*size = done;
	return 0;
}

int aa_file_write_atomic(const char *dir, const char *name, const struct aa_file_part *parts, int count,
			 struct aa_error *err)
{
	char tmp[4096], final[4096];
	if ((size_t)snprintf(final, sizeof final, "%s/%s", dir, name) >= sizeof final ||
	    (size_t)snprintf(tmp, sizeof tmp, "%s/.%s.XXXXXX", dir, name) >= sizeof tmp)
		return aa_error_set(err, AA_ERR_IO, "", "path %s/%s is too long", dir, name);
	/* The temp file lives in the same directory so that rename() replaces the file in one step. */
	const int fd = mkstemp(tmp);
	if (fd < 0)
		return aa_error_set(err, AA_ERR_IO, "", "cannot create a file in %s: %s", dir, strerror(errno));
	/* held until the file is renamed or its writer dies: a temporary file whose lock can be taken was
	 * left by a writer that died (aa_file_remove_stale_temp) */
	flock(fd, LOCK_EX);
	for (int i = 0; i < count; i++) {
		const char *data = parts[i].data;
		for (size_t done = 0; done < parts[i].size;) {
			const ssize_t w = write(fd, data + done, parts[i].size - done);
			if (w < 0 && errno == EINTR)
				continue;
			if (w <= 0) {
				if (w == 0)
					errno = EIO; /* a write of zero bytes leaves errno as it was */
				aa_error_set(err, AA_ERR_IO, "", "cannot write %s: %s", tmp, strerror(errno));
				goto fail;
			}
			done += (size_t)w;
		}
	}
	if (fchmod(fd, 0644) < 0 || fsync(fd) < 0) {
		aa_error_set(err, AA_ERR_IO, "", "cannot sync %s: %s", tmp, strerror(errno));
		goto fail;
	}
	if (close(fd) < 0) {
		aa_error_set(err, AA_ERR_IO, "", "cannot write %s: %s", tmp, strerror(errno));
		unlink(tmp);
		return -1;
	}
	if (rename(tmp, final) < 0) {
		aa_error_set(err, AA_ERR_IO, "", "cannot rename %s to %s: %s", tmp, final, strerror(errno));
		unlink(tmp);
		return -1;
	}
	/* The rename itself is durable only once the directory is synced. */
	const int dfd = open(dir, O_RDONLY | O_DIRECTORY);
	if (dfd < 0 || fsync(dfd) < 0) {
		aa_error_set(err, AA_ERR_IO, "", "cannot sync directory %s: %s", dir, strerror(errno));
		if (dfd >= 0)
			close(dfd);
		return -1;
	}
	close(dfd);
	return 0;
fail:
	close(fd);
	unlink(tmp);
	return -1;
}

bool aa_file_is_temp_name(const char *name)
{
	const size_t len = strlen(name);
	if (len < 9 || name[0] != '.' || name[len - 7] != '.')
		return false;
	for (size_t i = len - 6; i < len; i++)
		if (!((name[i] >= 'A' && name[i] <= 'Z') || (name[i] >= 'a' && name[i] <= 'z') ||
		      (name[i] >= '0' && name[i] <= '9')))
			return false;
	return true;
}

int aa_file_remove_stale_temp(const char *dir, const char *name)
{
	char path[4096];
	if (!aa_file_is_temp_name(name) || (size_t)snprintf(path, sizeof path, "%s/%s", dir, name) >= sizeof path)
		return 0;
	const int fd = open(path, O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
	if (fd < 0)
		return 0;
	struct stat st;
	int removed = 0;
	/* a live writer holds the lock: its file stays */
	if (fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && flock(fd, LOCK_EX | LOCK_NB) == 0)
		removed = unlink(path) == 0;
	close(fd);
	return removed;
}

static int make_one(char *path, struct aa_error *err)
{
	const bool failed = mkdir(path, 0755) < 0 && errno != EEXIST;
	const int saved = errno;
	struct stat st;
	const bool is_dir = !failed && stat(path, &st) == 0 && S_ISDIR(st.st_mode);
	if (failed || !is_dir)
		return aa_error_set(err, AA_ERR_IO, "", "cannot create directory %s: %s", path,
				    failed ? strerror(saved) : "a file of that name exists");
	return 0;
}

int aa_file_make_parents(char *path, struct aa_error *err)
{
	for (char *p = path + 1; *p; p++) {
		if (*p != '/')
			continue;
		*p = '\0';
		const int rc = make_one(path, err);
		*p = '/';
		if (rc)
			return -1;
	}
	return 0;
}

int aa_file_make_dirs(const char *path, struct aa_error *err)
{
	char buf[4096];
	if ((size_t)snprintf(buf, sizeof buf, "%s/", path) >= sizeof buf)
		return aa_error_set(err, AA_ERR_IO, "", "path %s is too long", path);
	return aa_file_make_parents(buf, err);
}
