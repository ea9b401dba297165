/* Build farms in aalabd (docs/protocol.md, "Build farms"), the handlers' side: filters of job lists by
 * label and suite, and the HTTP routes /v1/jobs?label=..., /v1/jobs/ID/compare?baseline=... (the JSON of
 * `aalab compare --json`, by the same engine code) and /v1/series (trends). Baselines are farm_jobs.c's. */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "daemon.h"
#include "run/farm.h"
#include "farm_routes.h"
#include "jobs.h"
#include "compare/compare.h"
#include "run/job_spec.h"

struct farm_filter {
	int label_count;
	struct aa_label labels[AA_MAX_LABELS];
	char suite[80];
	bool has_suite;
	char state[16];
};

bool farm_filter_matches(const struct farm_filter *f, const struct job *job)
{
	if (f->state[0] && strcmp(f->state, job_state_name(job->state)))
		return false;
	return farm_job_matches(job, f->labels, f->label_count, f->has_suite ? f->suite : NULL);
}

void farm_filter_free(struct farm_filter *f)
{
	free(f);
}

struct farm_filter *farm_filter_from_request(json_t *labels, json_t *suite, char *path, size_t path_size,
					     char *message, size_t message_size)
{
	struct farm_filter *f = calloc(1, sizeof *f);
	struct aa_error err = {0};
	if (!f) {
		snprintf(message, message_size, "out of memory");
		return NULL;
	}
	if (labels && !json_is_object(labels)) {
		snprintf(path, path_size, "labels");
		snprintf(message, message_size, "expected an object of labels, e.g. {\"branch\": \"main\"}");
		free(f);
		return NULL;
	}
	const char *key;
	json_t *v;
	json_object_foreach(labels, key, v) {
		char where[64];
		snprintf(where, sizeof where, "labels.%.40s", key);
		if (!json_is_string(v) ||
		    aa_label_set(f->labels, &f->label_count, key, json_string_value(v), where, &err)) {
			snprintf(path, path_size, "%s", where);
			snprintf(message, message_size, "%s", err.message[0] ? err.message : "expected a string");
			free(f);
			return NULL;
		}
	}
	if (suite) {
		if (!json_is_string(suite) || json_string_length(suite) >= sizeof f->suite) {
			snprintf(path, path_size, "suite");
			snprintf(message, message_size, "expected a suite name (or a job hash)");
			free(f);
			return NULL;
		}
		snprintf(f->suite, sizeof f->suite, "%s", json_string_value(suite));
		f->has_suite = true;
	}
	return f;
}

/* ------------------------------------------------------------------------------------------- HTTP */

/* key=value pairs of a query string, percent-decoded ('+' is a space). */
struct query {
	int count;
	char key[16][32];
	char value[16][256];
};

static int hex_value(char c)
{
	return isdigit((unsigned char)c) ? c - '0' : isxdigit((unsigned char)c) ? tolower((unsigned char)c) - 'a' + 10 : -1;
}

static int decode(const char *s, size_t n, char *out, size_t size)
{
	size_t k = 0;
	for (size_t i = 0; i < n; i++) {
		char c = s[i];
		if (c == '+') {
			c = ' ';
		} else if (c == '%') {
			if (i + 2 >= n)
				return -1;
			int hi = hex_value(s[i + 1]), lo = hex_value(s[i + 2]);
			if (hi < 0 || lo < 0 || (hi == 0 && lo == 0))
				return -1;
			c = (char)(hi * 16 + lo);
			i += 2;
		}
		if (k + 1 >= size || iscntrl((unsigned char)c))
			return -1;
		out[k++] = c;
	}
	out[k] = '\0';
	return 0;
}

static int parse_query(const char *q, struct query *out, char *message, size_t size)
{
	out->count = 0;
	while (q && *q) {
		size_t len = strcspn(q, "&");
		const char *eq = memchr(q, '=', len);
		if (len > 0) {
			if (out->count >= 16) {
				snprintf(message, size, "more than 16 query parameters");
				return -1;
			}
			size_t klen = eq ? (size_t)(eq - q) : len;
			if (decode(q, klen, out->key[out->count], sizeof out->key[0]) ||
			    decode(eq ? eq + 1 : q + len, eq ? len - klen - 1 : 0, out->value[out->count],
				   sizeof out->value[0])) {
				snprintf(message, size, "query parameter %.*s is not valid (bad escape, control character or "
					 "too long)", (int)(klen < 32 ? klen : 32), q);
				return -1;
			}
			out->count++;
		}
		q += len + (q[len] == '&');
	}
	return 0;
}

static void fail(struct farm_reply *out, int status, const char *fmt, const char *a, const char *b)
{
	out->status = status;
	snprintf(out->text, sizeof out->text, fmt, a, b);
	size_t n = strlen(out->text);
	if (n + 1 < sizeof out->text) {
		out->text[n] = '\n';
		out->text[n + 1] = '\0';
	}
}

/* label=KEY=VALUE (repeatable), suite=NAME, state=STATE into a filter; other keys are the caller's. */
static int filter_from_query(const struct query *q, struct farm_filter *f, struct farm_reply *out,
			     const char *const *other_keys)
{
	memset(f, 0, sizeof *f);
	for (int i = 0; i < q->count; i++) {
		struct aa_error err = {0};
		if (!strcmp(q->key[i], "label")) {
			if (aa_label_parse(q->value[i], f->labels, &f->label_count, "label", &err)) {
				fail(out, 400, "label: %s%s", err.message, "");
				return -1;
			}
		} else if (!strcmp(q->key[i], "suite")) {
			snprintf(f->suite, sizeof f->suite, "%s", q->value[i]);
			f->has_suite = true;
		} else if (!strcmp(q->key[i], "state")) {
			if (!job_state_known(q->value[i]) || strlen(q->value[i]) >= sizeof f->state) {
				fail(out, 400, "state: %s%s", "expected queued, running, done, failed or cancelled", "");
				return -1;
			}
			snprintf(f->state, sizeof f->state, "%s", q->value[i]);
		} else {
			bool known = false;
			for (int k = 0; other_keys && other_keys[k]; k++)
				known |= !strcmp(other_keys[k], q->key[i]);
			if (!known) {
				fail(out, 400, "%s: unknown query parameter%s", q->key[i], "");
				return -1;
			}
		}
	}
	return 0;
}

static void jobs_route(struct daemon *d, const struct query *q, struct farm_reply *out)
{
	struct farm_filter f;
	if (filter_from_query(q, &f, out, (const char *const[]){"t", NULL}))
		return;
	json_t *arr = json_array();
	pthread_mutex_lock(&d->store->lock);
	for (struct job *j = d->store->jobs; j; j = j->next)
		if (farm_filter_matches(&f, j))
			json_array_append_new(arr, job_to_json(j));
	pthread_mutex_unlock(&d->store->lock);
	out->status = 200;
	out->json = json_pack("{so}", "jobs", arr);
}

static void compare_route(struct daemon *d, const char *id, const struct query *q, struct farm_reply *out)
{
	struct aa_compare_options o = {0};
	const char *baseline = NULL;
	for (int i = 0; i < q->count; i++) {
		struct aa_error err = {0};
		if (!strcmp(q->key[i], "baseline")) {
			baseline = q->value[i];
		} else if (!strcmp(q->key[i], "fail_if") || !strcmp(q->key[i], "fail-if")) {
			if (!strcmp(q->value[i], "default")) {
				o.gate_count += aa_gates_default(o.gates + o.gate_count, AA_MAX_GATES - o.gate_count);
			} else if (o.gate_count >= AA_MAX_GATES || aa_gate_parse(q->value[i], &o.gates[o.gate_count], "fail_if", &err)) {
				fail(out, 400, "fail_if: %s%s", err.message[0] ? err.message : "too many gates", "");
				return;
			} else {
				o.gate_count++;
			}
		} else if (!strcmp(q->key[i], "allow_missing")) {
			o.allow_missing = strcmp(q->value[i], "0") != 0;
		} else if (!strcmp(q->key[i], "raw_cost")) {
			o.raw_cost = strcmp(q->value[i], "0") != 0;
		} else if (strcmp(q->key[i], "t")) {
			fail(out, 400, "%s: unknown query parameter; compare takes baseline, fail_if, allow_missing, raw_cost%s",
			     q->key[i], "");
			return;
		}
	}
	pthread_mutex_lock(&d->store->lock);
	struct job *job = store_find(d->store, id);
	enum job_state state = job ? job->state : JOB_QUEUED;
	char own[sizeof job->spec.baseline] = "";
	if (job)
		snprintf(own, sizeof own, "%s", job->spec.baseline);
	pthread_mutex_unlock(&d->store->lock);
	if (!job) {
		fail(out, 404, "no job '%s'%s", id, "");
		return;
	}
	if (!baseline && !own[0]) {
		fail(out, 400, "baseline: missing; give ?baseline=JOB or ?baseline=latest:KEY=VALUE (job %s names no "
		     "baseline of its own)%s", id, "");
		return;
	}
	if (state != JOB_DONE) {
		fail(out, 409, "job %s is %s; only a done job can be compared", id, job_state_name(state));
		return;
	}
	struct aa_error err = {0};
	char base_id[16];
	/* the job stays in the store while compared: retention never deletes the newest jobs, and the files are
	 * read whole or not at all */
	json_t *cmp = farm_compare_with(d->store, job, baseline ? baseline : own, &o, base_id, sizeof base_id, &err);
	if (!cmp) {
		fail(out, err.code == AA_ERR_NOT_FOUND ? 404 : err.code == AA_ERR_INVALID ? 400 : 500, "%s%s",
		     err.path[0] ? "baseline: " : "", err.message);
		return;
	}
	out->status = 200;
	out->json = cmp;
}

/* The value of one metric of one summary entry: what the dashboard plots. */
static json_t *series_value(json_t *entry, const char *metric)
{
	const char *key = !strcmp(metric, "memory") ? "memory_bytes" : metric;
	json_t *v = json_object_get(entry, key);
	return json_is_number(v) ? json_incref(v) : json_null();
}

static void series_route(struct daemon *d, const struct query *q, struct farm_reply *out)
{
	static const char *const metrics[] = {"psnr", "ssim", "flip", "flicker", "gpu_ms", "memory", NULL};
	struct farm_filter f;
	if (filter_from_query(q, &f, out, (const char *const[]){"metric", "case", "method", "t", NULL}))
		return;
	if (!f.has_suite) {
		fail(out, 400, "suite: missing; give ?suite=NAME (the job field suite; a job without one is plotted by "
		     "its job hash)%s%s", "", "");
		return;
	}
	const char *metric = NULL, *want_case = NULL, *want_method = NULL;
	for (int i = 0; i < q->count; i++) {
		if (!strcmp(q->key[i], "metric"))
			metric = q->value[i];
		else if (!strcmp(q->key[i], "case"))
			want_case = q->value[i];
		else if (!strcmp(q->key[i], "method"))
			want_method = q->value[i];
	}
	int known = metric ? -1 : 0;
	for (int i = 0; metric && metrics[i]; i++)
		if (!strcmp(metric, metrics[i]))
			known = i;
	if (known < 0) {
		fail(out, 400, "metric: '%s' is not plotted; metrics: psnr, ssim, flip, flicker, gpu_ms, memory%s", metric, "");
		return;
	}
	if (!f.state[0])
		snprintf(f.state, sizeof f.state, "done");
	json_t *jobs = json_array(), *series = json_array(), *index = json_object();
	pthread_mutex_lock(&d->store->lock);
	size_t count = 0;
	for (struct job *j = d->store->jobs; j; j = j->next) /* oldest first: submission order */
		if (farm_filter_matches(&f, j) && j->summary)
			count++;
	size_t at = 0;
	for (struct job *j = d->store->jobs; j; j = j->next) {
		if (!farm_filter_matches(&f, j) || !j->summary)
			continue;
		json_t *labels = json_object();
		for (int i = 0; i < j->spec.label_count; i++)
			json_object_set_new(labels, j->spec.labels[i].key, json_string(j->spec.labels[i].value));
		const char *commit = aa_job_label(&j->spec, "commit");
		json_array_append_new(jobs, json_pack("{ss sf so ss}", "id", j->id, "submitted_at", j->submitted_at,
						      "labels", labels, "x", commit ? commit : j->id));
		char plain_case[512];
		aa_case_id(&j->spec, 0, plain_case, sizeof plain_case);
		size_t i;
		json_t *e;
		json_array_foreach(j->summary, i, e) {
			const char *c = json_string_value(json_object_get(e, "case"));
			const char *label = json_string_value(json_object_get(e, "label"));
			if (!c)
				c = plain_case;
			if (!label || (want_case && strcmp(want_case, c)) || (want_method && strcmp(want_method, label)))
				continue;
			for (int m = 0; metrics[m]; m++) {
				if (metric && strcmp(metric, metrics[m]))
					continue;
				char key[1200];
				snprintf(key, sizeof key, "%s\n%s\n%s", c, label, metrics[m]);
				json_t *s = json_object_get(index, key);
				if (!s) {
					json_t *values = json_array();
					for (size_t k = 0; k < count; k++)
						json_array_append_new(values, json_null());
					s = json_pack("{ss ss ss so}", "case", c, "method", label, "metric", metrics[m], "values",
						      values);
					json_object_set_new(index, key, s);
					json_array_append(series, s);
				}
				json_array_set_new(json_object_get(s, "values"), at, series_value(e, metrics[m]));
			}
		}
		at++;
	}
	pthread_mutex_unlock(&d->store->lock);
	json_decref(index);
	json_t *labels = json_object();
	for (int i = 0; i < f.label_count; i++)
		json_object_set_new(labels, f.labels[i].key, json_string(f.labels[i].value));
	out->status = 200;
	out->json = json_pack("{ss so ss so so}", "suite", f.suite, "labels", labels, "x", "the job's commit label, "
			      "else its id", "jobs", jobs, "series", series);
}

bool farm_http(struct daemon *d, const char *path, const char *query, struct farm_reply *out)
{
	struct query q;
	const char *rest = !strncmp(path, "/v1/jobs/", 9) ? path + 9 : NULL;
	const char *slash = rest ? strchr(rest, '/') : NULL;
	bool jobs = !strcmp(path, "/v1/jobs") || !strcmp(path, "/v1/jobs/");
	bool compare = slash && !strcmp(slash, "/compare") && slash - rest < 16;
	bool series = !strcmp(path, "/v1/series");
	if (!jobs && !compare && !series)
		return false;
	out->json = NULL;
	if (parse_query(query, &q, out->text, sizeof out->text)) {
		out->status = 400;
		return true;
	}
	if (jobs) {
		jobs_route(d, &q, out);
	} else if (compare) {
		char id[16];
		snprintf(id, sizeof id, "%.*s", (int)(slash - rest), rest);
		compare_route(d, id, &q, out);
	} else {
		series_route(d, &q, out);
	}
	return true;
}
