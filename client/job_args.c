/* The job flags shared by `aalab run` and `aalab submit` (--scene, --methods, --size, ...): each sets a
 * field of the job JSON of docs/job-format.md, and a job file given first is overridden by them. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "client.h"
#include "run/farm.h"
#include "util/file_io.h"

static int parse_int(const char *cmd, const char *field, const char *text, json_int_t *out)
{
	char *end;
	errno = 0;
	long long v = strtoll(text, &end, 10);
	if (errno || end == text || *end) {
		fprintf(stderr, "aalab %s: %s: expected an integer, got '%s'\n", cmd, field, text);
		return -1;
	}
	*out = v;
	return 0;
}

int aa_job_flag(const char *cmd, const char *flag, const char *value, json_t *job)
{
	static const char *const strings[][2] = {{"scene", "scene"}, {"path", "path"}, {"size", "size"}};
	static const char *const ints[][2] = {{"frames", "frames"}, {"first-frame", "first_frame"}};
	json_int_t n;
	for (size_t i = 0; i < sizeof strings / sizeof strings[0]; i++)
		if (!strcmp(flag, strings[i][0])) {
			json_object_set_new(job, strings[i][1], json_string(value));
			return 0;
		}
	for (size_t i = 0; i < sizeof ints / sizeof ints[0]; i++)
		if (!strcmp(flag, ints[i][0])) {
			if (parse_int(cmd, ints[i][1], value, &n))
				return -1;
			json_object_set_new(job, ints[i][1], json_integer(n));
			return 0;
		}
	if (!strcmp(flag, "reference-samples")) {
		if (!strcmp(value, "auto")) {
			json_object_set_new(job, "reference", json_pack("{ss}", "samples", "auto"));
			return 0;
		}
		if (parse_int(cmd, "reference.samples", value, &n))
			return -1;
		json_object_set_new(job, "reference", json_pack("{sI}", "samples", n));
		return 0;
	}
	if (!strcmp(flag, "repeat")) {
		if (parse_int(cmd, "timing.repeat", value, &n))
			return -1;
		json_object_set_new(job, "timing", json_pack("{sI}", "repeat", n));
		return 0;
	}
	if (!strcmp(flag, "label")) { /* --label KEY=VALUE, repeatable: checked here so the message names it */
		struct aa_label label[AA_MAX_LABELS];
		int count = 0;
		struct aa_error err = {0};
		if (aa_label_parse(value, label, &count, "label", &err)) {
			fprintf(stderr, "aalab %s: --label: %s\n", cmd, err.message);
			return -1;
		}
		json_t *labels = json_object_get(job, "labels");
		if (!json_is_object(labels)) {
			labels = json_object();
			json_object_set_new(job, "labels", labels);
		}
		json_object_set_new(labels, label[0].key, json_string(label[0].value));
		return 0;
	}
	if (!strcmp(flag, "over-threshold")) { /* the range is checked with the job (over_threshold) */
		char *end;
		errno = 0;
		double v = strtod(value, &end);
		if (errno || end == value || *end) {
			fprintf(stderr, "aalab %s: over_threshold: expected a number, got '%s'\n", cmd, value);
			return -1;
		}
		json_object_set_new(job, "over_threshold", json_real(v));
		return 0;
	}
	if (!strcmp(flag, "baseline")) {
		json_object_set_new(job, "baseline", json_string(value));
		return 0;
	}
	if (!strcmp(flag, "methods")) {
		char **list;
		int count;
		if (aa_split_methods(value, &list, &count)) {
			fprintf(stderr, "aalab %s: methods: cannot parse '%s'\n", cmd, value);
			return -1;
		}
		json_t *arr = json_array();
		for (int i = 0; i < count; i++)
			json_array_append_new(arr, json_string(list[i]));
		aa_free_strings(list, count);
		json_object_set_new(job, "methods", arr);
		return 0;
	}
	return 1;
}

json_t *aa_job_load_file(const char *cmd, const char *path)
{
	json_error_t jerr;
	char suite[1200];
	struct aa_error err = {0};
	if (access(path, F_OK) != 0 && !strchr(path, '/')) {
		if (aa_suite_resolve(path, suite, sizeof suite, &err)) {
			fprintf(stderr, "aalab %s: %s\n", cmd, err.message);
			return NULL;
		}
		path = suite;
	}
	uint8_t *text = NULL;
	size_t size = 0;
	if (aa_file_read(path, 64u << 20, &text, &size, &err)) { /* a FIFO is refused, not waited on */
		fprintf(stderr, "aalab %s: job: %s\n", cmd, err.message);
		return NULL;
	}
	json_t *job = json_loadb((const char *)text, size, JSON_REJECT_DUPLICATES, &jerr);
	free(text);
	if (!job) {
		fprintf(stderr, "aalab %s: %s:%d:%d: %s\n", cmd, path, jerr.line, jerr.column, jerr.text);
		return NULL;
	}
	if (!json_is_object(job)) {
		fprintf(stderr, "aalab %s: %s: a job file holds a JSON object\n", cmd, path);
		json_decref(job);
		return NULL;
	}
	return job;
}

void aa_print_field_error(const char *lead, const char *path, const char *message)
{
	if (!message)
		message = "error";
	if (!path)
		path = "";
	/* named already: "path: ..." or "...: path: ..." (a scene file's "file: path: what") */
	char inside[300];
	size_t len = strlen(path);
	snprintf(inside, sizeof inside, ": %s:", path);
	bool named = !len || (strncmp(message, path, len) == 0 && message[len] == ':') || strstr(message, inside);
	fprintf(stderr, "%s%s%s%s\n", lead, named ? "" : path, named ? "" : ": ", message);
}

void aa_print_error(const char *cmd, const struct aa_error *err)
{
	char lead[64];
	snprintf(lead, sizeof lead, "aalab %s: ", cmd);
	aa_print_field_error(lead, err->path, err->message);
}

/* A job file's scene path is relative to the job file, not to where aalab runs: the file is then usable
 * from anywhere (flags given on the command line stay relative to the working directory). */
static void rebase_scene_path(json_t *job, const char *job_file)
{
	const json_t *scene = json_object_get(job, "scene");
	const char *slash = strrchr(job_file, '/');
	if (!json_is_string(scene) || !slash)
		return;
	const char *path = json_string_value(scene);
	size_t len = strlen(path);
	if (path[0] == '/' || len < 5 || strcmp(path + len - 5, ".json") != 0)
		return; /* a scene name, or an absolute path */
	char joined[2048];
	int n = snprintf(joined, sizeof joined, "%.*s/%s", (int)(slash - job_file), job_file, path);
	if (n > 0 && (size_t)n < sizeof joined)
		json_object_set_new(job, "scene", json_string(joined));
}

json_t *aa_job_build(const char *cmd, int argc, char **argv, int first, json_t *overrides)
{
	json_t *job;
	if (first < argc) {
		if (first + 1 < argc) {
			fprintf(stderr, "aalab %s: one job file at most, got '%s' and '%s'\n", cmd, argv[first],
				argv[first + 1]);
			return NULL;
		}
		job = aa_job_load_file(cmd, argv[first]);
		if (!job)
			return NULL;
		rebase_scene_path(job, argv[first]);
	} else {
		job = json_object();
	}
	/* --label adds to the file's labels rather than replacing them all */
	json_t *file_labels = json_object_get(job, "labels"), *flag_labels = json_object_get(overrides, "labels");
	if (json_is_object(file_labels) && flag_labels) {
		json_object_update(file_labels, flag_labels);
		json_t *rest = json_copy(overrides);
		json_object_del(rest, "labels");
		json_object_update(job, rest);
		json_decref(rest);
		return job;
	}
	json_object_update(job, overrides);
	return job;
}
void aa_free_strings(char **v, int count)
{
	for (int i = 0; i < count; i++)
		free(v[i]);
	free(v);
}

int aa_split_methods(const char *text, char ***out, int *count)
{
	char *copy = strdup(text);
	char **list = calloc(strlen(text) + 1, sizeof *list);
	int n = 0;
	if (!copy || !list) {
		free(copy);
		free(list);
		return -1;
	}
	char *save = NULL;
	for (char *tok = strtok_r(copy, ", \t", &save); tok; tok = strtok_r(NULL, ", \t", &save)) {
		bool continues = n > 0 && strchr(tok, '=') && !strchr(tok, ':');
		if (continues) {
			size_t len = strlen(list[n - 1]) + strlen(tok) + 2;
			char *joined = malloc(len);
			if (!joined)
				break;
			snprintf(joined, len, "%s,%s", list[n - 1], tok);
			free(list[n - 1]);
			list[n - 1] = joined;
		} else {
			list[n++] = strdup(tok);
		}
	}
	free(copy);
	*out = list;
	*count = n;
	return 0;
}
