/* The HTTP/1.1 subset for dashboards: GET and HEAD, keep-alive, no request bodies. Routes: the dashboard
 * page (web/), /healthz, /metrics (Prometheus text), and /v1/jobs... (JSON and stored files). */
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <time.h>

#include "daemon.h"
#include "farm_routes.h"
#include "http_parse.h"
#include "jobs.h"
#include "results/results.h"

struct response {
	int status;
	const char *type;
	char *body;          /* malloc'ed */
	size_t size;
	const char *extra;   /* more header lines, each ending in \r\n */
};

static const char *reason(int status)
{
	switch (status) {
	case 200: return "OK";
	case 400: return "Bad Request";
	case 401: return "Unauthorized";
	case 404: return "Not Found";
	case 405: return "Method Not Allowed";
	case 409: return "Conflict";
	case 500: return "Internal Server Error";
	case 414: return "URI Too Long";
	case 505: return "HTTP Version Not Supported";
	case 431: return "Request Header Fields Too Large";
	case 503: return "Service Unavailable";
	default: return "Error";
	}
}

static void text(struct response *r, int status, const char *msg)
{
	r->status = status;
	r->type = "text/plain; charset=utf-8";
	r->body = strdup(msg);
	r->size = r->body ? strlen(r->body) : 0;
}

static void json_body(struct response *r, json_t *o)
{
	r->status = 200;
	r->type = "application/json";
	r->body = json_dumps(o, JSON_COMPACT);
	r->size = r->body ? strlen(r->body) : 0;
	json_decref(o);
}

static void file_body(struct response *r, const char *path, const char *type)
{
	if (read_whole_file(path, 1u << 30, &r->body, &r->size)) {
		text(r, 404, "not found\n");
		return;
	}
	r->status = 200;
	r->type = type;
}

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

static void metrics(struct daemon *d, struct response *r)
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
		text(r, 503, "out of memory\n");
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
		d->conn_count, (unsigned long long)d->stats.connections_total,
		(unsigned long long)d->stats.requests_total, (unsigned long long)d->stats.errors_total,
		(unsigned long long)d->stats.http_requests_total, (unsigned long long)d->stats.frames_dropped_total,
		(loop_now_ms() - d->started_ms) / 1000.0);
	fclose(f);
	r->status = 200;
	r->type = "text/plain; version=0.0.4; charset=utf-8";
	r->body = buf;
	r->size = size;
}

static void job_route(struct daemon *d, char *rest, struct response *r)
{
	char *id = rest, *sub = strchr(rest, '/');
	if (sub)
		*sub++ = 0;
	if (strlen(id) >= 16) {
		text(r, 404, "no such job\n");
		return;
	}
	pthread_mutex_lock(&d->store->lock);
	struct job *job = store_find(d->store, id);
	json_t *o = job && !sub ? job_to_json(job) : NULL;
	pthread_mutex_unlock(&d->store->lock);
	if (!job) {
		text(r, 404, "no such job\n");
		return;
	}
	if (!sub) {
		json_body(r, o);
		return;
	}
	/* frames|diff|flip/{method}/{n}.png: the method as its label ("ssaa:16") or directory name ("ssaa_16") */
	char rel[600], path[1400];
	snprintf(rel, sizeof rel, "%s", sub);
	if (!strncmp(sub, "frames/", 7) || !strncmp(sub, "diff/", 5) || !strncmp(sub, "flip/", 5)) {
		char *name = strchr(sub, '/') + 1, *slash = strchr(name, '/');
		if (!slash || percent_decode(name)) {
			text(r, 404, "not found\n");
			return;
		}
		slash = strchr(name, '/');
		*slash = 0;
		char dir[300];
		aa_label_dirname(name, dir, sizeof dir);
		long n = strtol(slash + 1, NULL, 10);
		if (strspn(slash + 1, "0123456789") == 0 || strcmp(slash + 1 + strspn(slash + 1, "0123456789"), ".png") ||
		    n > 99999999) {
			text(r, 404, "not found\n");
			return;
		}
		*strchr(sub, '/') = 0; /* sub is now "frames", "diff" or "flip" */
		snprintf(rel, sizeof rel, "%s/%s/%04ld.png", sub, dir, n);
	}
	if (job_file_path(d->store->dir, id, rel, path, sizeof path)) {
		text(r, 404, "not found\n");
		return;
	}
	file_body(r, path, file_content_type(rel));
}

static void route(struct daemon *d, char *target, struct response *r)
{
	char *q = strchr(target, '?');
	if (q)
		*q++ = 0; /* the dashboard adds ?t= to defeat caches; the farm routes read the rest */
	struct farm_reply farm;
	if (farm_http(d, target, q, &farm)) {
		if (farm.json)
			json_body(r, farm.json);
		else
			text(r, farm.status, farm.text);
		return;
	}
	if (!strcmp(target, "/healthz")) {
		text(r, d->draining ? 503 : 200, d->draining ? "draining\n" : "ok\n");
	} else if (!strcmp(target, "/metrics")) {
		metrics(d, r);
	} else if (!strncmp(target, "/v1/jobs/", 9)) {
		job_route(d, target + 9, r);
	} else if (!strcmp(target, "/") || !strncmp(target, "/web/", 5)) {
		const char *name = target[1] ? target + 5 : "index.html";
		char path[1400];
		if (!*name || name[0] == '.' || strchr(name, '/') || strlen(name) > 64 || !d->cfg.web_dir[0]) {
			text(r, 404, "not found\n");
			return;
		}
		snprintf(path, sizeof path, "%s/%.64s", d->cfg.web_dir, name);
		file_body(r, path, file_content_type(name));
	} else {
		text(r, 404, "not found\n");
	}
}

static void respond(struct conn *c, struct response *r, bool head, bool keep_alive)
{
	char hdr[1024];
	int n = snprintf(hdr, sizeof hdr, "HTTP/1.1 %d %s\r\nServer: aalabd/" PACKAGE_VERSION "\r\n"
			 "Content-Type: %s\r\nContent-Length: %zu\r\nCache-Control: no-store\r\n%sConnection: %s\r\n\r\n",
			 r->status, reason(r->status), r->type ? r->type : "text/plain", r->size,
			 r->extra ? r->extra : "", keep_alive ? "keep-alive" : "close");
	conn_send(c, hdr, (size_t)n);
	if (!head && r->body)
		conn_send(c, r->body, r->size);
	free(r->body);
	if (!keep_alive)
		conn_close_after_flush(c);
}

static void refuse_request(struct conn *c, int status, const char *why)
{
	struct response r = {0};
	char msg[300];
	snprintf(msg, sizeof msg, "%s\n", why);
	text(&r, status, msg);
	respond(c, &r, false, false);
}

/* Handles every complete request in the input buffer; a malformed one is answered and ends the
 * connection as soon as its bad line is in (http_parse.c). */
void http_input(struct conn *c)
{
	struct daemon *d = c->d;
	int handled = 0;
	c->backlog = false;
	while (!c->closed && !c->close_after_flush && c->in_len > 0) {
		if (conn_turn_over(c, handled++, c->turn_ms)) { /* the rest in a later turn (conns_pump_input) */
			c->backlog = true;
			return;
		}
		struct http_request req;
		const char *why;
		long taken = http_parse_request(c->in, c->in_len, &req, &why);
		if (taken == 0)
			return;
		d->stats.http_requests_total++;
		if (taken < 0) {
			c->in_len = 0;
			refuse_request(c, (int)-taken, why);
			return;
		}
		memmove(c->in, c->in + taken, c->in_len - (size_t)taken);
		c->in_len -= (size_t)taken;
		bool head = !strcmp(req.method, "HEAD");
		bool authorized = !d->token[0] || !c->via_tcp || (req.bearer[0] && token_equal(req.bearer, d->token));
		struct response r = {0};
		if (req.has_body) {
			refuse_request(c, 400, "bad request: GET or HEAD with no body");
			return;
		} else if (strcmp(req.method, "GET") && !head) {
			text(&r, 405, "only GET and HEAD\n");
			r.extra = "Allow: GET, HEAD\r\n";
		} else if (!authorized && strcmp(req.target, "/healthz")) {
			text(&r, 401, "send Authorization: Bearer TOKEN\n");
			r.extra = "WWW-Authenticate: Bearer\r\n";
		} else {
			route(d, req.target, &r);
		}
		respond(c, &r, head, req.keep_alive);
	}
}
