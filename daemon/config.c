/* aalabd's configuration: defaults, and a file of "key = value" lines ('#' starts a comment) whose keys
 * are the long options without "--" (docs/aalabd.8). SIGHUP reads the file again. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "config.h"
#include "util/file_open.h"
#include "util/json_text.h"
#include "util/socket_path.h"
#include "reference/reference_cache.h"

void config_defaults(struct config *c)
{
	memset(c, 0, sizeof *c);
	/* the same default as aalab's (util/socket_path.h); a path too long for a socket is cut and then refused
	 * by the check of the socket path */
	char socket_path[1024];
	aa_socket_default_path(socket_path, sizeof socket_path);
	size_t n = strlen(socket_path) < sizeof c->socket_path ? strlen(socket_path) : sizeof c->socket_path - 1;
	memcpy(c->socket_path, socket_path, n);
	c->socket_path[n] = 0;
	const char *state = getenv("STATE_DIRECTORY"); /* systemd's StateDirectory= */
	if (state && *state)
		snprintf(c->state_dir, sizeof c->state_dir, "%s", state);
	else
		snprintf(c->state_dir, sizeof c->state_dir, "%s/.local/state/aalabd",
			 getenv("HOME") ? getenv("HOME") : "/tmp");
	c->max_request_bytes = 1 << 20;
	c->max_connections = 256;
	c->max_connections_per_peer = 64;
	c->hello_timeout_s = 10;
	c->max_jobs_per_client = 32;
	c->max_queued_jobs = 1000;
	c->max_job_budget = 2e11;
	c->idle_timeout_s = 600;
	c->slow_client_timeout_s = 30;
	c->request_timeout_s = 30;
	c->client_buffer_bytes = 4 << 20;
	c->retention_jobs = 200;
	c->max_job_interruptions = 3;
	c->render_nice = 5;
	c->retention_bytes = 10ull << 30;
	c->scene_cache_bytes = 512ull << 20;
	c->reference_cache_bytes = AA_REFERENCE_CACHE_DEFAULT_BYTES;
	c->drain_timeout_s = 60;
	c->job_time_limit_s = 3600;
}

struct key {
	const char *name;
	enum { K_STR, K_INT, K_SIZE, K_U64, K_DOUBLE, K_BOOL } type;
	size_t offset, size;
	double min, max;
};

#define STR(n, f) {n, K_STR, offsetof(struct config, f), sizeof ((struct config *)0)->f, 0, 0}
#define NUM(n, t, f, lo, hi) {n, t, offsetof(struct config, f), 0, lo, hi}
static const struct key keys[] = {
	STR("socket", socket_path), STR("state-dir", state_dir), STR("tcp", tcp), STR("token-file", token_file),
	STR("http", http), STR("web-dir", web_dir), STR("device", device),
	NUM("max-request-bytes", K_SIZE, max_request_bytes, 1024, 1 << 30),
	NUM("max-connections", K_INT, max_connections, 1, 100000),
	NUM("max-connections-per-peer", K_INT, max_connections_per_peer, 1, 100000),
	NUM("hello-timeout", K_INT, hello_timeout_s, 1, 86400),
	NUM("max-jobs-per-client", K_INT, max_jobs_per_client, 1, 1000000),
	NUM("max-queued-jobs", K_INT, max_queued_jobs, 1, 1000000),
	NUM("max-job-budget", K_DOUBLE, max_job_budget, 1, 1e18),
	NUM("idle-timeout", K_INT, idle_timeout_s, 1, 86400 * 7),
	NUM("slow-client-timeout", K_INT, slow_client_timeout_s, 1, 86400),
	NUM("request-timeout", K_INT, request_timeout_s, 1, 86400),
	NUM("client-buffer-bytes", K_SIZE, client_buffer_bytes, 4096, 1 << 30),
	NUM("retention-jobs", K_INT, retention_jobs, 0, 10000000),
	NUM("max-job-interruptions", K_INT, max_job_interruptions, 0, 1000),
	NUM("retention-bytes", K_U64, retention_bytes, 0, 1e18),
	NUM("scene-cache-bytes", K_U64, scene_cache_bytes, 0, 1e18),
	STR("reference-cache", reference_cache),
	NUM("reference-cache-size", K_U64, reference_cache_bytes, AA_REFERENCE_CACHE_MIN_BYTES, 1e18),
	NUM("drain-timeout", K_INT, drain_timeout_s, 0, 86400),
	NUM("verbose", K_INT, verbose, 0, 3),
	{"allow-user-methods", K_BOOL, offsetof(struct config, allow_user_methods), 0, 0, 0},
	NUM("job-time-limit", K_INT, job_time_limit_s, 0, 86400 * 7),
	NUM("render-nice", K_INT, render_nice, 0, 19),
};

/* Sets one option by name; used by the config file and by the command line. */
bool config_has_key(const char *name)
{
	for (size_t i = 0; i < sizeof keys / sizeof keys[0]; i++)
		if (strcmp(keys[i].name, name) == 0)
			return true;
	return false;
}

int config_set(struct config *c, const char *name, const char *value, char *err, size_t err_size)
{
	for (size_t i = 0; i < sizeof keys / sizeof keys[0]; i++) {
		const struct key *k = &keys[i];
		if (strcmp(k->name, name) != 0)
			continue;
		char *field = (char *)c + k->offset;
		if (k->type == K_BOOL) {
			static const char *const yes[] = {"yes", "true", "on", "1"}, *const no[] = {"no", "false", "off", "0"};
			for (int b = 0; b < 4; b++)
				if (!strcmp(value, yes[b]) || !strcmp(value, no[b])) {
					*(bool *)field = !strcmp(value, yes[b]);
					return 0;
				}
			snprintf(err, err_size, "%s: expected yes or no, got '%s'", name, value);
			return -1;
		}
		if (k->type == K_STR) {
			if (strlen(value) >= k->size) {
				snprintf(err, err_size, "%s: longer than %zu bytes", name, k->size - 1);
				return -1;
			}
			memcpy(field, value, strlen(value) + 1);
			return 0;
		}
		char *end;
		errno = 0;
		double v = strtod(value, &end);
		/* sizes may end in K, M or G (powers of 1024) */
		if (end != value && *end && strchr("KMG", *end) && !end[1]) {
			v *= *end == 'K' ? 1024.0 : *end == 'M' ? 1048576.0 : 1073741824.0;
			end++;
		}
		if (errno || end == value || *end || v < k->min || v > k->max ||
		    (k->type != K_DOUBLE && v != (double)(long long)v)) {
			snprintf(err, err_size, "%s: expected a whole number from %.0f to %.0f, got '%s'", name, k->min,
				 k->max, value);
			return -1;
		}
		switch (k->type) {
		case K_INT: *(int *)field = (int)v; break;
		case K_SIZE: *(size_t *)field = (size_t)v; break;
		case K_U64: *(uint64_t *)field = (uint64_t)v; break;
		case K_DOUBLE: *(double *)field = v; break;
		default: break;
		}
		return 0;
	}
	snprintf(err, err_size, "unknown option '%s'", name);
	return -1;
}

int config_load(struct config *c, const char *path, char *err, size_t err_size)
{
	struct aa_error aerr = {0};
	FILE *f = aa_file_fopen_regular(path, "config", &aerr); /* a FIFO would block the reload */
	if (!f) {
		snprintf(err, err_size, "%s", aerr.message);
		return -1;
	}
	char line[2048], msg[512];
	int lineno = 0, rc = 0;
	while (fgets(line, sizeof line, f)) {
		lineno++;
		char *hash = strchr(line, '#');
		if (hash)
			*hash = 0;
		char *s = aa_trim(line);
		if (!*s)
			continue;
		char *eq = strchr(s, '=');
		if (!eq) {
			snprintf(err, err_size, "%s:%d: expected 'key = value'", path, lineno);
			rc = -1;
			break;
		}
		*eq = 0;
		if (config_set(c, aa_trim(s), aa_trim(eq + 1), msg, sizeof msg)) {
			snprintf(err, err_size, "%s:%d: %s", path, lineno, msg);
			rc = -1;
			break;
		}
	}
	fclose(f);
	return rc;
}

void config_reference_cache_dir(const struct config *c, char *out, size_t size)
{
	if (!strcmp(c->reference_cache, "off"))
		snprintf(out, size, "%s", "");
	else if (c->reference_cache[0])
		snprintf(out, size, "%s", c->reference_cache);
	else
		snprintf(out, size, "%s/references", c->state_dir);
}

void config_apply_reload(struct config *to, const struct config *from)
{
	/* listeners, state directory and device stay as they are until a restart */
	struct config keep = *to;
	*to = *from;
	memcpy(to->socket_path, keep.socket_path, sizeof to->socket_path);
	memcpy(to->state_dir, keep.state_dir, sizeof to->state_dir);
	memcpy(to->tcp, keep.tcp, sizeof to->tcp);
	memcpy(to->http, keep.http, sizeof to->http);
	memcpy(to->device, keep.device, sizeof to->device);
	/* the store of references is opened at start-up */
	memcpy(to->reference_cache, keep.reference_cache, sizeof to->reference_cache);
	to->reference_cache_bytes = keep.reference_cache_bytes;
	memcpy(to->config_file, keep.config_file, sizeof to->config_file);
	/* whether GPU work runs in a worker process is decided at start-up */
	to->allow_user_methods = keep.allow_user_methods;
	/* the rendering threads took their priority when they started */
	to->render_nice = keep.render_nice;
}
