/* The aalabd protocol (docs/protocol.md): one JSON object per line, answered by one line with "ok";
 * submit may carry a scene as a binary payload, watch streams a job's events, get sends stored files.
 * Every error is {code, message, path}, path naming the field at fault. */
#include <ctype.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "daemon.h"
#include "run/farm.h"
#include "farm_routes.h"
#include "jobs.h"
#include "stream.h"
#include "methods/user_method.h"
#include "methods/methods.h"
#include "run/job_spec.h"


static void reply(struct conn *c, json_t *tag, json_t *body)
{
	json_object_set_new(body, "ok", json_true());
	if (tag)
		json_object_set(body, "tag", tag);
	conn_send_json(c, body);
}

/* Refuses keys a request does not know: a typo must not be silently ignored. */
static int check_keys(struct conn *c, json_t *msg, json_t *tag, const char *const *allowed)
{
	const char *key;
	json_t *v;
	json_object_foreach(msg, key, v) {
		int i = 0;
		if (!strcmp(key, "op") || !strcmp(key, "tag") || !strcmp(key, "payload") || !strcmp(key, "payload_format"))
			continue;
		while (allowed[i] && strcmp(allowed[i], key))
			i++;
		if (!allowed[i]) {
			char shown[65];
			snprintf(shown, sizeof shown, "%s", key);
			for (char *p = shown; *p; p++)
				if (iscntrl((unsigned char)*p))
					*p = '?';
			protocol_error(c, tag, "bad_request", shown, "unknown key for op '%s'",
				       json_string_value(json_object_get(msg, "op")));
			return -1;
		}
	}
	return 0;
}

static const char *get_job_id(struct conn *c, json_t *msg, json_t *tag)
{
	json_t *j = json_object_get(msg, "job");
	if (!j) {
		protocol_error(c, tag, "bad_request", "job", "missing: the job id");
		return NULL;
	}
	const char *id = json_string_value(j);
	if (!id || strlen(id) >= 16) {
		protocol_error(c, tag, "bad_request", "job", "a job id is a string like \"000042\"");
		return NULL;
	}
	return id;
}

/* Looks a job up and returns it with the store locked, or answers not_found. */
static struct job *lock_job(struct conn *c, json_t *msg, json_t *tag)
{
	const char *id = get_job_id(c, msg, tag);
	if (!id)
		return NULL;
	pthread_mutex_lock(&conn_daemon(c)->store->lock);
	struct job *job = store_find(conn_daemon(c)->store, id);
	if (!job) {
		pthread_mutex_unlock(&conn_daemon(c)->store->lock);
		protocol_error(c, tag, "not_found", "job", "no job '%s' (finished jobs are kept up to retention-jobs)", id);
	}
	return job;
}

static json_t *limits_json(const struct config *cfg)
{
	/* the budget is a count (pixels x frames x samples): an integer, as the other limits */
	return json_pack("{sI sI si si si sI si}", "max_request_bytes", (json_int_t)cfg->max_request_bytes,
			 "max_job_budget", (json_int_t)cfg->max_job_budget, "max_jobs_per_client", cfg->max_jobs_per_client,
			 "idle_timeout", cfg->idle_timeout_s, "slow_client_timeout", cfg->slow_client_timeout_s,
			 "client_buffer_bytes", (json_int_t)cfg->client_buffer_bytes, "max_frames", AA_MAX_FRAMES);
}


static void op_hello(struct conn *c, json_t *msg, json_t *tag)
{
	static const char *const keys[] = {"version", "token", "client", NULL};
	if (check_keys(c, msg, tag, keys))
		return;
	json_t *v = json_object_get(msg, "version");
	if (v && !json_is_integer(v)) {
		protocol_error(c, tag, "bad_request", "version", "expected an integer: the highest protocol version the "
			       "client speaks (this server speaks %d)", AALABD_PROTOCOL_VERSION);
		return;
	}
	if (v && json_integer_value(v) < 1) {
		protocol_error(c, tag, "unsupported_version", "version", "this server speaks protocol version %d; "
			       "send the highest version the client speaks", AALABD_PROTOCOL_VERSION);
		return;
	}
	if (c->via_tcp && c->t->token[0]) {
		const char *given = json_string_value(json_object_get(msg, "token"));
		if (!token_equal(given, c->t->token)) {
			protocol_error(c, tag, "unauthorized", "token", "%s: TCP clients send the bearer token of the "
				       "daemon's token file in hello (aalab: AALAB_TOKEN, AALAB_TOKEN_FILE or --token-file)",
				       given && *given ? "wrong token" : "no token");
			conn_close_after_flush(c);
			return;
		}
		c->authed = true;
	}
	reply(c, tag, json_pack("{si s[i] ss so s[sss] ss}", "protocol", AALABD_PROTOCOL_VERSION, "versions",
				AALABD_PROTOCOL_VERSION, "server", "aalabd " PACKAGE_VERSION, "limits",
				limits_json(&conn_daemon(c)->cfg), "frame_formats", "png", "rgba8", "rgba16f", "peer", c->peer));
}

static double method_samples(const struct aa_method_spec *m)
{
	int i = aa_method_param_index(m->method, "samples");
	return i >= 0 && m->params.v[i] > 1 ? m->params.v[i] : 1;
}

/* A "bundle" payload: {"scene": "the scene file's text", "files": {"name": "text", ...}}, the scene (if
 * any) and the method and shader files of the job's user methods (docs/protocol.md). */
static json_t *parse_bundle(struct conn *c, json_t *tag, const char *payload, size_t size)
{
	json_error_t jerr;
	json_t *b = json_loadb(payload, size, JSON_REJECT_DUPLICATES, &jerr);
	if (!json_is_object(b)) {
		protocol_error(c, tag, "invalid", "payload", "a bundle is a JSON object {\"scene\": TEXT, \"files\": "
			       "{NAME: TEXT}}%s%s", b ? "" : ": ", b ? "" : jerr.text);
		json_decref(b);
		return NULL;
	}
	const char *key;
	json_t *v;
	json_object_foreach(b, key, v) {
		if (strcmp(key, "scene") && strcmp(key, "files")) {
			protocol_error(c, tag, "invalid", "payload", "unknown key in the bundle; valid keys: scene, files");
			json_decref(b);
			return NULL;
		}
	}
	json_t *scene = json_object_get(b, "scene"), *files = json_object_get(b, "files");
	if ((scene && !json_is_string(scene)) || (files && !json_is_object(files))) {
		protocol_error(c, tag, "invalid", scene && !json_is_string(scene) ? "payload.scene" : "payload.files",
			       "expected the scene file's text (a string) and an object of file texts by name");
		json_decref(b);
		return NULL;
	}
	json_object_foreach(files, key, v) {
		if (!json_is_string(v)) {
			protocol_error(c, tag, "invalid", "payload.files", "each file is its text, a string");
			json_decref(b);
			return NULL;
		}
	}
	return b;
}

/* Everything after the job parsed: the scene, the budget, the limits and the store. */
static void submit_parsed(struct conn *c, json_t *tag, struct aa_job_spec *spec, const char *scene_text,
			  size_t scene_size, const json_t *files)
{
	struct daemon *d = conn_daemon(c);
	struct aa_error err = {0};
	char file[1024];
	if (scene_text && spec->is_suite) {
		protocol_error(c, tag, "invalid", "payload", "a suite names its scenes; send a scene payload with a job of "
			       "one case");
		return;
	}
	if (scene_text) {
		/* checked now so that a bad scene is refused with its field, not failed later in the queue */
		struct aa_scene *scene = NULL;
		char *text = strndup(scene_text, scene_size);
		int rc = !text || memchr(scene_text, 0, scene_size) ||
			 aa_scene_load_string(text, "scene", NULL, &scene, &err);
		free(text);
		aa_scene_free(scene);
		if (rc) {
			char path[300];
			snprintf(path, sizeof path, "payload%s%s", err.path[0] ? "." : "", err.path);
			protocol_error(c, tag, err.code ? aa_error_code_name(err.code) : "invalid", path, "%s",
				       err.message[0] ? err.message : "the scene is not text");
			return;
		}
		snprintf(spec->scene, sizeof spec->scene, "inline");
	}
	/* every case's scene is a name the daemon knows; a suite's fields are cases[i].scene */
	double budget = 0;
	for (int i = 0; i < aa_job_case_count(spec); i++) {
		struct aa_job_spec one;
		aa_job_case(spec, i, &one);
		char where[64];
		snprintf(where, sizeof where, spec->is_suite ? "job.cases[%d].scene" : "job.scene", i);
		if (!scene_text && (strchr(one.scene, '/') || strstr(one.scene, ".."))) {
			protocol_error(c, tag, "invalid", where, "the daemon takes scene names only (see the scenes op); "
				       "send your own scene file as the payload of submit");
			return;
		}
		if (!scene_text && aa_scene_resolve(one.scene, file, sizeof file, &err)) {
			protocol_error(c, tag, aa_error_code_name(err.code), where, "%s", err.message);
			return;
		}
		double samples = one.reference_samples;
		for (int m = 0; m < one.method_count; m++)
			samples += (double)one.timing_repeat * method_samples(&one.methods[m]); /* repeats render again */
		budget += (double)one.width * one.height * one.frames * samples;
	}
	if (budget > d->cfg.max_job_budget) {
		protocol_error(c, tag, "limit", "job", "job budget %.3g (width x height x frames x (reference samples "
			       "+ timing.repeat x method samples), summed over cases) is over max-job-budget %.3g", budget,
			       d->cfg.max_job_budget);
		return;
	}
	struct aa_baseline baseline;
	if (spec->baseline[0] && aa_baseline_parse(spec->baseline, &baseline, "baseline", &err) == 0 && !baseline.latest) {
		pthread_mutex_lock(&d->store->lock);
		bool known = store_find(d->store, baseline.job) != NULL;
		pthread_mutex_unlock(&d->store->lock);
		if (!known) {
			protocol_error(c, tag, "not_found", "job.baseline", "no job '%s' to compare with", baseline.job);
			return;
		}
	}
	if (d->draining) {
		protocol_error(c, tag, "shutting_down", "", "the daemon is shutting down; submit again after restart");
		return;
	}
	pthread_mutex_lock(&d->store->lock);
	int mine = store_count_active(d->store, c->peer), queued = store_count_active(d->store, NULL);
	pthread_mutex_unlock(&d->store->lock);
	if (mine >= d->cfg.max_jobs_per_client) {
		protocol_error(c, tag, "limit", "", "%s already has %d jobs queued or running (max-jobs-per-client)",
			       c->peer, mine);
		return;
	}
	if (queued >= d->cfg.max_queued_jobs) {
		protocol_error(c, tag, "limit", "", "%d jobs are queued (max-queued-jobs); try again later", queued);
		return;
	}
	struct job *j = store_submit(d->store, spec, c->peer, scene_text, scene_size, files, &err);
	if (!j) {
		protocol_error(c, tag, aa_error_code_name(err.code), err.path, "%s", err.message);
		return;
	}
	reply(c, tag, json_pack("{ss ss si}", "job", j->id, "state", "queued", "ahead", queued));
}

static void op_submit(struct conn *c, json_t *msg, json_t *tag, const char *payload, size_t size)
{
	static const char *const keys[] = {"job", NULL};
	struct daemon *d = conn_daemon(c);
	if (check_keys(c, msg, tag, keys))
		return;
	json_t *job = json_object_get(msg, "job");
	if (!json_is_object(job)) {
		protocol_error(c, tag, "bad_request", "job", "expected the job object of docs/job-format.md");
		return;
	}
	const char *fmt = json_string_value(json_object_get(msg, "payload_format"));
	if (payload && (!fmt || (strcmp(fmt, "scene") != 0 && strcmp(fmt, "bundle") != 0))) {
		protocol_error(c, tag, "bad_request", "payload_format", "a submit payload is a scene file "
			       "(payload_format \"scene\") or a bundle of a scene and method files (\"bundle\")");
		return;
	}
	/* user methods run a client's shaders: only where the configuration allows, and then in the worker
	 * process (aalabd(8), allow-user-methods) */
	json_t *item;
	size_t i;
	json_array_foreach(json_object_get(job, "methods"), i, item) {
		if (aa_job_method_is_user(item) && !d->cfg.allow_user_methods) {
			char path[40];
			snprintf(path, sizeof path, "job.methods[%zu]", i);
			protocol_error(c, tag, "forbidden", path, "user methods are off on this daemon (allow-user-methods in "
				       "aalabd(8)); run the job with aalab run --local");
			return;
		}
	}
	json_t *bundle = payload && !strcmp(fmt, "bundle") ? parse_bundle(c, tag, payload, size) : NULL;
	if (payload && !strcmp(fmt, "bundle") && !bundle)
		return;
	const json_t *files = json_object_get(bundle, "files"), *scene = json_object_get(bundle, "scene");
	const char *scene_text = bundle ? json_string_value(scene) : payload;
	size_t scene_size = bundle ? json_string_length(scene) : size;
	/* the files of user methods are read from the bundle only, never from this machine's disk */
	json_t *none = json_object();
	struct aa_file_source src;
	aa_file_source_json(files ? files : none, &src);
	struct aa_job_spec spec;
	struct aa_error err = {0};
	if (aa_job_spec_from_json_files(job, &src, &spec, &err)) {
		char path[300];
		snprintf(path, sizeof path, "job%s%s", err.path[0] ? "." : "", err.path);
		protocol_error(c, tag, aa_error_code_name(err.code), path, "%s", err.message);
	} else {
		bool user = false;
		for (int m = 0; m < spec.method_count; m++)
			user |= aa_method_is_user(spec.methods[m].method);
		submit_parsed(c, tag, &spec, scene_text, scene_size, user ? files : NULL);
		aa_job_spec_release(&spec);
	}
	json_decref(none);
	json_decref(bundle);
}

static void op_status(struct conn *c, json_t *msg, json_t *tag)
{
	static const char *const keys[] = {"job", NULL};
	if (check_keys(c, msg, tag, keys))
		return;
	struct job *job = lock_job(c, msg, tag);
	if (!job)
		return;
	json_t *o = job_to_json(job);
	pthread_mutex_unlock(&conn_daemon(c)->store->lock);
	reply(c, tag, json_pack("{so}", "job", o));
}

static void op_list(struct conn *c, json_t *msg, json_t *tag)
{
	static const char *const keys[] = {"state", "limit", "labels", "suite", NULL};
	if (check_keys(c, msg, tag, keys))
		return;
	json_t *st = json_object_get(msg, "state"), *lim = json_object_get(msg, "limit");
	if (st && (!json_is_string(st) || !job_state_known(json_string_value(st)))) {
		protocol_error(c, tag, "bad_request", "state", "expected queued, running, done, failed or cancelled");
		return;
	}
	if (lim && (!json_is_integer(lim) || json_integer_value(lim) < 1)) {
		protocol_error(c, tag, "bad_request", "limit", "expected a positive integer");
		return;
	}
	json_int_t limit = lim ? json_integer_value(lim) : 1000;
	char path[64] = "", message[512] = "";
	struct farm_filter *filter = farm_filter_from_request(json_object_get(msg, "labels"), json_object_get(msg, "suite"),
							      path, sizeof path, message, sizeof message);
	if (!filter) {
		protocol_error(c, tag, "bad_request", path, "%s", message);
		return;
	}
	json_t *arr = json_array();
	pthread_mutex_lock(&conn_daemon(c)->store->lock);
	int total = 0;
	for (struct job *j = conn_daemon(c)->store->jobs; j; j = j->next)
		total += (!st || !strcmp(job_state_name(j->state), json_string_value(st))) && farm_filter_matches(filter, j);
	int skip = total > limit ? total - (int)limit : 0; /* the newest `limit` jobs */
	for (struct job *j = conn_daemon(c)->store->jobs; j; j = j->next) {
		if ((st && strcmp(job_state_name(j->state), json_string_value(st))) || !farm_filter_matches(filter, j))
			continue;
		if (skip > 0) {
			skip--;
			continue;
		}
		json_array_append_new(arr, job_to_json(j));
	}
	pthread_mutex_unlock(&conn_daemon(c)->store->lock);
	farm_filter_free(filter);
	reply(c, tag, json_pack("{so}", "jobs", arr));
}

static void op_cancel(struct conn *c, json_t *msg, json_t *tag)
{
	static const char *const keys[] = {"job", NULL};
	if (check_keys(c, msg, tag, keys))
		return;
	struct job *job = lock_job(c, msg, tag);
	if (!job)
		return;
	struct aa_error err = {0};
	int rc = store_cancel(conn_daemon(c)->store, job, &err);
	json_t *o = rc ? NULL : json_pack("{ss ss}", "job", job->id, "state", job_state_name(job->state));
	pthread_mutex_unlock(&conn_daemon(c)->store->lock);
	if (rc) {
		protocol_error(c, tag, "invalid", "job", "%s", err.message);
		return;
	}
	conns_pump_watches(c->t);
	reply(c, tag, o);
}

static void op_scenes(struct conn *c, json_t *msg, json_t *tag)
{
	static const char *const keys[] = {NULL};
	if (check_keys(c, msg, tag, keys))
		return;
	char **names;
	int count;
	if (aa_scene_list(&names, &count)) {
		protocol_error(c, tag, "internal", "", "cannot list the scene directories");
		return;
	}
	json_t *arr = json_array();
	for (int i = 0; i < count; i++) {
		/* only what a submit accepts: a symbolic link leading out of its folder is refused there */
		char file[1400];
		struct aa_error ignored = {0};
		if (aa_scene_resolve(names[i], file, sizeof file, &ignored) == 0)
			json_array_append_new(arr, json_string(names[i]));
		free(names[i]);
	}
	free(names);
	reply(c, tag, json_pack("{so}", "scenes", arr));
}

static void op_methods(struct conn *c, json_t *msg, json_t *tag)
{
	static const char *const keys[] = {NULL};
	if (check_keys(c, msg, tag, keys))
		return;
	json_t *arr = aa_methods_describe();
	reply(c, tag, json_pack("{so}", "methods", arr));
}

static void op_watch(struct conn *c, json_t *msg, json_t *tag)
{
	static const char *const keys[] = {"job", "after", "frames", NULL};
	if (check_keys(c, msg, tag, keys))
		return;
	json_t *after = json_object_get(msg, "after"), *frames = json_object_get(msg, "frames");
	if (after && (!json_is_integer(after) || json_integer_value(after) < 0)) {
		protocol_error(c, tag, "bad_request", "after", "expected the sequence number of the last event seen (0: all)");
		return;
	}
	int fmt = FRAMES_NONE;
	const char *f = frames ? json_string_value(frames) : "none";
	if (f && !strcmp(f, "png"))
		fmt = FRAMES_PNG;
	else if (f && !strcmp(f, "rgba8"))
		fmt = FRAMES_RGBA8;
	else if (f && !strcmp(f, "rgba16f"))
		fmt = FRAMES_RGBA16F;
	else if (!f || strcmp(f, "none")) {
		protocol_error(c, tag, "bad_request", "frames", "expected none, png, rgba8 or rgba16f");
		return;
	}
	if (c->watch) {
		protocol_error(c, tag, "busy", "", "this connection is already watching job %s; open another",
			       c->watch->job->id);
		return;
	}
	struct watch *w = calloc(1, sizeof *w);
	if (!w) {
		protocol_error(c, tag, "internal", "", "out of memory");
		return;
	}
	struct job *job = lock_job(c, msg, tag);
	if (!job) {
		free(w);
		return;
	}
	store_load_events(conn_daemon(c)->store, job);
	job_hold(job);
	w->job = job;
	w->next_seq = after ? (unsigned long)json_integer_value(after) + 1 : 1;
	w->frames = fmt;
	w->tag = json_incref(tag);
	c->watch = w;
	json_t *o = json_pack("{ss ss sI sI}", "job", job->id, "state", job_state_name(job->state), "events",
			      (json_int_t)job->event_count, "run", (json_int_t)job->run);
	pthread_mutex_unlock(&conn_daemon(c)->store->lock);
	reply(c, tag, o);
	stream_pump_watch(c);
}

static void op_ping(struct conn *c, json_t *msg, json_t *tag)
{
	static const char *const keys[] = {NULL};
	if (check_keys(c, msg, tag, keys))
		return;
	reply(c, tag, json_pack("{sb}", "pong", 1));
}

struct op_entry {
	const char *name;
	void (*exec)(struct conn *c, json_t *msg, json_t *tag);
};

static const struct op_entry ops[] = {
	{"hello", op_hello}, {"ping", op_ping}, {"status", op_status}, {"list", op_list}, {"cancel", op_cancel},
	{"scenes", op_scenes}, {"methods", op_methods}, {"watch", op_watch}, {"get", op_get},
};

static void protocol_request(struct conn *c, json_t *msg, const char *op, const char *payload, size_t payload_size)
{
	/* the envelope (object, tag, op, payload only with submit) was checked by protocol_parse_line */
	json_t *tag = json_object_get(msg, "tag");
	if (!c->authed && strcmp(op, "hello") != 0)
		protocol_error(c, tag, "unauthorized", "token", "on TCP, send hello with the token first");
	else if (strcmp(op, "submit") == 0)
		op_submit(c, msg, tag, payload, payload_size);
	else {
		size_t i = 0, n = sizeof ops / sizeof ops[0];
		while (i < n && strcmp(ops[i].name, op) != 0)
			i++;
		if (i < n)
			ops[i].exec(c, msg, tag);
		else
			protocol_error(c, tag, "unknown_op", "op", "unknown op; ops: hello, ping, submit, watch, status, "
				       "list, cancel, get, scenes, methods");
	}
	json_decref(msg);
}

const struct conn_handlers daemon_handlers = {
	.on_request = protocol_request,
	.on_http_request = http_route,
	.on_writable = stream_pump_watch,
	.on_close = stream_end_watch,
};
