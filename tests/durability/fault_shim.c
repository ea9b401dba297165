/* An LD_PRELOAD shim for durability tests: wraps the calls an atomic write is made of (mkstemp, open,
 * write, fsync, close, rename, unlink), records their order with the paths involved, and fails or crashes
 * a chosen one, so that aalabd and aalab can be tested unchanged.
 *
 *   AALAB_FAULT_ROOT=DIR   only paths under DIR are recorded or faulted (default: all)
 *   AALAB_FAULT_LOG=FILE   appends one line per call: "OP PATH [PATH2]" (OP: mkstemp, open-write, write,
 *                          fsync, fsync-dir, syncfs, close, rename, unlink); paths are resolved through
 *                          /proc/self/fd, so files opened by fopen count too
 *   AALAB_FAULT=OP:GLOB[:N][:crash|:delay]
 *                          the Nth call (1-based; 0 or none: every call) of OP (write, fsync, syncfs, rename)
 *                          whose path's base name matches GLOB (fnmatch; for rename, the old or the new
 *                          name) fails: write with ENOSPC, the others with EIO; with ":crash" the
 *                          process is killed (SIGKILL) instead, before the call happens; with ":delay"
 *                          the call succeeds after 300 ms (a slow disk, to widen a window between two
 *                          steps that must look like one from outside)
 *
 * Built without sanitizers; in sanitizer builds the tests preload the sanitizer runtime first. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <fnmatch.h>
#include <limits.h>
#include <signal.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <time.h>
#include <unistd.h>

/* Set up once, when the shim is loaded; no locks afterwards: a record is one O_APPEND write (atomic for a
 * line this short) and the fault counter is atomic, so wrapped calls stay async-signal-safe (aalabd's
 * signal handlers write to a pipe). */
static int log_fd = -1;
static char root[PATH_MAX];
static struct {
	char op[16], glob[256];
	long nth, seen;
	bool crash, delay, active;
} fault;

__attribute__((constructor)) static void init(void)
{
	const char *r = getenv("AALAB_FAULT_ROOT");
	if (r && *r && !realpath(r, root))
		snprintf(root, sizeof root, "%s", r);
	const char *l = getenv("AALAB_FAULT_LOG");
	log_fd = l && *l ? (int)syscall(SYS_open, l, O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644) : -1;
	const char *f = getenv("AALAB_FAULT");
	if (f && *f) {
		char spec[400];
		snprintf(spec, sizeof spec, "%s", f);
		char *save = NULL, *op = strtok_r(spec, ":", &save), *glob = strtok_r(NULL, ":", &save);
		if (op && glob) {
			snprintf(fault.op, sizeof fault.op, "%s", op);
			snprintf(fault.glob, sizeof fault.glob, "%s", glob);
			fault.active = true;
			for (char *t; (t = strtok_r(NULL, ":", &save));) {
				if (strcmp(t, "crash") == 0)
					fault.crash = true;
				else if (strcmp(t, "delay") == 0)
					fault.delay = true;
				else
					fault.nth = strtol(t, NULL, 10);
			}
		}
	}
}

static bool under_root(const char *path)
{
	size_t n = strlen(root);
	return n == 0 || (strncmp(path, root, n) == 0 && (path[n] == '/' || path[n] == '\0'));
}

static void fd_path(int fd, char *out, size_t size)
{
	char link[64];
	snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
	ssize_t n = readlink(link, out, size - 1);
	out[n > 0 ? n : 0] = '\0';
}

static void absolute(const char *path, char *out, size_t size)
{
	char dir[PATH_MAX], full[PATH_MAX * 2];
	if (path[0] == '/' || !getcwd(dir, sizeof dir)) {
		snprintf(full, sizeof full, "%s", path);
	} else {
		snprintf(full, sizeof full, "%s/%s", dir, path);
	}
	/* the directory part resolves (the file itself may not exist yet) */
	char *slash = strrchr(full, '/');
	char resolved[PATH_MAX];
	if (slash && slash != full) {
		*slash = '\0';
		if (realpath(full, resolved)) {
			if ((size_t)snprintf(out, size, "%s/%s", resolved, slash + 1) >= size)
				out[0] = '\0'; /* too long to be one of ours */
			return;
		}
		*slash = '/';
	}
	if ((size_t)snprintf(out, size, "%s", full) >= size)
		out[0] = '\0';
}

static void record(const char *op, const char *a, const char *b)
{
	if (log_fd < 0 || !under_root(a))
		return;
	char line[PATH_MAX * 2 + 64];
	int n = snprintf(line, sizeof line, "%s %s%s%s\n", op, a, b ? " " : "", b ? b : "");
	if (n > 0)
		(void)!syscall(SYS_write, log_fd, line, (size_t)n < sizeof line ? (size_t)n : sizeof line - 1);
}

static bool base_matches(const char *path)
{
	const char *base = strrchr(path, '/');
	return fnmatch(fault.glob, base ? base + 1 : path, 0) == 0;
}

/* Whether this call must fail (or crash): op matches, a path matches, and it is the chosen one. */
static bool faulted(const char *op, const char *a, const char *b)
{
	if (!fault.active || strcmp(op, fault.op) != 0 || !under_root(a))
		return false;
	if (!base_matches(a) && !(b && base_matches(b)))
		return false;
	long seen = __atomic_add_fetch(&fault.seen, 1, __ATOMIC_SEQ_CST);
	if (fault.nth > 0 && seen != fault.nth)
		return false;
	if (fault.crash) {
		record("crash", a, b);
		kill(getpid(), SIGKILL);
	}
	if (fault.delay) {
		record("delay", a, b);
		struct timespec pause = {0, 300 * 1000 * 1000};
		while (nanosleep(&pause, &pause) < 0 && errno == EINTR)
			;
		return false;
	}
	record("fault", a, b);
	return true;
}

/* The next definition of name (libc's, or a sanitizer's interceptor's), looked up on first use. */
#define REAL(name, ret, args) \
	static ret(*real_##name) args; \
	if (!real_##name) \
		real_##name = (ret(*) args)dlsym(RTLD_NEXT, #name)

static int tracked_mkstemp(const char *name, char *templ, int flags, bool with_flags)
{
	REAL(mkstemp, int, (char *));
	REAL(mkostemp, int, (char *, int));
	int fd = with_flags ? real_mkostemp(templ, flags) : real_mkstemp(templ);
	if (fd >= 0) {
		char path[PATH_MAX];
		fd_path(fd, path, sizeof path);
		record(name, path, NULL);
	}
	return fd;
}

int mkstemp(char *templ) { return tracked_mkstemp("mkstemp", templ, 0, false); }
int mkstemp64(char *templ) { return tracked_mkstemp("mkstemp", templ, 0, false); }
int mkostemp(char *templ, int flags) { return tracked_mkstemp("mkstemp", templ, flags, true); }

static void note_open(int fd, int flags)
{
	if (fd < 0 || (flags & O_ACCMODE) == O_RDONLY)
		return;
	char path[PATH_MAX];
	fd_path(fd, path, sizeof path);
	record((flags & O_TRUNC) ? "open-truncate" : "open-write", path, NULL);
}

static mode_t mode_arg(int flags, va_list ap)
{
	return (flags & O_CREAT) || (flags & O_TMPFILE) == O_TMPFILE ? (mode_t)va_arg(ap, int) : 0;
}

int open(const char *path, int flags, ...)
{
	REAL(open, int, (const char *, int, ...));
	va_list ap;
	va_start(ap, flags);
	mode_t mode = mode_arg(flags, ap);
	va_end(ap);
	int fd = real_open(path, flags, mode);
	note_open(fd, flags);
	return fd;
}

int open64(const char *path, int flags, ...)
{
	REAL(open64, int, (const char *, int, ...));
	va_list ap;
	va_start(ap, flags);
	mode_t mode = mode_arg(flags, ap);
	va_end(ap);
	int fd = real_open64(path, flags, mode);
	note_open(fd, flags);
	return fd;
}

int openat(int dirfd, const char *path, int flags, ...)
{
	REAL(openat, int, (int, const char *, int, ...));
	va_list ap;
	va_start(ap, flags);
	mode_t mode = mode_arg(flags, ap);
	va_end(ap);
	int fd = real_openat(dirfd, path, flags, mode);
	note_open(fd, flags);
	return fd;
}

ssize_t write(int fd, const void *buf, size_t count)
{
	REAL(write, ssize_t, (int, const void *, size_t));
	char path[PATH_MAX];
	fd_path(fd, path, sizeof path);
	bool fail = path[0] == '/' && faulted("write", path, NULL);
	if (path[0] == '/')
		record(fail ? "write-failed" : "write", path, NULL);
	if (fail) {
		errno = ENOSPC;
		return -1;
	}
	return real_write(fd, buf, count);
}

static int tracked_sync(int fd, bool data_only)
{
	REAL(fsync, int, (int));
	REAL(fdatasync, int, (int));
	char path[PATH_MAX];
	fd_path(fd, path, sizeof path);
	struct stat st;
	bool dir = fstat(fd, &st) == 0 && S_ISDIR(st.st_mode);
	bool fail = faulted("fsync", path, NULL);
	record(fail ? "fsync-failed" : dir ? "fsync-dir" : "fsync", path, NULL);
	if (fail) {
		errno = EIO;
		return -1;
	}
	return data_only ? real_fdatasync(fd) : real_fsync(fd);
}

int fsync(int fd) { return tracked_sync(fd, false); }
int fdatasync(int fd) { return tracked_sync(fd, true); }

/* syncfs flushes a whole file system; its path is that of the descriptor it is given */
int syncfs(int fd)
{
	REAL(syncfs, int, (int));
	char path[PATH_MAX];
	fd_path(fd, path, sizeof path);
	bool fail = faulted("syncfs", path, NULL);
	record(fail ? "syncfs-failed" : "syncfs", path, NULL);
	if (fail) {
		errno = EIO;
		return -1;
	}
	return real_syncfs(fd);
}

int close(int fd)
{
	REAL(close, int, (int));
	char path[PATH_MAX];
	fd_path(fd, path, sizeof path);
	if (path[0] == '/' && fd != log_fd)
		record("close", path, NULL);
	return real_close(fd);
}

int rename(const char *from, const char *to)
{
	REAL(rename, int, (const char *, const char *));
	char a[PATH_MAX], b[PATH_MAX];
	absolute(from, a, sizeof a);
	absolute(to, b, sizeof b);
	bool fail = faulted("rename", a, b);
	record(fail ? "rename-failed" : "rename", a, b);
	if (fail) {
		errno = EIO;
		return -1;
	}
	return real_rename(from, to);
}

int unlink(const char *path)
{
	REAL(unlink, int, (const char *));
	char a[PATH_MAX];
	absolute(path, a, sizeof a);
	record("unlink", a, NULL);
	return real_unlink(path);
}
