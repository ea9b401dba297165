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
#include "jobs.h"
#include "image/image.h"

int read_whole_file(const char *path, size_t max, char **data, size_t *size)
{
	int fd = open(path, O_RDONLY | O_CLOEXEC);
	struct stat st;
	if (fd < 0)
		return -1;
	if (fstat(fd, &st) < 0 || !S_ISREG(st.st_mode) || (size_t)st.st_size > max) {
		close(fd);
		return -1;
	}
	char *buf = malloc((size_t)st.st_size + 1);
	size_t got = 0;
	while (buf && got < (size_t)st.st_size) {
		ssize_t n = read(fd, buf + got, (size_t)st.st_size - got);
		if (n <= 0)
			break;
		got += (size_t)n;
	}
	close(fd);
	if (!buf || got != (size_t)st.st_size) {
		free(buf);
		return -1;
	}
	*data = buf;
	*size = got;
	return 0;
}

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
	static const char *const top[] = {"results.json", "report.html", "events.jsonl", "scene.json", NULL};
	/* images live in frames/, diff/ and flip/ as PNG, linear colour in linear/ as raw RGBA16F
	 * (engine/results/results.h) */
	bool ok = false;
	for (int i = 0; top[i]; i++)
		ok |= strcmp(rel, top[i]) == 0;
	bool linear = !strncmp(rel, "linear/", 7);
	if (!ok && (!strncmp(rel, "frames/", 7) || !strncmp(rel, "diff/", 5) || !strncmp(rel, "flip/", 5) || linear)) {
		const char *name = strchr(rel, '/') + 1, *slash = strchr(name, '/');
		if (slash && name_ok(name, (size_t)(slash - name))) {
			const char *file = slash + 1;
			size_t digits = strspn(file, "0123456789");
			ok = digits >= 4 && digits <= 9 && strcmp(file + digits, linear ? ".rgba16f" : ".png") == 0;
		}
	}
	if (!ok || !name_ok(id, strlen(id)))
		return -1;
	return (size_t)snprintf(out, size, "%s/%s/%s", jobs_dir, id, rel) < size ? 0 : -1;
}

const char *file_content_type(const char *rel)
{
	size_t n = strlen(rel);
	if (n > 5 && !strcmp(rel + n - 5, ".json"))
		return "application/json";
	if (n > 6 && !strcmp(rel + n - 6, ".jsonl"))
		return "application/jsonl";
	if (n > 5 && !strcmp(rel + n - 5, ".html"))
		return "text/html; charset=utf-8";
	if (n > 4 && !strcmp(rel + n - 4, ".png"))
		return "image/png";
	if (n > 3 && !strcmp(rel + n - 3, ".js"))
		return "text/javascript; charset=utf-8";
	if (n > 4 && !strcmp(rel + n - 4, ".css"))
		return "text/css; charset=utf-8";
	return "application/octet-stream";
}

/* Sends one event of the log, with its frame as a payload when the watch asked for frames. */
static void send_event(struct conn *c, char *line)
{
	json_t *ev = NULL;
	const char *image = NULL;
	if (c->watch_frames != FRAMES_NONE && (ev = json_loads(line, 0, NULL)))
		image = json_string_value(json_object_get(ev, c->watch_frames == FRAMES_RGBA16F ? "linear" : "image"));
	if (!image) {
		size_t n = strlen(line);
		line[n] = '\n'; /* the caller's copy: its terminator becomes the newline */
		conn_send(c, line, n + 1);
		json_decref(ev);
		return;
	}
	char path[1400];
	char *data = NULL;
	size_t size = 0;
	struct aa_image_rgba8 img = {0};
	struct aa_error err = {0};
	bool have = job_file_path(c->d->store->dir, c->watch_job->id, image, path, sizeof path) == 0;
	if (have && c->watch_frames == FRAMES_RGBA8) {
		have = aa_image_read_rgba8(path, &img, &err) == 0;
		data = (char *)img.pixels;
		size = (size_t)img.width * img.height * 4;
		json_object_set_new(ev, "width", json_integer(img.width));
		json_object_set_new(ev, "height", json_integer(img.height));
	} else if (have) { /* PNG bytes, or raw RGBA16F halves stored as they are sent */
		have = read_whole_file(path, c->d->cfg.client_buffer_bytes * 4, &data, &size) == 0;
		if (c->watch_frames == FRAMES_RGBA16F) {
			json_object_set_new(ev, "width", json_integer(c->watch_job->spec.width));
			json_object_set_new(ev, "height", json_integer(c->watch_job->spec.height));
		}
	}
	/* a client that is behind loses frames, never events, and never slows the renderer */
	if (have && conn_pending(c) > 0 && conn_pending(c) + size > c->d->cfg.client_buffer_bytes) {
		have = false;
		c->frames_dropped++;
		c->d->stats.frames_dropped_total++;
		json_object_set_new(ev, "frame_dropped", json_string("client too slow: frame not sent"));
	}
	if (have) {
		json_object_set_new(ev, "payload", json_integer((json_int_t)size));
		static const char *const formats[] = {"none", "png", "rgba8", "rgba16f"};
		json_object_set_new(ev, "payload_format", json_string(formats[c->watch_frames]));
	}
	conn_send_json(c, ev);
	if (have)
		conn_send(c, data, size);
	free(data);
}

void protocol_pump_watch(struct conn *c)
{
	struct daemon *d = c->d;
	struct store *s = d->store;
	while (!c->closed && c->watch_job && conn_pending(c) < d->cfg.client_buffer_bytes) {
		pthread_mutex_lock(&s->lock);
		struct job *job = c->watch_job;
		char *line = NULL;
		bool end = false;
		if (c->watch_next_seq <= job->event_count)
			line = strdup(job->events[c->watch_next_seq - 1]);
		else
			end = job->log_complete;
		if (end)
			job->watchers--;
		pthread_mutex_unlock(&s->lock);
		if (end) {
			json_t *o = json_pack("{ss ss sI}", "event", "watch_end", "job", job->id, "frames_dropped",
					      (json_int_t)c->frames_dropped);
			if (c->watch_tag)
				json_object_set(o, "tag", c->watch_tag);
			c->watch_job = NULL;
			conn_send_json(c, o);
			conn_finish_watch(c);
			return;
		}
		if (!line)
			return;
		c->watch_next_seq++;
		send_event(c, line);
		free(line);
	}
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
		if (depth < 2 && (depth > 0 || !strcmp(de->d_name, "frames") || !strcmp(de->d_name, "diff") ||
				  !strcmp(de->d_name, "flip") || !strcmp(de->d_name, "linear")))
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
	pthread_mutex_lock(&c->d->store->lock);
	struct job *job = store_find(c->d->store, id);
	enum job_state state = job ? job->state : JOB_QUEUED;
	pthread_mutex_unlock(&c->d->store->lock);
	if (!job) {
		protocol_error(c, tag, "not_found", "job", "no job '%s'", id);
		return;
	}
	char path[1400];
	if (!file) {
		json_t *files = json_array();
		snprintf(path, sizeof path, "%s/%s", c->d->store->dir, id);
		list_files(path, "", files, 0);
		json_t *o = json_pack("{ss ss so}", "job", id, "state", job_state_name(state), "files", files);
		json_object_set_new(o, "ok", json_true());
		if (tag)
			json_object_set(o, "tag", tag);
		conn_send_json(c, o);
		return;
	}
	if (job_file_path(c->d->store->dir, id, file, path, sizeof path)) {
		protocol_error(c, tag, "invalid", "file", "not a file of a job: results.json, report.html, events.jsonl, "
			       "scene.json, or frames|diff|flip/NAME/NNNN.png");
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
