/* The HTTP routes (handlers): the dashboard page (web/), /healthz, /metrics (Prometheus text),
 * /v1/jobs... (JSON and stored files) and the farm routes (farm_routes.c). Framing is http_conn.c's. */
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <time.h>

#include "daemon.h"
#include "farm_routes.h"
#include "http_conn.h"
#include "stream.h"
#include "jobs.h"
#include "results/results.h"

/* Decodes %XX in place; -1 on a bad escape or an encoded NUL or '/'. */
static int percent_decode(char *s)
{
	char *out = s;
	for (; *s; s++) {
		if (*s != '%') {
			*out++ = *s;
			continue;
		}
		if (!isxdigit((unsigned char)s[1]) || !isxdigit((unsigned char)s[2]))
			return -1;
		char hex[3] = {s[1], s[2], 0};
		char c = (char)strtol(hex, NULL, 16);
		if (c == 0 || c == '/')
			return -1;
		*out++ = c;
		s += 2;
	}
	*out = 0;
	return 0;
}

static void metrics(struct daemon *d, struct http_response *r)
{
	struct store *s = d->store;
	struct scene_cache_stats cs;
	scene_cache_stats(s->scenes, &cs);
	if (s->use_process) { /* the scenes are the worker process's: as of its last job */
		pthread_mutex_lock(&s->lock);
		cs = s->process_scenes;
		pthread_mutex_unlock(&s->lock);
	}
	char *buf = NULL;
	size_t size = 0;
	FILE *f = open_memstream(&buf, &size);
	if (!f) {
		http_text(r, 503, "out of memory\n");
		return;
	}
	pthread_mutex_lock(&s->lock);
	fprintf(f, "# HELP aalab_jobs Jobs known to the daemon, by state.\n# TYPE aalab_jobs gauge\n");
	for (int st = JOB_QUEUED; st <= JOB_CANCELLED; st++)
		fprintf(f, "aalab_jobs{state=\"%s\"} %d\n", job_state_name(st), store_count_state(s, st));
	double busy = s->gpu_busy_seconds;
	if (s->running && s->running->started_at > 0) {
		struct timespec ts;
		clock_gettime(CLOCK_REALTIME, &ts);
		busy += ts.tv_sec + ts.tv_nsec / 1e9 - s->running->started_at;
	}
	fprintf(f, "# HELP aalab_frames_rendered_total Method frames rendered and scored.\n"
		"# TYPE aalab_frames_rendered_total counter\naalab_frames_rendered_total %llu\n"
		"# HELP aalab_jobs_finished_total Jobs that ended (done, failed or cancelled while running).\n"
		"# TYPE aalab_jobs_finished_total counter\naalab_jobs_finished_total %llu\n"
		"# HELP aalab_gpu_busy_seconds_total Seconds the GPU worker spent running jobs.\n"
		"# TYPE aalab_gpu_busy_seconds_total counter\naalab_gpu_busy_seconds_total %.3f\n",
		(unsigned long long)s->frames_rendered, (unsigned long long)s->jobs_finished, busy);
	fprintf(f, "# HELP aalab_gpu_scene_cache_hits_total Jobs whose scene was already on the GPU.\n"
		"# TYPE aalab_gpu_scene_cache_hits_total counter\naalab_gpu_scene_cache_hits_total %llu\n"
		"# HELP aalab_gpu_scene_cache_misses_total Jobs that uploaded their scene.\n"
		"# TYPE aalab_gpu_scene_cache_misses_total counter\naalab_gpu_scene_cache_misses_total %llu\n"
		"# HELP aalab_gpu_scene_cache_bytes GPU memory held by uploaded scenes.\n"
		"# TYPE aalab_gpu_scene_cache_bytes gauge\naalab_gpu_scene_cache_bytes %llu\n",
		(unsigned long long)s->gpu_scenes.hits, (unsigned long long)s->gpu_scenes.misses,
		(unsigned long long)s->gpu_scenes.bytes);
	const struct aa_reference_cache_stats rc = s->references;
	fprintf(f, "# HELP aalab_reference_cache_hits_total Reference frames (or auto levels) read from the store.\n"
		"# TYPE aalab_reference_cache_hits_total counter\naalab_reference_cache_hits_total %llu\n"
		"# HELP aalab_reference_cache_misses_total Reference lookups the store could not serve: rendered.\n"
		"# TYPE aalab_reference_cache_misses_total counter\naalab_reference_cache_misses_total %llu\n"
		"# HELP aalab_reference_cache_read_bytes_total Bytes of entries read from the store.\n"
		"# TYPE aalab_reference_cache_read_bytes_total counter\naalab_reference_cache_read_bytes_total %llu\n"
		"# HELP aalab_reference_cache_written_bytes_total Bytes of entries written to the store.\n"
		"# TYPE aalab_reference_cache_written_bytes_total counter\naalab_reference_cache_written_bytes_total %llu\n"
		"# HELP aalab_reference_cache_evictions_total Entries removed to keep the store under its size.\n"
		"# TYPE aalab_reference_cache_evictions_total counter\naalab_reference_cache_evictions_total %llu\n"
		"# HELP aalab_reference_cache_discarded_total Entries that failed their check, removed and rendered again.\n"
		"# TYPE aalab_reference_cache_discarded_total counter\naalab_reference_cache_discarded_total %llu\n",
		(unsigned long long)rc.hits, (unsigned long long)rc.misses, (unsigned long long)rc.bytes_read,
		(unsigned long long)rc.bytes_written, (unsigned long long)rc.evictions, (unsigned long long)rc.discarded);
	pthread_mutex_unlock(&s->lock);
	fprintf(f, "# HELP aalab_scene_cache_hits_total Scene lookups served from the cache.\n"
		"# TYPE aalab_scene_cache_hits_total counter\naalab_scene_cache_hits_total %llu\n"
		"# HELP aalab_scene_cache_misses_total Scene lookups that loaded the file.\n"
		"# TYPE aalab_scene_cache_misses_total counter\naalab_scene_cache_misses_total %llu\n"
		"# HELP aalab_scene_cache_reloads_total Scenes loaded again because their file changed.\n"
		"# TYPE aalab_scene_cache_reloads_total counter\naalab_scene_cache_reloads_total %llu\n"
		"# HELP aalab_scene_cache_evictions_total Scenes dropped to stay within the byte budget.\n"
		"# TYPE aalab_scene_cache_evictions_total counter\naalab_scene_cache_evictions_total %llu\n"
		"# HELP aalab_scene_cache_bytes Bytes of scenes held.\n# TYPE aalab_scene_cache_bytes gauge\n"
		"aalab_scene_cache_bytes %llu\n",
		(unsigned long long)cs.hits, (unsigned long long)cs.misses, (unsigned long long)cs.reloads,
		(unsigned long long)cs.evictions, (unsigned long long)cs.bytes);
	fprintf(f, "# HELP aalab_connections Open client connections.\n# TYPE aalab_connections gauge\n"
		"aalab_connections %d\n"
		"# HELP aalab_connections_total Connections accepted.\n# TYPE aalab_connections_total counter\n"
		"aalab_connections_total %llu\n"
		"# HELP aalab_requests_total Protocol requests received.\n# TYPE aalab_requests_total counter\n"
		"aalab_requests_total %llu\n"
		"# HELP aalab_request_errors_total Protocol requests answered with an error.\n"
		"# TYPE aalab_request_errors_total counter\naalab_request_errors_total %llu\n"
		"# HELP aalab_http_requests_total HTTP requests served.\n# TYPE aalab_http_requests_total counter\n"
		"aalab_http_requests_total %llu\n"
		"# HELP aalab_frames_dropped_total Frames left out of slow clients' watch streams.\n"
		"# TYPE aalab_frames_dropped_total counter\naalab_frames_dropped_total %llu\n"
		"# HELP aalab_uptime_seconds Seconds since the daemon started.\n# TYPE aalab_uptime_seconds gauge\n"
		"aalab_uptime_seconds %.1f\n",
		d->t.conn_count, (unsigned long long)d->t.stats.connections_total,
		(unsigned long long)d->t.stats.requests_total, (unsigned long long)d->t.stats.errors_total,
		(unsigned long long)d->t.stats.http_requests_total, (unsigned long long)d->t.stats.frames_dropped_total,
		(loop_now_ms() - d->started_ms) / 1000.0);
	fclose(f);
	r->status = 200;
	r->type = "text/plain; version=0.0.4; charset=utf-8";
	r->body = buf;
	r->size = size;
}

static void job_route(struct daemon *d, char *rest, struct http_response *r)
{
	char *id = rest, *sub = strchr(rest, '/');
	if (sub)
		*sub++ = 0;
	if (strlen(id) >= 16) {
		http_text(r, 404, "no such job\n");
		return;
	}
	pthread_mutex_lock(&d->store->lock);
	struct job *job = store_find(d->store, id);
	json_t *o = job && !sub ? job_to_json(job) : NULL;
	pthread_mutex_unlock(&d->store->lock);
	if (!job) {
		http_text(r, 404, "no such job\n");
		return;
	}
	if (!sub) {
		http_json(r, o);
		return;
	}
	/* frames|diff|flip/{method}/{n}.png: the method as its label ("ssaa:16") or directory name ("ssaa_16") */
	char rel[600], path[1400];
	snprintf(rel, sizeof rel, "%s", sub);
	if (!strncmp(sub, "frames/", 7) || !strncmp(sub, "diff/", 5) || !strncmp(sub, "flip/", 5)) {
		char *name = strchr(sub, '/') + 1, *slash = strchr(name, '/');
		if (!slash || percent_decode(name)) {
			http_text(r, 404, "not found\n");
			return;
		}
		slash = strchr(name, '/');
		*slash = 0;
		char dir[300];
		aa_label_dirname(name, dir, sizeof dir);
		long n = strtol(slash + 1, NULL, 10);
		if (strspn(slash + 1, "0123456789") == 0 || strcmp(slash + 1 + strspn(slash + 1, "0123456789"), ".png") ||
		    n > 99999999) {
			http_text(r, 404, "not found\n");
			return;
		}
		*strchr(sub, '/') = 0; /* sub is now "frames", "diff" or "flip" */
		snprintf(rel, sizeof rel, "%s/%s/%04ld.png", sub, dir, n);
	}
	if (job_file_path(d->store->dir, id, rel, path, sizeof path)) {
		http_text(r, 404, "not found\n");
		return;
	}
	http_file(r, path, file_content_type(rel));
}

void http_route(struct conn *c, char *target, struct http_response *r)
{
	struct daemon *d = conn_daemon(c);
	char *q = strchr(target, '?');
	if (q)
		*q++ = 0; /* the dashboard adds ?t= to defeat caches; the farm routes read the rest */
	struct farm_reply farm;
	if (farm_http(d, target, q, &farm)) {
		if (farm.json)
			http_json(r, farm.json);
		else
			http_text(r, farm.status, farm.text);
		return;
	}
	if (!strcmp(target, "/healthz")) {
		http_text(r, d->draining ? 503 : 200, d->draining ? "draining\n" : "ok\n");
	} else if (!strcmp(target, "/metrics")) {
		metrics(d, r);
	} else if (!strncmp(target, "/v1/jobs/", 9)) {
		job_route(d, target + 9, r);
	} else if (!strcmp(target, "/") || !strncmp(target, "/web/", 5)) {
		const char *name = target[1] ? target + 5 : "index.html";
		char path[1400];
		if (!*name || name[0] == '.' || strchr(name, '/') || strlen(name) > 64 || !d->cfg.web_dir[0]) {
			http_text(r, 404, "not found\n");
			return;
		}
		snprintf(path, sizeof path, "%s/%.64s", d->cfg.web_dir, name);
		http_file(r, path, file_content_type(name));
	} else {
		http_text(r, 404, "not found\n");
	}
}

