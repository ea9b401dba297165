/* aalab run's output folder: checked before the job, written under a temporary name, renamed when
 * complete; Ctrl-C says what was kept. */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <ftw.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <jansson.h>

#include "out_dir.h"

static int mkdir_p(const char *dir)
{
	char tmp[1024];
	snprintf(tmp, sizeof tmp, "%s", dir);
	for (char *p = tmp + 1; *p; p++)
		if (*p == '/') {
			*p = 0;
			if (mkdir(tmp, 0777) != 0 && errno != EEXIST)
				return -1;
			*p = '/';
		}
	return mkdir(tmp, 0777) != 0 && errno != EEXIST ? -1 : 0;
}

static int remove_entry(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
	(void)st; (void)flag; (void)ftw;
	return remove(path) < 0 && errno != ENOENT ? -1 : 0;
}

static void remove_tree(const char *dir)
{
	nftw(dir, remove_entry, 16, FTW_DEPTH | FTW_PHYS);
}

/* An aalab result is a folder with a results.json that has the results' own fields (a suite's: its cases). */
static bool is_aalab_result(const char *dir)
{
	char path[1100];
	snprintf(path, sizeof path, "%s/results.json", dir);
	json_t *r = json_load_file(path, 0, NULL);
	bool yes = json_is_object(r) &&
		   ((json_object_get(r, "methods") && json_object_get(r, "reference")) ||
		    json_is_array(json_object_get(r, "cases"))) &&
		   json_object_get(r, "job");
	json_decref(r);
	return yes;
}

static bool is_empty_dir(const char *dir)
{
	DIR *d = opendir(dir);
	if (!d)
		return false;
	struct dirent *de;
	bool empty = true;
	while (empty && (de = readdir(d)))
		empty = !strcmp(de->d_name, ".") || !strcmp(de->d_name, "..");
	closedir(d);
	return empty;
}

int aa_out_dir_prepare(struct aa_out_dir *o, const char *dir, bool force, char *err, size_t err_size)
{
	memset(o, 0, sizeof *o);
	size_t n = strlen(dir);
	while (n > 1 && dir[n - 1] == '/')
		n--;
	if (n == 0 || n >= sizeof o->final - 40) {
		snprintf(err, err_size, "out: '%s' is not a usable folder name", dir);
		return -1;
	}
	memcpy(o->final, dir, n);
	o->final[n] = 0;
	struct stat st;
	if (stat(o->final, &st) == 0) {
		if (!S_ISDIR(st.st_mode)) {
			snprintf(err, err_size, "out: '%s' exists and is not a folder", o->final);
			return -1;
		}
		if (!is_empty_dir(o->final)) {
			if (!is_aalab_result(o->final)) {
				snprintf(err, err_size, "out: '%s' is not empty and is not an aalab result; refusing to write "
					 "into it (choose another --out)", o->final);
				return -1;
			}
			if (!force) {
				snprintf(err, err_size, "out: '%s' holds an earlier aalab result; --force replaces it, or "
					 "choose another --out", o->final);
				return -1;
			}
			o->replace = true;
		}
	}
	/* the temporary folder sits beside DIR, so that the rename stays on one file system */
	char parent[1024];
	snprintf(parent, sizeof parent, "%s", o->final);
	char *slash = strrchr(parent, '/');
	const char *base = slash ? slash + 1 : parent;
	if (slash == parent)
		parent[1] = 0;
	else if (slash)
		*slash = 0;
	if (slash && mkdir_p(parent)) {
		snprintf(err, err_size, "out: cannot create '%s': %s", parent, strerror(errno));
		return -1;
	}
	snprintf(o->work, sizeof o->work, "%s%s.%s.aalab-partial.XXXXXX", slash ? parent : "",
		 slash && strcmp(parent, "/") ? "/" : "", base);
	if (!mkdtemp(o->work)) {
		snprintf(err, err_size, "out: cannot create a folder beside '%s': %s", o->final, strerror(errno));
		return -1;
	}
	chmod(o->work, 0777 & ~umask(umask(0))); /* mkdtemp makes 0700; results are as readable as mkdir's */
	return 0;
}

int aa_out_dir_commit(struct aa_out_dir *o, char *err, size_t err_size)
{
	char old[1200] = "";
	struct stat st;
	/* every frame, image and file in the folder on disk before the rename publishes it: one syncfs of
	 * the file system rather than an fsync per image (a long job writes thousands) */
	int work_fd = open(o->work, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
	if (work_fd < 0 || syncfs(work_fd) != 0) {
		snprintf(err, err_size, "out: cannot sync the results in '%s' to disk: %s", o->work, strerror(errno));
		if (work_fd >= 0)
			close(work_fd);
		return -1;
	}
	close(work_fd);
	if (stat(o->final, &st) == 0) {
		/* an empty folder, or an earlier result that --force replaces: moved aside, removed after */
		snprintf(old, sizeof old, "%s.aalab-old.%ld", o->final, (long)getpid());
		if (rename(o->final, old) != 0) {
			snprintf(err, err_size, "out: cannot move '%s' aside: %s (the results are in %s)", o->final,
				 strerror(errno), o->work);
			return -1;
		}
	}
	if (rename(o->work, o->final) != 0) {
		snprintf(err, err_size, "out: cannot rename '%s' to '%s': %s", o->work, o->final, strerror(errno));
		if (old[0])
			rename(old, o->final);
		return -1;
	}
	if (old[0])
		remove_tree(old);
	o->work[0] = 0; /* it is DIR now */
	/* the rename survives a crash only once the folder holding DIR is synced */
	char parent[1024];
	snprintf(parent, sizeof parent, "%s", o->final);
	char *slash = strrchr(parent, '/');
	if (!slash)
		snprintf(parent, sizeof parent, ".");
	else
		slash[slash == parent] = 0;
	int fd = open(parent, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
	if (fd < 0 || fsync(fd) != 0) {
		snprintf(err, err_size, "out: cannot sync directory '%s' after renaming the results into it: %s "
			 "(they are in '%s' but may not survive a crash)", parent, strerror(errno), o->final);
		if (fd >= 0)
			close(fd);
		return -1;
	}
	close(fd);
	return 0;
}

void aa_out_dir_discard(struct aa_out_dir *o)
{
	if (o->work[0])
		remove_tree(o->work);
}

static char interrupt_head[3300], interrupt_tail[3300];
static volatile int *interrupt_frames;

static void put_number(char *buf, size_t *n, int v)
{
	char digits[16];
	int k = 0;
	do {
		digits[k++] = (char)('0' + v % 10);
		v /= 10;
	} while (v > 0 && k < 15);
	while (k > 0)
		buf[(*n)++] = digits[--k];
}

/* Async-signal-safe: the message was written before the job; only the count is added here. */
static void on_interrupt(int sig)
{
	(void)sig;
	char msg[6700];
	size_t n = 0, h = strlen(interrupt_head), t = strlen(interrupt_tail);
	memcpy(msg + n, interrupt_head, h);
	n += h;
	if (interrupt_frames)
		put_number(msg, &n, *interrupt_frames);
	memcpy(msg + n, interrupt_tail, t);
	n += t;
	(void)h;
	ssize_t w = write(STDERR_FILENO, msg, n);
	(void)w;
	_exit(130);
}

void aa_out_dir_on_interrupt(struct aa_out_dir *o, bool in_daemon, volatile int *frames_written, int frames_total)
{
	const char *dir_state = o->replace ? "still holds the earlier result" : "was not written";
	if (frames_written) {
		snprintf(interrupt_head, sizeof interrupt_head, "\naalab run: interrupted; kept ");
		snprintf(interrupt_tail, sizeof interrupt_tail, " of %d frames' images, written so far, in %s (no "
			 "results.json); %s %s\n", frames_total, o->work, o->final, dir_state);
	} else {
		snprintf(interrupt_head, sizeof interrupt_head, "\naalab run: interrupted; what was written so far "
			 "is in %s (no results.json%s); %s %s\n", o->work,
			 in_daemon ? "; the job goes on in aalabd: aalab cancel" : "", o->final, dir_state);
		interrupt_tail[0] = 0;
	}
	interrupt_frames = frames_written;
	struct sigaction sa = {.sa_handler = on_interrupt};
	sigemptyset(&sa.sa_mask);
	sigaction(SIGINT, &sa, NULL);
	sigaction(SIGTERM, &sa, NULL);
}
