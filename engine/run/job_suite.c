/* The parts of a job that make it a suite or name it for a build farm (docs/job-format.md, "Suites",
 * "Labels", "Baselines"): a matrix of cases (scenes x paths x sizes) or a list of cases, a suite name,
 * labels and a baseline. The single-case keys of the job are the defaults of every case. */
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "run/farm.h"
#include "run/job_parse.h"
#include "util/file_name.h"
#include "util/sha256.h"
#include "run/job_spec.h"
#include "util/json_text.h"

static const char *const case_keys[] = {"scene", "path", "size", "frames", "first_frame", NULL};

/* Names (suite names, label keys): letters, digits, '.', '_' and '-', starting with a letter or digit. */
static bool name_ok(const char *s, size_t max)
{
	size_t n = strlen(s);
	if (n == 0 || n > max || !isalnum((unsigned char)s[0]))
		return false;
	for (size_t i = 0; i < n; i++)
		if (!isalnum((unsigned char)s[i]) && !strchr("._-", s[i]))
			return false;
	return true;
}

/* A key as shown in a path or message: bounded, control characters replaced. */
static void shown(const char *text, char *buf, size_t size)
{
	size_t n = 0;
	for (; text[n] && n + 1 < size && n < 40; n++)
		buf[n] = iscntrl((unsigned char)text[n]) ? '?' : text[n];
	buf[n] = '\0';
}

int aa_label_set(struct aa_label *labels, int *count, const char *key, const char *value, const char *path,
		 struct aa_error *err)
{
	char k[48];
	shown(key, k, sizeof k);
	if (!name_ok(key, sizeof labels->key - 1))
		return aa_error_set(err, AA_ERR_INVALID, path, "label key \"%s\" is not valid; a key is 1 to %zu letters, "
				    "digits, '.', '_' or '-', starting with a letter or digit (e.g. commit, branch, "
				    "build_url, machine)", k, sizeof labels->key - 1);
	size_t n = strlen(value);
	if (n == 0)
		return aa_error_set(err, AA_ERR_INVALID, path, "label %s has an empty value", k);
	if (n >= sizeof labels->value)
		return aa_error_set(err, AA_ERR_LIMIT, path, "label %s is %zu bytes long; the limit is %zu", k, n,
				    sizeof labels->value - 1);
	for (size_t i = 0; i < n; i++)
		if (iscntrl((unsigned char)value[i]))
			return aa_error_set(err, AA_ERR_INVALID, path, "label %s contains a control character at byte %zu",
					    k, i);
	int i = 0;
	while (i < *count && strcmp(labels[i].key, key) != 0)
		i++;
	if (i == *count) {
		if (*count >= AA_MAX_LABELS)
			return aa_error_set(err, AA_ERR_LIMIT, path, "more than %d labels", AA_MAX_LABELS);
		(*count)++;
	}
	snprintf(labels[i].key, sizeof labels[i].key, "%s", key);
	snprintf(labels[i].value, sizeof labels[i].value, "%s", value);
	return 0;
}

int aa_label_parse(const char *text, struct aa_label *labels, int *count, const char *path, struct aa_error *err)
{
	const char *eq = strchr(text, '=');
	char key[64];
	if (!eq || eq == text || (size_t)(eq - text) >= sizeof key)
		return aa_error_set(err, AA_ERR_INVALID, path, "\"%.60s\" is not a label; write KEY=VALUE, e.g. "
				    "commit=1a2b3c4 or branch=main", text);
	memcpy(key, text, (size_t)(eq - text));
	key[eq - text] = '\0';
	return aa_label_set(labels, count, key, eq + 1, path, err);
}

static int parse_labels(const json_t *v, struct aa_job_spec *s, struct aa_error *err)
{
	if (!json_is_object(v))
		return aa_error_set(err, AA_ERR_INVALID, "labels", "expected an object like {\"commit\": \"1a2b3c4\"}, got %s",
				    aa_json_type_name(v));
	const char *key;
	json_t *value;
	s->label_count = 0;
	json_object_foreach((json_t *)v, key, value) {
		char path[96], k[48];
		shown(key, k, sizeof k);
		snprintf(path, sizeof path, "labels.%s", k);
		if (!json_is_string(value))
			return aa_error_set(err, AA_ERR_INVALID, path, "expected a string, got %s", aa_json_type_name(value));
		if (strlen(json_string_value(value)) != json_string_length(value))
			return aa_error_set(err, AA_ERR_INVALID, path, "contains a NUL byte");
		if (aa_label_set(s->labels, &s->label_count, key, json_string_value(value), path, err) < 0)
			return -1;
	}
	return 0;
}

int aa_baseline_parse(const char *text, struct aa_baseline *out, const char *path, struct aa_error *err)
{
	memset(out, 0, sizeof *out);
	size_t digits = strspn(text, "0123456789");
	if (digits > 0 && text[digits] == '\0') {
		if (digits >= sizeof out->job)
			return aa_error_set(err, AA_ERR_INVALID, path, "job id \"%.40s\" is too long", text);
		memcpy(out->job, text, digits + 1);
		return 0;
	}
	if (strcmp(text, "latest") != 0 && strncmp(text, "latest:", 7) != 0)
		return aa_error_set(err, AA_ERR_INVALID, path, "\"%.60s\" is not a baseline; give a job id (\"000042\") or "
				    "\"latest:KEY=VALUE[,KEY=VALUE...]\" for the latest finished job of the same suite "
				    "with those labels (e.g. latest:branch=main)", text);
	out->latest = true;
	if (text[6] == '\0')
		return 0;
	char list[512];
	if (strlen(text + 7) >= sizeof list)
		return aa_error_set(err, AA_ERR_LIMIT, path, "baseline is too long");
	snprintf(list, sizeof list, "%s", text + 7);
	char *save = NULL;
	for (char *item = strtok_r(list, ",", &save); item; item = strtok_r(NULL, ",", &save))
		if (aa_label_parse(item, out->labels, &out->label_count, path, err) < 0)
			return -1;
	if (out->label_count == 0)
		return aa_error_set(err, AA_ERR_INVALID, path, "\"latest:\" names no label; write latest:KEY=VALUE");
	return 0;
}

/* An array of 1 to AA_MAX_CASES entries. */
static int matrix_array(const json_t *v, const char *key, const char *example, struct aa_error *err)
{
	if (!json_is_array(v))
		return aa_error_set(err, AA_ERR_INVALID, key, "expected an array like %s, got %s", example,
				    aa_json_type_name(v));
	if (json_array_size(v) == 0)
		return aa_error_set(err, AA_ERR_INVALID, key, "the list is empty; give at least one entry, e.g. %s", example);
	if (json_array_size(v) > AA_MAX_CASES)
		return aa_error_set(err, AA_ERR_LIMIT, key, "%zu entries; a suite has at most %d cases", json_array_size(v),
				    AA_MAX_CASES);
	return 0;
}

static int case_scene(const json_t *v, const char *path, struct aa_case_spec *c, struct aa_error *err)
{
	if (aa_job_parse_string(v, path, false, c->scene, sizeof c->scene, err) < 0)
		return -1;
	return aa_job_parse_scene(c->scene, path, err);
}

static int case_size(const json_t *v, const char *path, struct aa_case_spec *c, struct aa_error *err)
{
	if (json_is_string(v)) {
		if (aa_parse_size(json_string_value(v), &c->width, &c->height, err) < 0) {
			snprintf(err->path, sizeof err->path, "%s", path);
			return -1;
		}
		return 0;
	}
	char p0[96], p1[96];
	snprintf(p0, sizeof p0, "%s[0]", path);
	snprintf(p1, sizeof p1, "%s[1]", path);
	if (!json_is_array(v) || json_array_size(v) != 2)
		return aa_error_set(err, AA_ERR_INVALID, path, "expected \"WIDTHxHEIGHT\" or [width, height], got %s",
				    aa_json_type_name(v));
	if (aa_job_parse_int(json_array_get(v, 0), p0, 1, AA_MAX_SIZE, &c->width, err) < 0 ||
	    aa_job_parse_int(json_array_get(v, 1), p1, 1, AA_MAX_SIZE, &c->height, err) < 0)
		return -1;
	return 0;
}

/* The job's own scene, path, size and frames: what every case starts from. */
static int case_defaults(const struct aa_job_spec *s, struct aa_case_spec *c, struct aa_error *err)
{
	if (strlen(s->scene) >= sizeof c->scene)
		return aa_error_set(err, AA_ERR_LIMIT, "scene", "is %zu bytes long; in a suite the limit is %zu",
				    strlen(s->scene), sizeof c->scene - 1);
	memset(c, 0, sizeof *c);
	snprintf(c->scene, sizeof c->scene, "%s", s->scene);
	snprintf(c->path, sizeof c->path, "%s", s->path);
	c->width = s->width;
	c->height = s->height;
	c->frames = s->frames;
	c->first_frame = s->first_frame;
	return 0;
}

static int parse_case_object(const json_t *v, const char *path, struct aa_case_spec *c, struct aa_error *err)
{
	char where[128];
	if (!json_is_object(v))
		return aa_error_set(err, AA_ERR_INVALID, path, "expected a case object like {\"scene\": \"thin-wires\", "
				    "\"size\": \"160x90\"}, got %s", aa_json_type_name(v));
	if (aa_job_parse_keys(v, path, case_keys, err) < 0)
		return -1;
	const json_t *f;
	if ((f = json_object_get(v, "scene"))) {
		snprintf(where, sizeof where, "%s.scene", path);
		if (case_scene(f, where, c, err) < 0)
			return -1;
	}
	if ((f = json_object_get(v, "path"))) {
		snprintf(where, sizeof where, "%s.path", path);
		if (aa_job_parse_string(f, where, false, c->path, sizeof c->path, err) < 0)
			return -1;
	}
	if ((f = json_object_get(v, "size"))) {
		snprintf(where, sizeof where, "%s.size", path);
		if (case_size(f, where, c, err) < 0)
			return -1;
	}
	if ((f = json_object_get(v, "frames"))) {
		snprintf(where, sizeof where, "%s.frames", path);
		if (aa_job_parse_int(f, where, 1, AA_MAX_FRAMES, &c->frames, err) < 0)
			return -1;
	}
	if ((f = json_object_get(v, "first_frame"))) {
		snprintf(where, sizeof where, "%s.first_frame", path);
		if (aa_job_parse_int(f, where, 0, 10000000, &c->first_frame, err) < 0)
			return -1;
	}
	return 0;
}

/* scenes x paths x sizes, scenes outermost. */
static int parse_matrix(const json_t *job, struct aa_job_spec *s, struct aa_error *err)
{
	const json_t *scenes = json_object_get(job, "scenes"), *paths = json_object_get(job, "paths"),
		     *sizes = json_object_get(job, "sizes");
	if (scenes && json_object_get(job, "scene"))
		return aa_error_set(err, AA_ERR_INVALID, "scenes", "give either \"scene\" or \"scenes\", not both");
	if (paths && json_object_get(job, "path"))
		return aa_error_set(err, AA_ERR_INVALID, "paths", "give either \"path\" or \"paths\", not both");
	if (sizes && (json_object_get(job, "size") || json_object_get(job, "width") || json_object_get(job, "height")))
		return aa_error_set(err, AA_ERR_INVALID, "sizes", "give either \"sizes\" or \"size\"/\"width\"/\"height\", "
				    "not both");
	if ((scenes && matrix_array(scenes, "scenes", "[\"thin-wires\", \"hard-edges\"]", err) < 0) ||
	    (paths && matrix_array(paths, "paths", "[\"default\", \"static\"]", err) < 0) ||
	    (sizes && matrix_array(sizes, "sizes", "[\"160x90\", \"320x180\"]", err) < 0))
		return -1;
	size_t ns = scenes ? json_array_size(scenes) : 1, np = paths ? json_array_size(paths) : 1,
	       nz = sizes ? json_array_size(sizes) : 1;
	if (ns * np * nz > AA_MAX_CASES)
		return aa_error_set(err, AA_ERR_LIMIT, scenes ? "scenes" : paths ? "paths" : "sizes",
				    "%zu scenes x %zu paths x %zu sizes is %zu cases; a suite has at most %d",
				    ns, np, nz, ns * np * nz, AA_MAX_CASES);
	struct aa_case_spec base, axis_scene[AA_MAX_CASES], axis_path[AA_MAX_CASES], axis_size[AA_MAX_CASES];
	if (case_defaults(s, &base, err) < 0)
		return -1;
	for (size_t i = 0; i < ns; i++) {
		char path[48];
		snprintf(path, sizeof path, "scenes[%zu]", i);
		axis_scene[i] = base;
		if (scenes && case_scene(json_array_get(scenes, i), path, &axis_scene[i], err) < 0)
			return -1;
		for (size_t j = 0; scenes && j < i; j++)
			if (!strcmp(axis_scene[j].scene, axis_scene[i].scene))
				return aa_error_set(err, AA_ERR_INVALID, path, "same scene as scenes[%zu]; list it once", j);
	}
	for (size_t i = 0; i < np; i++) {
		char path[48];
		snprintf(path, sizeof path, "paths[%zu]", i);
		axis_path[i] = base;
		if (paths && aa_job_parse_string(json_array_get(paths, i), path, false, axis_path[i].path,
						 sizeof axis_path[i].path, err) < 0)
			return -1;
		for (size_t j = 0; paths && j < i; j++)
			if (!strcmp(axis_path[j].path, axis_path[i].path))
				return aa_error_set(err, AA_ERR_INVALID, path, "same path as paths[%zu]; list it once", j);
	}
	for (size_t i = 0; i < nz; i++) {
		char path[48];
		snprintf(path, sizeof path, "sizes[%zu]", i);
		axis_size[i] = base;
		if (sizes && case_size(json_array_get(sizes, i), path, &axis_size[i], err) < 0)
			return -1;
		for (size_t j = 0; sizes && j < i; j++)
			if (axis_size[j].width == axis_size[i].width && axis_size[j].height == axis_size[i].height)
				return aa_error_set(err, AA_ERR_INVALID, path, "same size as sizes[%zu]; list it once", j);
	}
	s->case_count = 0;
	for (size_t i = 0; i < ns; i++)
		for (size_t j = 0; j < np; j++)
			for (size_t k = 0; k < nz; k++) {
				struct aa_case_spec *c = &s->cases[s->case_count++];
				*c = base;
				memcpy(c->scene, axis_scene[i].scene, sizeof c->scene);
				memcpy(c->path, axis_path[j].path, sizeof c->path);
				c->width = axis_size[k].width;
				c->height = axis_size[k].height;
			}
	return 0;
}

static int parse_cases(const json_t *job, struct aa_job_spec *s, struct aa_error *err)
{
	const json_t *cases = json_object_get(job, "cases");
	const char *const matrix[] = {"scenes", "paths", "sizes"};
	for (int i = 0; i < 3; i++)
		if (json_object_get(job, matrix[i]))
			return aa_error_set(err, AA_ERR_INVALID, "cases", "give either \"cases\" or the matrix keys "
					    "(scenes, paths, sizes), not both");
	if (matrix_array(cases, "cases", "[{\"scene\": \"thin-wires\"}, {\"scene\": \"hard-edges\", "
			 "\"size\": \"320x180\"}]", err) < 0)
		return -1;
	struct aa_case_spec base;
	if (case_defaults(s, &base, err) < 0)
		return -1;
	s->case_count = 0;
	for (size_t i = 0; i < json_array_size(cases); i++) {
		char path[48];
		snprintf(path, sizeof path, "cases[%zu]", i);
		struct aa_case_spec *c = &s->cases[s->case_count];
		*c = base;
		if (parse_case_object(json_array_get(cases, i), path, c, err) < 0)
			return -1;
		s->case_count++;
	}
	return 0;
}

int aa_job_suite_from_json(const json_t *job, struct aa_job_spec *s, struct aa_error *err)
{
	const json_t *v;
	s->is_suite = false;
	s->case_count = 0;
	if ((v = json_object_get(job, "suite"))) {
		if (aa_job_parse_string(v, "suite", false, s->suite, sizeof s->suite, err) < 0)
			return -1;
		if (!name_ok(s->suite, sizeof s->suite - 1))
			return aa_error_set(err, AA_ERR_INVALID, "suite", "\"%.60s\" is not a suite name; use letters, digits, "
					    "'.', '_' and '-', starting with a letter or digit", s->suite);
	}
	if ((v = json_object_get(job, "labels")) && parse_labels(v, s, err) < 0)
		return -1;
	if ((v = json_object_get(job, "verdicts"))) { /* docs/hard-cases.md */
		if (!json_is_boolean(v))
			return aa_error_set(err, AA_ERR_INVALID, "verdicts", "expected true or false");
		s->verdicts = json_is_true(v);
	}
	if ((v = json_object_get(job, "baseline"))) {
		struct aa_baseline b;
		if (aa_job_parse_string(v, "baseline", false, s->baseline, sizeof s->baseline, err) < 0 ||
		    aa_baseline_parse(s->baseline, &b, "baseline", err) < 0)
			return -1;
	}
	bool matrix = json_object_get(job, "scenes") || json_object_get(job, "paths") || json_object_get(job, "sizes");
	if (json_object_get(job, "cases")) {
		if (parse_cases(job, s, err) < 0)
			return -1;
	} else if (matrix) {
		if (parse_matrix(job, s, err) < 0)
			return -1;
	} else {
		return 0;
	}
	s->is_suite = true;
	const char *where = json_object_get(job, "cases") ? "cases" : "scenes";
	for (int i = 0; i < s->case_count; i++) {
		char path[48], id[512], dir[512], other_id[512], other_dir[512];
		snprintf(path, sizeof path, "%s[%d]", where, i);
		if (!json_object_get(job, "cases"))
			snprintf(path, sizeof path, "%s", json_object_get(job, "scenes") ? "scenes" :
							  json_object_get(job, "paths") ? "paths" : "sizes");
		const struct aa_case_spec *c = &s->cases[i];
		const int repeat = s->timing_auto ? aa_timing_auto_repeat(c->frames) : s->timing_repeat;
		if ((long)c->frames * repeat > AA_MAX_FRAMES)
			return aa_error_set(err, AA_ERR_LIMIT, path, "%d frames x %d repeats is over %d timed renders per "
					    "method; lower frames or timing.repeat", c->frames, repeat, AA_MAX_FRAMES);
		aa_case_id(s, i, id, sizeof id);
		aa_case_dirname(s, i, dir, sizeof dir);
		for (int j = 0; j < i; j++) {
			aa_case_id(s, j, other_id, sizeof other_id);
			aa_case_dirname(s, j, other_dir, sizeof other_dir);
			if (!strcmp(id, other_id))
				return aa_error_set(err, AA_ERR_INVALID, path, "the same case (%s) as case %d; list it once",
						    id, j);
			if (!strcmp(dir, other_dir))
				return aa_error_set(err, AA_ERR_INVALID, path, "case %s would share the image directory %s with "
						    "case %s; rename a scene or path", id, dir, other_id);
		}
	}
	return 0;
}

/* A case's fields wherever they are kept: in cases[] for a suite, in the job itself otherwise. */
struct case_view {
	const char *scene, *path;
	int width, height, frames, first_frame;
};

static struct case_view case_of(const struct aa_job_spec *spec, int i)
{
	if (spec->is_suite && i >= 0 && i < spec->case_count) {
		const struct aa_case_spec *c = &spec->cases[i];
		return (struct case_view){c->scene, c->path, c->width, c->height, c->frames, c->first_frame};
	}
	return (struct case_view){spec->scene, spec->path, spec->width, spec->height, spec->frames, spec->first_frame};
}

static json_t *case_json(struct case_view c)
{
	char size[32];
	snprintf(size, sizeof size, "%dx%d", c.width, c.height);
	return json_pack("{s:s, s:s, s:s, s:i, s:i}", "scene", c.scene, "path", c.path, "size", size, "frames",
			 c.frames, "first_frame", c.first_frame);
}

static json_t *labels_json(const struct aa_job_spec *spec)
{
	json_t *o = json_object();
	for (int i = 0; i < spec->label_count && i < AA_MAX_LABELS; i++)
		json_object_set_new(o, spec->labels[i].key, json_string(spec->labels[i].value));
	return o;
}

void aa_job_suite_to_json(const struct aa_job_spec *spec, json_t *job)
{
	if (!job)
		return;
	if (spec->suite[0])
		json_object_set_new(job, "suite", json_string(spec->suite));
	if (spec->label_count > 0)
		json_object_set_new(job, "labels", labels_json(spec));
	if (spec->baseline[0])
		json_object_set_new(job, "baseline", json_string(spec->baseline));
	if (spec->verdicts)
		json_object_set_new(job, "verdicts", json_true());
	if (!spec->is_suite)
		return;
	const char *const single[] = {"scene", "path", "size", "frames", "first_frame"};
	for (int i = 0; i < 5; i++)
		json_object_del(job, single[i]);
	json_t *cases = json_array();
	for (int i = 0; i < spec->case_count && i < AA_MAX_CASES; i++)
		json_array_append_new(cases, case_json(case_of(spec, i)));
	json_object_set_new(job, "cases", cases);
}

int aa_job_case_count(const struct aa_job_spec *spec)
{
	return spec->is_suite ? spec->case_count : 1;
}

void aa_job_case(const struct aa_job_spec *spec, int i, struct aa_job_spec *out)
{
	*out = *spec;
	if (!spec->is_suite)
		return;
	const struct aa_case_spec *c = &spec->cases[i];
	snprintf(out->scene, sizeof out->scene, "%s", c->scene);
	snprintf(out->path, sizeof out->path, "%s", c->path);
	out->width = c->width;
	out->height = c->height;
	out->frames = c->frames;
	out->first_frame = c->first_frame;
	if (spec->timing_auto)
		out->timing_repeat = aa_timing_auto_repeat(c->frames);
	out->is_suite = false;
	out->case_count = 0;
}

void aa_case_id(const struct aa_job_spec *spec, int i, char *out, size_t size)
{
	struct case_view c = case_of(spec, i);
	int n = snprintf(out, size, "%s/%s/%dx%d", c.scene, c.path, c.width, c.height);
	if (c.first_frame != 0 && n >= 0 && (size_t)n < size)
		snprintf(out + n, size - (size_t)n, "@%d", c.first_frame);
}

void aa_case_dirname(const struct aa_job_spec *spec, int i, char *out, size_t size)
{
	char id[512];
	aa_case_id(spec, i, id, sizeof id);
	/* a scene given as a file path keeps only its base name: directories are for people to browse */
	struct case_view c = case_of(spec, i);
	const char *slash = strrchr(c.scene, '/');
	if (slash)
		memmove(id, id + (slash + 1 - c.scene), strlen(id + (slash + 1 - c.scene)) + 1);
	aa_label_dirname(id, out, size);
}

void aa_case_relpath(const struct aa_job_spec *spec, int i, char *out, size_t size)
{
	char dir[512];
	if (!spec->is_suite) {
		snprintf(out, size, "%s", "");
		return;
	}
	aa_case_dirname(spec, i, dir, sizeof dir);
	snprintf(out, size, "cases/%s", dir);
}

const char *aa_job_label(const struct aa_job_spec *spec, const char *key)
{
	for (int i = 0; i < spec->label_count && i < AA_MAX_LABELS; i++)
		if (!strcmp(spec->labels[i].key, key))
			return spec->labels[i].value;
	return NULL;
}

void aa_job_hash(const struct aa_job_spec *spec, char *out, size_t size)
{
	json_t *cases = json_array(), *methods = json_array();
	for (int i = 0; i < aa_job_case_count(spec); i++) {
		json_array_append_new(cases, case_json(case_of(spec, i)));
	}
	for (int i = 0; i < spec->method_count && i < AA_MAX_METHODS; i++)
		json_array_append_new(methods, json_string(spec->methods[i].label));
	/* a suite's "auto" repeat is one per case, each following from the case's frames: the same work as
	 * that number when every case has the same, else "auto" with the cases' frames */
	int case_repeat = spec->timing_repeat;
	bool varies = false;
	for (int i = 0; spec->is_suite && spec->timing_auto && i < aa_job_case_count(spec); i++) {
		const int r = aa_timing_auto_repeat(spec->cases[i].frames);
		varies = varies || (i > 0 && r != case_repeat);
		case_repeat = r;
	}
	json_t *repeat = varies ? json_string("auto") : json_integer(case_repeat);
	json_t *what = json_pack("{s:o, s:{s:i}, s:o, s:{s:o}}", "cases", cases, "reference", "samples",
				 spec->reference_samples, "methods", methods, "timing", "repeat", repeat);
	if (what && spec->over_threshold != AA_OVER_THRESHOLD_DEFAULT) /* as given only: earlier hashes stay */
		json_object_set_new(what, "over_threshold", json_real(spec->over_threshold));
	if (what && spec->reference_auto) /* only then: the hash of other jobs is as before */
		json_object_set_new(json_object_get(what, "reference"), "target_psnr",
				    json_real(spec->reference_target_psnr));
	char *text = what ? json_dumps(what, JSON_COMPACT | JSON_SORT_KEYS) : NULL;
	json_decref(what);
	char hex[65] = "";
	if (text)
		aa_sha256_hex(text, strlen(text), hex);
	free(text);
	snprintf(out, size, "sha256:%s", hex);
}
