/* Sending job data: the watch stream (events from the job's log, each with its frame as a payload when
 * asked, dropped with a notice when the client is behind) and stored files for get. */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "daemon.h"
#include "http_conn.h"
#include "jobs.h"
#include "stream.h"
#include "image/image.h"


static bool name_ok(const char *s, size_t n)
{
	if (n == 0 || s[0] == '.')
		return false;
	for (size_t i = 0; i < n; i++)
		if (!strchr("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789._-", s[i]) || !s[i])
			return false;
	return true;
}

int job_file_path(const char *jobs_dir, const char *id, const char *rel, char *out, size_t size)
{
	static const char *const top[] = {"results.json", "report.html", "events.jsonl", "scene.json",
					  "method-files.json", NULL};
	/* a suite keeps each case's report and images under cases/NAME/ (docs/results-format.md) */
	const char *inner = rel;
	bool in_case = !strncmp(rel, "cases/", 6);
	if (in_case) {
		const char *name = rel + 6, *slash = strchr(name, '/');
		if (!slash || !name_ok(name, (size_t)(slash - name)))
			return -1;
		inner = slash + 1;
	}
	/* images live in frames/, diff/ and flip/ as PNG, linear colour in linear/ as raw RGBA16F and in exr/
	 * as float EXR (engine/results/results.h) */
	bool ok = false;
	for (int i = 0; top[i]; i++)
		ok |= strcmp(inner, top[i]) == 0 && (!in_case || !strcmp(inner, "report.html"));
	bool linear = !strncmp(inner, "linear/", 7), exr = !strncmp(inner, "exr/", 4);
	if (!ok && (!strncmp(inner, "frames/", 7) || !strncmp(inner, "diff/", 5) || !strncmp(inner, "flip/", 5) || linear ||
		    exr)) {
		const char *name = strchr(inner, '/') + 1, *slash = strchr(name, '/');
		if (slash && name_ok(name, (size_t)(slash - name))) {
			const char *file = slash + 1;
			size_t digits = strspn(file, "0123456789");
			ok = digits >= 4 && digits <= 9 &&
			     strcmp(file + digits, linear ? ".rgba16f" : exr ? ".exr" : ".png") == 0;
		}
	}
	if (!ok && !strncmp(inner, "viewer/", 7)) { /* report.html's frame scripts (engine/report/report_viewer.c) */
		const size_t digits = strspn(inner + 7, "0123456789");
		ok = digits >= 4 && digits <= 9 && strcmp(inner + 7 + digits, ".js") == 0;
	}
	if (!ok || !name_ok(id, strlen(id)))
		return -1;
	return (size_t)snprintf(out, size, "%s/%s/%s", jobs_dir, id, rel) < size ? 0 : -1;
}


/* Frames as sent, shared by every watcher: a frame is read (and for rgba8 decoded) once, not once per
 * watcher, and recent ones are kept (up to FRAME_CACHE_SLOTS frames and FRAME_CACHE_BYTES), since
 * watchers of one job ask for the same frames at about the same time, or replay the same log. Keyed by
 * the file and its size and time, so a job run again never gets an old frame. */
#define FRAME_CACHE_SLOTS 32
#define FRAME_CACHE_BYTES (64u << 20)

struct cached_frame {
	char path[1400];
	int format;
	off_t file_size;
	struct timespec mtime;
	char *data;
	size_t size;
	int width, height;
	unsigned long last_use;
};

static struct cached_frame frame_cache[FRAME_CACHE_SLOTS];
static unsigned long frame_cache_clock;

void stream_cache_clear(void)
{
	for (int i = 0; i < FRAME_CACHE_SLOTS; i++) {
		free(frame_cache[i].data);
		frame_cache[i] = (struct cached_frame){0};
	}
}

static const struct cached_frame *frame_get(struct conn *c, const char *path, const struct stat *st)
{
	struct cached_frame *slot = &frame_cache[0];
	for (int i = 0; i < FRAME_CACHE_SLOTS; i++) {
		struct cached_frame *f = &frame_cache[i];
		if (f->data && f->format == c->watch->frames && f->file_size == st->st_size &&
		    f->mtime.tv_sec == st->st_mtim.tv_sec && f->mtime.tv_nsec == st->st_mtim.tv_nsec &&
		    !strcmp(f->path, path)) {
			f->last_use = ++frame_cache_clock;
			return f;
		}
		if (!f->data || f->last_use < slot->last_use)
			slot = f;
	}
	struct cached_frame fresh = {.format = c->watch->frames, .file_size = st->st_size, .mtime = st->st_mtim};
	snprintf(fresh.path, sizeof fresh.path, "%s", path);
	if (c->watch->frames == FRAMES_RGBA8) {
		struct aa_image_rgba8 img = {0};
		struct aa_error err = {0};
		if (aa_image_read_rgba8(path, &img, &err))
			return NULL;
		fresh.data = (char *)img.pixels;
		fresh.size = (size_t)img.width * img.height * 4;
		fresh.width = img.width;
		fresh.height = img.height;
	} else { /* PNG bytes, or raw RGBA16F halves stored as they are sent */
		if (read_whole_file(path, c->t->cfg->client_buffer_bytes * 4, &fresh.data, &fresh.size))
			return NULL;
		fresh.width = c->watch->job->spec.width;
		fresh.height = c->watch->job->spec.height;
	}
	free(slot->data);
	*slot = fresh;
	slot->last_use = ++frame_cache_clock;
	/* within the byte budget: the least recently used others go first */
	for (;;) {
		size_t total = 0;
		struct cached_frame *oldest = NULL;
		for (int i = 0; i < FRAME_CACHE_SLOTS; i++) {
			struct cached_frame *f = &frame_cache[i];
			total += f->data ? f->size : 0;
			if (f->data && f != slot && (!oldest || f->last_use < oldest->last_use))
				oldest = f;
		}
		if (total <= FRAME_CACHE_BYTES || !oldest)
			break;
		free(oldest->data);
		*oldest = (struct cached_frame){0};
	}
	return slot;
}

/* The bytes a frame will take in the stream, known before reading it. */
static size_t frame_size_estimate(const struct conn *c, const struct stat *st)
{
	const struct aa_job_spec *spec = &c->watch->job->spec;
	if (c->watch->frames == FRAMES_RGBA8)
		return (size_t)spec->width * spec->height * 4;
	return (size_t)st->st_size;
}

/* Sends one event of the log, with its frame as a payload when the watch asked for frames. */
static void send_event(struct conn *c, char *line)
{
	json_t *ev = NULL;
	const char *image = NULL;
	if (c->watch->frames != FRAMES_NONE && (ev = json_loads(line, 0, NULL)))
		image = json_string_value(json_object_get(ev, c->watch->frames == FRAMES_RGBA16F ? "linear" : "image"));
	if (!image) {
		size_t n = strlen(line);
		line[n] = '\n'; /* the caller's copy: its terminator becomes the newline */
		conn_send(c, line, n + 1);
		json_decref(ev);
		return;
	}
	char path[1400];
	struct stat st;
	bool have = job_file_path(conn_daemon(c)->store->dir, c->watch->job->id, image, path, sizeof path) == 0 &&
		    stat(path, &st) == 0;
	/* A client that is behind loses frames, never events, and never slows the renderer. The check comes
	 * before the frame is read or decoded, so a stalled watcher costs the loop no more than an idle one. */
	if (have && conn_pending(c) > 0 && conn_pending(c) + frame_size_estimate(c, &st) > c->t->cfg->client_buffer_bytes) {
		have = false;
		c->watch->frames_dropped++;
		c->t->stats.frames_dropped_total++;
		json_object_set_new(ev, "frame_dropped", json_string("client too slow: frame not sent"));
	}
	const struct cached_frame *frame = have ? frame_get(c, path, &st) : NULL;
	if (frame) {
		/* raw RGBA16F has no header: a suite's event carries its case's size, others the job's */
		if (c->watch->frames == FRAMES_RGBA8 || (c->watch->frames == FRAMES_RGBA16F && !json_object_get(ev, "width"))) {
			json_object_set_new(ev, "width", json_integer(frame->width));
			json_object_set_new(ev, "height", json_integer(frame->height));
		}
		json_object_set_new(ev, "payload", json_integer((json_int_t)frame->size));
		static const char *const formats[] = {"none", "png", "rgba8", "rgba16f"};
		json_object_set_new(ev, "payload_format", json_string(formats[c->watch->frames]));
	}
	conn_send_json(c, ev);
	if (frame)
		conn_send(c, frame->data, frame->size);
}

void stream_pump_watch(struct conn *c)
{
	struct daemon *d = conn_daemon(c);
	struct store *s = d->store;
	while (!c->closed && c->watch && conn_pending(c) < d->cfg.client_buffer_bytes) {
		pthread_mutex_lock(&s->lock);
		struct job *job = c->watch->job;
		char *line = NULL;
		bool end = false;
		char id[sizeof job->id];
		snprintf(id, sizeof id, "%s", job->id);
		if (c->watch->next_seq <= job->event_count)
			line = strdup(job->events[c->watch->next_seq - 1]);
		else
			end = job->log_complete;
		struct watch *w = c->watch;
		if (end) {
			job_release(s, job); /* the job may be gone from here on (jobs.h) */
			c->watch = NULL;
		}
		pthread_mutex_unlock(&s->lock);
		if (end) {
			json_t *o = json_pack("{ss ss sI}", "event", "watch_end", "job", id, "frames_dropped",
					      (json_int_t)w->frames_dropped);
			if (w->tag)
				json_object_set(o, "tag", w->tag);
			json_decref(w->tag);
			free(w);
			conn_send_json(c, o);
			conn_finish_watch(c);
			return;
		}
		if (!line)
			return;
		c->watch->next_seq++;
		send_event(c, line);
		free(line);
	}
}

void stream_end_watch(struct conn *c)
{
	struct watch *w = c->watch;
	if (!w)
		return;
	struct store *s = conn_daemon(c)->store;
	pthread_mutex_lock(&s->lock);
	job_release(s, w->job);
	pthread_mutex_unlock(&s->lock);
	c->watch = NULL;
	json_decref(w->tag);
	free(w);
}

static void list_files(const char *base, const char *rel, json_t *out, int depth)
{
	char path[1600];
	snprintf(path, sizeof path, "%s%s%s", base, *rel ? "/" : "", rel);
	DIR *dir = opendir(path);
	if (!dir)
		return;
	struct dirent *de;
	while ((de = readdir(dir))) {
		if (de->d_name[0] == '.')
			continue;
		char sub[600];
		snprintf(sub, sizeof sub, "%s%s%s", rel, *rel ? "/" : "", de->d_name);
		if (depth == 0 && !strcmp(de->d_name, "cases")) /* a suite: each case's folder is listed as a job's */
			list_files(base, sub, out, -1);
		else if (depth == -1)
			list_files(base, sub, out, 0);
		else if (depth == 0 && !strcmp(de->d_name, "viewer")) /* viewer/NNNN.js: files right below it */
			list_files(base, sub, out, 2);
		else if (depth < 2 && (depth > 0 || !strcmp(de->d_name, "frames") || !strcmp(de->d_name, "diff") ||
				       !strcmp(de->d_name, "flip") || !strcmp(de->d_name, "linear") ||
				       !strcmp(de->d_name, "exr")))
			list_files(base, sub, out, depth + 1);
		else if (depth == 2 || strcmp(de->d_name, "job.json") != 0)
			json_array_append_new(out, json_string(sub));
	}
	closedir(dir);
}

void op_get(struct conn *c, json_t *msg, json_t *tag)
{
	json_t *jid = json_object_get(msg, "job"), *jfile = json_object_get(msg, "file");
	const char *key;
	json_t *v;
	json_object_foreach(msg, key, v)
		if (strcmp(key, "op") && strcmp(key, "tag") && strcmp(key, "job") && strcmp(key, "file")) {
			protocol_error(c, tag, "bad_request", key, "unknown key for op 'get'");
			return;
		}
	const char *id = json_string_value(jid), *file = json_string_value(jfile);
	if (!id || strlen(id) >= 16) {
		protocol_error(c, tag, "bad_request", "job", "a job id is a string like \"000042\"");
		return;
	}
	if (jfile && !file) {
		protocol_error(c, tag, "bad_request", "file", "expected a file name such as results.json");
		return;
	}
	pthread_mutex_lock(&conn_daemon(c)->store->lock);
	struct job *job = store_find(conn_daemon(c)->store, id);
	enum job_state state = job ? job->state : JOB_QUEUED;
	pthread_mutex_unlock(&conn_daemon(c)->store->lock);
	if (!job) {
		protocol_error(c, tag, "not_found", "job", "no job '%s'", id);
		return;
	}
	char path[1400];
	if (!file) {
		json_t *files = json_array();
		snprintf(path, sizeof path, "%s/%s", conn_daemon(c)->store->dir, id);
		list_files(path, "", files, 0);
		json_t *o = json_pack("{ss ss so}", "job", id, "state", job_state_name(state), "files", files);
		json_object_set_new(o, "ok", json_true());
		if (tag)
			json_object_set(o, "tag", tag);
		conn_send_json(c, o);
		return;
	}
	if (job_file_path(conn_daemon(c)->store->dir, id, file, path, sizeof path)) {
		protocol_error(c, tag, "invalid", "file", "not a file of a job: results.json, report.html, events.jsonl, "
			       "scene.json, method-files.json, frames|diff|flip/NAME/NNNN.png, linear/NAME/NNNN.rgba16f, "
			       "exr/NAME/NNNN.exr or viewer/NNNN.js");
		return;
	}
	char *data;
	size_t size;
	if (read_whole_file(path, 1u << 30, &data, &size)) {
		protocol_error(c, tag, "not_found", "file", "job %s has no %s (yet): %s", id, file,
			       errno ? strerror(errno) : "unreadable");
		return;
	}
	json_t *o = json_pack("{sb ss ss sI ss}", "ok", 1, "job", id, "file", file, "payload", (json_int_t)size,
			      "payload_format", file_content_type(file));
	if (tag)
		json_object_set(o, "tag", tag);
	conn_send_json(c, o);
	conn_send(c, data, size);
	free(data);
}
