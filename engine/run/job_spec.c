/* The job spec: defaults, parsing and validation of the job JSON (docs/job-format.md), and back to JSON. */
#include <ctype.h>
#include <limits.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "types/job.h"
#include "run/job_parse.h"
#include "methods/user_method.h"
#include "methods/methods.h"
#include "run/job_spec.h"
#include "run/method_sweep.h"
#include "util/json_text.h"
#include "util/suggest.h"

/* first_frame is a frame index on the camera path; capped so first_frame + frames fits an int easily. */
#define AA_MAX_FIRST_FRAME 10000000

static const char *const job_keys[] = { "scene", "path", "size", "width", "height", "frames", "first_frame",
					"reference", "methods", "keep_frames", "linear_frames", "exr_frames", "viewer", "over_threshold", "name", "timing",
					"suite", "scenes", "paths", "sizes", "cases", "labels", "baseline", "shard", "verdicts", "debug_targets", NULL };
static const char *const timing_keys[] = { "repeat", NULL };
static const char *const shard_keys[] = { "warmup", NULL };
static const char *const reference_keys[] = { "samples", "target_psnr", "max_samples", NULL };
static const char *const method_keys[] = { "name", "params", NULL };

/* Every job error carries the JSON path of the field; the message does not repeat it, since callers
 * print "path: message" (as for every aa_error). */
static int __attribute__((format(printf, 4, 5)))
bad(struct aa_error *err, enum aa_error_code code, const char *path, const char *fmt, ...)
{
	char msg[640];
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(msg, sizeof msg, fmt, ap);
	va_end(ap);
	return aa_error_set(err, code, path, "%s", msg);
}

static int check_keys(const json_t *obj, const char *path, const char *const *valid, struct aa_error *err)
{
	const char *key;
	json_t *value;
	json_object_foreach((json_t *)obj, key, value) {
		int i = 0;
		while (valid[i] && strcmp(valid[i], key) != 0)
			i++;
		if (valid[i])
			continue;
		char list[512] = "", where[300], k[64], mean[96];
		for (i = 0; valid[i]; i++)
			snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", i ? ", " : "", valid[i]);
		snprintf(where, sizeof where, "%s%s%s", path, *path ? "." : "", aa_shown_text(key, k, sizeof k));
		aa_suggest_text(key, valid, -1, mean, sizeof mean);
		return bad(err, AA_ERR_INVALID, where, "unknown key%s; valid keys: %s", mean, list);
	}
	return 0;
}

/* Integers only (8.0 is refused: counts are written as integers). Above max is a limit, below min is
 * invalid, so a client can tell "ask for less" from "that makes no sense". */
static int get_int(const json_t *v, const char *path, long long min, long long max, int *out,
		   struct aa_error *err)
{
	if (!json_is_integer(v))
		return bad(err, AA_ERR_INVALID, path, "expected an integer, got %s", aa_json_type_name(v));
	const long long x = json_integer_value(v);
	if (x < min || x > max)
		return bad(err, x > max ? AA_ERR_LIMIT : AA_ERR_INVALID, path,
			   "%lld is out of range; valid range: %lld to %lld", x, min, max);
	*out = (int)x;
	return 0;
}

/* A string that fits out, is non-empty unless allowed, and holds no control characters. */
static int get_string(const json_t *v, const char *path, bool allow_empty, char *out, size_t size,
		      struct aa_error *err)
{
	if (!json_is_string(v))
		return bad(err, AA_ERR_INVALID, path, "expected a string, got %s", aa_json_type_name(v));
	const char *s = json_string_value(v);
	const size_t n = json_string_length(v);
	if (n == 0 && !allow_empty)
		return bad(err, AA_ERR_INVALID, path, "must not be empty");
	if (n >= size)
		return bad(err, AA_ERR_LIMIT, path, "is %zu bytes long; the limit is %zu", n, size - 1);
	for (size_t i = 0; i < n; i++)
		if (iscntrl((unsigned char)s[i]) || s[i] == '\0')
			return bad(err, AA_ERR_INVALID, path, "contains a control character at byte %zu", i);
	memcpy(out, s, n + 1);
	return 0;
}

/* Scene names are looked up in the scene directories, so a name must not climb out of them; anything
 * that is not a plain name is a file path and must name a .json scene file. Resolution happens later. */
static int check_scene_syntax(const char *scene, const char *path, struct aa_error *err)
{
	const size_t n = strlen(scene);
	bool plain = isalnum((unsigned char)scene[0]) && n < 64;
	for (size_t i = 0; plain && i < n; i++)
		plain = isalnum((unsigned char)scene[i]) || strchr("._-", scene[i]);
	if (plain)
		return 0;
	if (n > 5 && strcmp(scene + n - 5, ".json") == 0)
		return 0;
	return bad(err, AA_ERR_INVALID, path,
		   "\"%.60s\" is neither a scene name (letters, digits, '.', '_', '-', starting with a letter or "
		   "digit, under 64 bytes) nor a path to a .json scene file", scene);
}

int aa_parse_size(const char *text, int *w, int *h, struct aa_error *err)
{
	char s[64];
	if (!text)
		text = "";
	const char *x = strpbrk(text, "xX");
	const size_t lw = x ? (size_t)(x - text) : 0, lh = x ? strlen(x + 1) : 0;
	const bool digits = x && lw > 0 && lh > 0 && strspn(text, "0123456789") == lw &&
			    strspn(x + 1, "0123456789") == lh;
	if (!digits)
		return bad(err, AA_ERR_INVALID, "size",
			   "\"%s\" is not a size; write WIDTHxHEIGHT with each from 1 to %d, e.g. 640x360",
			   aa_shown_text(text, s, sizeof s), AA_MAX_SIZE);
	/* More than 9 digits is out of range anyway; checking length first avoids overflow. */
	const long long vw = lw > 9 ? LLONG_MAX : atoll(text), vh = lh > 9 ? LLONG_MAX : atoll(x + 1);
	const long long bad_v = vw < 1 || vw > AA_MAX_SIZE ? vw : vh;
	if (vw < 1 || vw > AA_MAX_SIZE || vh < 1 || vh > AA_MAX_SIZE)
		return bad(err, bad_v > AA_MAX_SIZE ? AA_ERR_LIMIT : AA_ERR_INVALID, "size",
			   "\"%s\": %s is out of range; width and height must each be from 1 to %d",
			   aa_shown_text(text, s, sizeof s), bad_v == vw ? "width" : "height", AA_MAX_SIZE);
	*w = (int)vw;
	*h = (int)vh;
	return 0;
}

static int parse_size_value(const json_t *v, struct aa_job_spec *s, struct aa_error *err)
{
	if (json_is_string(v))
		return aa_parse_size(json_string_value(v), &s->width, &s->height, err);
	if (!json_is_array(v) || json_array_size(v) != 2)
		return bad(err, AA_ERR_INVALID, "size",
			   "expected \"WIDTHxHEIGHT\" or [width, height], got %s%s", aa_json_type_name(v),
			   json_is_array(v) ? " of the wrong length" : "");
	if (get_int(json_array_get(v, 0), "size[0]", 1, AA_MAX_SIZE, &s->width, err) < 0 ||
	    get_int(json_array_get(v, 1), "size[1]", 1, AA_MAX_SIZE, &s->height, err) < 0)
		return -1;
	return 0;
}

/* JSON parameter values go through the same text parser as "key=value", so both forms validate alike. */
static int param_value_text(const json_t *v, const char *path, char *out, size_t size, struct aa_error *err)
{
	switch (json_typeof(v)) {
	case JSON_INTEGER:
		snprintf(out, size, "%" JSON_INTEGER_FORMAT, json_integer_value(v));
		return 0;
	case JSON_REAL:
		snprintf(out, size, "%.17g", json_real_value(v));
		return 0;
	case JSON_TRUE:
	case JSON_FALSE:
		snprintf(out, size, "%s", json_is_true(v) ? "true" : "false");
		return 0;
	case JSON_STRING:
		return get_string(v, path, true, out, size, err);
	default:
		return bad(err, AA_ERR_INVALID, path, "expected a number, string or boolean, got %s", aa_json_type_name(v));
	}
}

/* {"name": "user", "params": {"file": "my_aa.json", "strength": 0.5}}: the method file first, then its
 * parameters, each checked as in the string form. */
static int parse_user_object(const json_t *params, const char *path, const struct aa_file_source *files,
			     struct aa_method_spec *ms, struct aa_error *err)
{
	char where[300], text[AA_METHOD_TEXT_MAX], file[AA_USER_PATH_MAX];
	snprintf(where, sizeof where, "%s.params.file", path);
	const json_t *jfile = json_is_object(params) ? json_object_get(params, "file") : NULL;
	if (!jfile)
		return bad(err, AA_ERR_INVALID, where, "missing: a user method names its method file, "
			   "{\"name\": \"user\", \"params\": {\"file\": \"my_aa.json\"}}");
	if (get_string(jfile, where, false, file, sizeof file, err) < 0)
		return -1;
	if (strchr(file, ','))
		return bad(err, AA_ERR_INVALID, where, "a method file name cannot hold ',' (it could not be written as "
			   "a method string)");
	struct aa_user_method *um;
	if (aa_user_method_load(file, files, path, &um, err))
		return -1;
	ms->method = &um->method;
	aa_method_defaults(ms->method, &ms->params);
	const char *key;
	json_t *value;
	json_object_foreach((json_t *)params, key, value) {
		char k[64];
		if (!strcmp(key, "file"))
			continue;
		snprintf(where, sizeof where, "%s.params.%s", path, aa_shown_text(key, k, sizeof k));
		if (param_value_text(value, where, text, sizeof text, err) < 0 ||
		    aa_method_set_param(ms->method, &ms->params, key, text, where, err) < 0)
			return -1;
	}
	return 0;
}

/* A method string that starts with "user" names a method file: "user:file=my_aa.json,strength=0.5". */
static bool is_user_text(const char *text)
{
	while (isspace((unsigned char)*text))
		text++;
	if (strncmp(text, "user", 4))
		return false;
	text += 4;
	while (isspace((unsigned char)*text))
		text++;
	return *text == ':' || *text == '\0';
}

bool aa_job_method_is_user(const json_t *method)
{
	if (json_is_string(method))
		return is_user_text(json_string_value(method));
	const json_t *name = json_object_get(method, "name");
	return json_is_object(method) && json_is_string(name) && !strcmp(json_string_value(name), "user");
}

/* {"name": "ssaa", "params": {"samples": 16}} */
static int parse_method_object(const json_t *obj, const char *path, const struct aa_file_source *files,
			       struct aa_method_spec *ms, struct aa_error *err)
{
	char where[300], name[64], text[AA_METHOD_TEXT_MAX], known[512];
	if (check_keys(obj, path, method_keys, err) < 0)
		return -1;
	const json_t *jname = json_object_get(obj, "name");
	snprintf(where, sizeof where, "%s.name", path);
	if (!jname)
		return bad(err, AA_ERR_INVALID, where, "missing; give the method name, e.g. \"ssaa\"");
	if (get_string(jname, where, false, name, sizeof name, err) < 0)
		return -1;
	if (strchr(name, ':'))
		return bad(err, AA_ERR_INVALID, where,
			   "\"%s\" is a method string; in the object form give the bare name and put parameters in "
			   "\"params\"", name);
	const json_t *params = json_object_get(obj, "params");
	if (!strcmp(name, "user"))
		return parse_user_object(params, path, files, ms, err);
	ms->method = aa_method_find(name);
	if (!ms->method) {
		char mean[96];
		aa_method_suggest(name, mean, sizeof mean);
		aa_method_list_names(known, sizeof known);
		return bad(err, AA_ERR_NOT_FOUND, where, "unknown method \"%s\"%s; known methods: %s",
			   aa_shown_text(name, text, sizeof text), mean, known);
	}
	aa_method_defaults(ms->method, &ms->params);

	if (!params)
		return 0;
	snprintf(where, sizeof where, "%s.params", path);
	if (!json_is_object(params))
		return bad(err, AA_ERR_INVALID, where, "expected an object of parameter values, got %s",
			   aa_json_type_name(params));
	const char *key;
	json_t *value;
	json_object_foreach((json_t *)params, key, value) {
		char k[64];
		snprintf(where, sizeof where, "%s.params.%s", path, aa_shown_text(key, k, sizeof k));
		if (param_value_text(value, where, text, sizeof text, err) < 0 ||
		    aa_method_set_param(ms->method, &ms->params, key, text, where, err) < 0)
			return -1;
	}
	return 0;
}

/* One method of the job from one configuration of methods[i] (path): its slot ms, and its label. */
static int parse_method_item(const json_t *item, const char *path, const struct aa_file_source *files,
			     struct aa_method_spec *ms, struct aa_error *err)
{
	char label[AA_METHOD_TEXT_MAX];
	ms->method = NULL; /* each slot holds a reference once parsed; see release_methods */
	if (json_is_string(item) && is_user_text(json_string_value(item))) {
		const char *colon = strchr(json_string_value(item), ':');
		if (aa_user_method_parse(colon ? colon + 1 : "", files, path, &ms->method, &ms->params, err) < 0)
			return -1;
	} else if (json_is_string(item)) {
		if (aa_method_parse(json_string_value(item), path, &ms->method, &ms->params, err) < 0)
			return -1;
	} else if (json_is_object(item)) {
		if (parse_method_object(item, path, files, ms, err) < 0)
			return -1;
	} else {
		return bad(err, AA_ERR_INVALID, path,
			   "expected a method string (\"ssaa:16\") or an object {\"name\": ..., \"params\": {...}}, "
			   "got %s", aa_json_type_name(item));
	}
	aa_method_label(ms->method, &ms->params, label, sizeof label);
	if (strlen(label) >= sizeof ms->label)
		return bad(err, AA_ERR_LIMIT, path, "label \"%.60s...\" is longer than %zu bytes", label,
			   sizeof ms->label - 1);
	memcpy(ms->label, label, strlen(label) + 1);
	return 0;
}

static int parse_methods(const json_t *v, const struct aa_file_source *files, struct aa_job_spec *s,
			 struct aa_error *err)
{
	if (!json_is_array(v))
		return bad(err, AA_ERR_INVALID, "methods", "expected an array of methods, got %s", aa_json_type_name(v));
	const size_t n = json_array_size(v);
	if (n == 0)
		return bad(err, AA_ERR_INVALID, "methods", "the list is empty; give at least one method, e.g. [\"none\"]");
	if (n > AA_MAX_METHODS)
		return bad(err, AA_ERR_LIMIT, "methods", "%zu methods; a job compares at most %d", n, AA_MAX_METHODS);

	/* count: the methods so far, each configuration of a sweep one; item_of[k]: the job's methods[] item
	 * that method k came from, for the errors */
	int count = 0;
	size_t item_of[AA_MAX_METHODS];
	s->method_count = 0;
	for (size_t i = 0; i < n; i++) {
		char path[32];
		snprintf(path, sizeof path, "methods[%zu]", i);
		json_t *configs = aa_method_sweep_expand(json_array_get(v, i), path, AA_MAX_METHODS - count, err);
		if (!configs)
			return -1;
		if (count + (int)json_array_size(configs) > AA_MAX_METHODS) { /* an item that is no sweep, past a sweep */
			json_decref(configs);
			return bad(err, AA_ERR_LIMIT, path, "the job has %d method%s before this one, its sweeps counted by "
				   "configuration; a job compares at most %d", count, count == 1 ? "" : "s", AA_MAX_METHODS);
		}
		const bool sweep = json_array_size(configs) > 1;
		for (size_t c = 0; c < json_array_size(configs); c++) {
			struct aa_method_spec *ms = &s->methods[count];
			const int rc = parse_method_item(json_array_get(configs, c), path, files, ms, err);
			s->method_count = ++count; /* the slot may hold a reference even on an error */
			if (rc < 0) {
				json_decref(configs);
				return -1;
			}
			item_of[count - 1] = i;
			/* Equal labels mean equal parameters: the same work twice, and results that cannot be told apart. */
			for (int j = 0; j < count - 1; j++) {
				if (strcmp(s->methods[j].label, ms->label) != 0)
					continue;
				json_decref(configs);
				const struct aa_user_method *a = aa_user_method_of(s->methods[j].method),
							    *b = aa_user_method_of(ms->method);
				if (a && b && strcmp(a->sha256, b->sha256) != 0)
					return bad(err, AA_ERR_INVALID, path, "%s and methods[%zu] (%s) are different user methods "
						   "with the same label %s: give each method file its own \"name\"", b->file,
						   item_of[j], a->file, ms->label);
				if (item_of[j] == i)
					return bad(err, AA_ERR_INVALID, path, "the sweep names %s twice (a value listed twice, "
						   "or written two ways); list each value once", ms->label);
				return bad(err, AA_ERR_INVALID, path, "same method and parameters as methods[%zu] (%s)%s; "
					   "list it once", item_of[j], ms->label, sweep ? ", which this sweep also names" : "");
			}
		}
		json_decref(configs);
	}
	return 0;
}

static int parse_reference(const json_t *v, struct aa_job_spec *s, struct aa_error *err)
{
	if (!json_is_object(v))
		return bad(err, AA_ERR_INVALID, "reference", "expected an object like {\"samples\": 64}, got %s",
			   aa_json_type_name(v));
	if (check_keys(v, "reference", reference_keys, err) < 0)
		return -1;
	const json_t *samples = json_object_get(v, "samples");
	const json_t *target = json_object_get(v, "target_psnr"), *cap = json_object_get(v, "max_samples");
	if (json_is_string(samples)) {
		if (strcmp(json_string_value(samples), "auto") != 0)
			return bad(err, AA_ERR_INVALID, "reference.samples",
				   "expected an even integer or \"auto\", got the string \"%.32s\"",
				   json_string_value(samples));
		s->reference_auto = true;
		s->reference_target_psnr = AA_REFERENCE_AUTO_TARGET_PSNR;
		s->reference_samples = AA_REFERENCE_AUTO_MAX_SAMPLES;
		if (target) {
			if (!json_is_number(target))
				return bad(err, AA_ERR_INVALID, "reference.target_psnr", "expected a number of dB, got %s",
					   aa_json_type_name(target));
			const double t = json_number_value(target);
			if (!(t >= 20.0 && t <= 80.0))
				return bad(err, AA_ERR_INVALID, "reference.target_psnr",
					   "%g is out of range; valid range: 20 to 80 dB", t);
			s->reference_target_psnr = t;
		}
		/* doubling from 8 reaches the cap exactly when it is a power of two */
		if (cap && get_int(cap, "reference.max_samples", 8, AA_MAX_REFERENCE_SAMPLES, &s->reference_samples,
				   err) < 0)
			return -1;
		if (s->reference_samples & (s->reference_samples - 1))
			return bad(err, AA_ERR_INVALID, "reference.max_samples",
				   "%d is not a power of two; N doubles from 8 up to it", s->reference_samples);
		return 0;
	}
	if (target || cap)
		return bad(err, AA_ERR_INVALID, target ? "reference.target_psnr" : "reference.max_samples",
			   "applies only with \"samples\": \"auto\"");
	if (!samples)
		return 0;
	s->reference_auto = false;
	if (get_int(samples, "reference.samples", 2, AA_MAX_REFERENCE_SAMPLES, &s->reference_samples, err) < 0)
		return -1;
	if (s->reference_samples % 2 != 0)
		return bad(err, AA_ERR_INVALID, "reference.samples",
			   "%d is odd; the count must be even because the first half (N/2 samples) is compared "
			   "with all N to measure the reference's convergence", s->reference_samples);
	return 0;
}

static int parse_timing(const json_t *v, struct aa_job_spec *s, struct aa_error *err)
{
	if (!json_is_object(v))
		return bad(err, AA_ERR_INVALID, "timing", "expected an object like {\"repeat\": 5}, got %s",
			   aa_json_type_name(v));
	if (check_keys(v, "timing", timing_keys, err) < 0)
		return -1;
	const json_t *repeat = json_object_get(v, "repeat");
	if (json_is_string(repeat) && !strcmp(json_string_value(repeat), "auto")) {
		s->timing_auto = true;
		return 0;
	}
	if (json_is_string(repeat))
		return bad(err, AA_ERR_INVALID, "timing.repeat", "expected an integer or \"auto\", got the string "
			   "\"%.32s\"", json_string_value(repeat));
	if (repeat && get_int(repeat, "timing.repeat", 1, AA_MAX_REPEAT, &s->timing_repeat, err) < 0)
		return -1;
	s->timing_auto = s->timing_auto && !repeat;
	return 0;
}

/* shard.warmup: frames a shard renders before its first scored one (docs/farm.md, "Warm-up") */
static int parse_shard(const json_t *v, struct aa_job_spec *s, struct aa_error *err)
{
	if (!json_is_object(v))
		return bad(err, AA_ERR_INVALID, "shard", "expected an object like {\"warmup\": 16}, got %s",
			   aa_json_type_name(v));
	if (check_keys(v, "shard", shard_keys, err) < 0)
		return -1;
	const json_t *warmup = json_object_get(v, "warmup");
	if (warmup && get_int(warmup, "shard.warmup", 0, AA_MAX_SHARD_WARMUP, &s->shard_warmup, err) < 0)
		return -1;
	return 0;
}

void aa_job_spec_defaults(struct aa_job_spec *spec)
{
	memset(spec, 0, sizeof *spec);
	snprintf(spec->scene, sizeof spec->scene, "thin-wires");
	snprintf(spec->path, sizeof spec->path, "default");
	spec->width = 640;
	spec->height = 360;
	spec->frames = 1;
	spec->first_frame = 0;
	spec->reference_samples = 64;
	spec->timing_repeat = 1; /* a spec made in code times once; a job parsed from JSON defaults to "auto" */
	spec->keep_frames = true;
	spec->over_threshold = AA_OVER_THRESHOLD_DEFAULT;
	spec->viewer = true;
	spec->inject_nonfinite_frame = -1;
	spec->shard_warmup = -1;
	/* the default comparison: no AA against 16x supersampling */
	const char *defaults[] = {"none", "ssaa"};
	for (int i = 0; i < 2; i++) {
		struct aa_method_spec *m = &spec->methods[spec->method_count];
		m->method = aa_method_find(defaults[i]);
		if (!m->method)
			continue;
		aa_method_defaults(m->method, &m->params);
		aa_method_label(m->method, &m->params, m->label, sizeof m->label);
		spec->method_count++;
	}
}

/* User methods hold a reference in every slot parse_methods filled; built-in methods hold none. */
static void release_methods(struct aa_job_spec *s)
{
	for (int i = 0; i < AA_MAX_METHODS; i++)
		if (aa_method_is_user(s->methods[i].method)) {
			aa_method_unref(s->methods[i].method);
			s->methods[i].method = NULL;
		}
}

void aa_job_spec_release(struct aa_job_spec *spec)
{
	release_methods(spec);
}

void aa_job_spec_retain(const struct aa_job_spec *spec)
{
	for (int i = 0; i < AA_MAX_METHODS; i++)
		aa_method_ref(spec->methods[i].method);
}

static int parse_job(const json_t *job, const struct aa_file_source *files, struct aa_job_spec *spec,
		     struct aa_error *err);

int aa_job_spec_from_json(const json_t *job, struct aa_job_spec *spec, struct aa_error *err)
{
	return aa_job_spec_from_json_files(job, NULL, spec, err);
}

int aa_job_spec_from_json_files(const json_t *job, const struct aa_file_source *files, struct aa_job_spec *spec,
				struct aa_error *err)
{
	/* Parse into a copy so that a refused job leaves *spec as it was. */
	struct aa_job_spec s;
	aa_job_spec_defaults(&s);
	s.timing_auto = true; /* timing.repeat "auto" unless the job says otherwise */
	if (parse_job(job, files, &s, err) < 0) {
		release_methods(&s);
		return -1;
	}
	*spec = s;
	return 0;
}

static int parse_job(const json_t *job, const struct aa_file_source *files, struct aa_job_spec *spec,
		     struct aa_error *err)
{
	struct aa_job_spec s = *spec;
	if (!json_is_object(job))
		return bad(err, AA_ERR_INVALID, "", "a job must be a JSON object, got %s",
			   job ? aa_json_type_name(job) : "nothing");
	if (check_keys(job, "", job_keys, err) < 0)
		return -1;

	const json_t *v;
	if ((v = json_object_get(job, "scene")) &&
	    (get_string(v, "scene", false, s.scene, sizeof s.scene, err) < 0 || check_scene_syntax(s.scene, "scene", err) < 0))
		return -1;
	if ((v = json_object_get(job, "path")) && get_string(v, "path", false, s.path, sizeof s.path, err) < 0)
		return -1;
	if ((v = json_object_get(job, "size"))) {
		if (json_object_get(job, "width") || json_object_get(job, "height"))
			return bad(err, AA_ERR_INVALID, "size", "give either \"size\" or \"width\"/\"height\", not both");
		if (parse_size_value(v, &s, err) < 0)
			return -1;
	}
	if ((v = json_object_get(job, "width")) && get_int(v, "width", 1, AA_MAX_SIZE, &s.width, err) < 0)
		return -1;
	if ((v = json_object_get(job, "height")) && get_int(v, "height", 1, AA_MAX_SIZE, &s.height, err) < 0)
		return -1;
	if ((v = json_object_get(job, "frames")) && get_int(v, "frames", 1, AA_MAX_FRAMES, &s.frames, err) < 0)
		return -1;
	if ((v = json_object_get(job, "first_frame")) &&
	    get_int(v, "first_frame", 0, AA_MAX_FIRST_FRAME, &s.first_frame, err) < 0)
		return -1;
	if ((v = json_object_get(job, "reference")) && parse_reference(v, &s, err) < 0)
		return -1;
	if ((v = json_object_get(job, "methods")) && parse_methods(v, files, &s, err) < 0) {
		*spec = s; /* the references taken so far, for the caller to release */
		return -1;
	}
	*spec = s; /* from here on every method's reference is in *spec */
	if ((v = json_object_get(job, "keep_frames"))) {
		if (!json_is_boolean(v))
			return bad(err, AA_ERR_INVALID, "keep_frames", "expected true or false, got %s", aa_json_type_name(v));
		s.keep_frames = json_is_true(v);
	}
	if ((v = json_object_get(job, "linear_frames"))) {
		if (!json_is_boolean(v))
			return bad(err, AA_ERR_INVALID, "linear_frames", "expected true or false, got %s", aa_json_type_name(v));
		s.linear_frames = json_is_true(v);
	}
	if ((v = json_object_get(job, "exr_frames"))) {
		if (!json_is_boolean(v))
			return bad(err, AA_ERR_INVALID, "exr_frames", "expected true or false, got %s", aa_json_type_name(v));
		s.exr_frames = json_is_true(v);
		if (s.exr_frames && !s.keep_frames)
			return bad(err, AA_ERR_INVALID, "exr_frames", "EXR frames are images: they need keep_frames true");
	}
	if ((v = json_object_get(job, "viewer"))) {
		if (!json_is_boolean(v))
			return bad(err, AA_ERR_INVALID, "viewer", "expected true or false, got %s", aa_json_type_name(v));
		s.viewer = json_is_true(v);
	}
	if ((v = json_object_get(job, "debug_targets"))) {
		if (!json_is_boolean(v))
			return bad(err, AA_ERR_INVALID, "debug_targets", "expected true or false, got %s", aa_json_type_name(v));
		s.debug_targets = json_is_true(v);
	}
	if ((v = json_object_get(job, "over_threshold"))) {
		if (!json_is_number(v) || !(json_number_value(v) >= 0.0 && json_number_value(v) <= 1.0))
			return bad(err, AA_ERR_INVALID, "over_threshold", "expected a number from 0 to 1 (a share of full "
				   "scale), got %s", json_is_number(v) ? "a number out of range" : aa_json_type_name(v));
		s.over_threshold = json_number_value(v);
	}
	if ((v = json_object_get(job, "name")) && get_string(v, "name", true, s.name, sizeof s.name, err) < 0)
		return -1;
	if ((v = json_object_get(job, "timing")) && parse_timing(v, &s, err) < 0)
		return -1;
	if ((v = json_object_get(job, "shard")) && parse_shard(v, &s, err) < 0)
		return -1;
	if (s.timing_auto) /* a suite's cases each get their own (aa_job_case) */
		s.timing_repeat = aa_timing_auto_repeat(s.frames);
	/* every timed render keeps its pass times: bound them as frames alone are bounded */
	if ((long)s.frames * s.timing_repeat > AA_MAX_FRAMES)
		return bad(err, AA_ERR_LIMIT, "timing.repeat", "%d frames x %d repeats is over %d timed renders per "
			   "method; lower frames or timing.repeat", s.frames, s.timing_repeat, AA_MAX_FRAMES);
	if (aa_job_suite_from_json(job, &s, err) < 0)
		return -1;
	*spec = s;
	return 0;
}

/* The canonical form: every field present, size as text and methods as their labels, which parse back
 * to the same parameters (user methods as "user:file=FILE,..." strings, which read the same file). */
json_t *aa_job_spec_to_json(const struct aa_job_spec *spec)
{
	char size[32];
	snprintf(size, sizeof size, "%dx%d", spec->width, spec->height);
	json_t *methods = json_array();
	for (int i = 0; methods && i < spec->method_count && i < AA_MAX_METHODS; i++) {
		/* a user method's label is its file's name; the string that reads it again names the file */
		char text[AA_METHOD_TEXT_MAX];
		const struct aa_method_spec *ms = &spec->methods[i];
		if (aa_method_is_user(ms->method))
			aa_user_method_spec_text(ms->method, &ms->params, text, sizeof text);
		json_array_append_new(methods, json_string(aa_method_is_user(ms->method) ? text : ms->label));
	}
	json_t *job = json_pack("{s:s, s:s, s:s, s:i, s:i, s:{s:i}, s:o?, s:b, s:b, s:s, s:{s:i}}",
				"scene", spec->scene, "path", spec->path, "size", size, "frames", spec->frames,
				"first_frame", spec->first_frame, "reference", "samples", spec->reference_samples,
				"methods", methods, "keep_frames", spec->keep_frames, "linear_frames",
				spec->linear_frames, "name", spec->name, "timing", "repeat", spec->timing_repeat);
	if (job && spec->reference_auto)
		json_object_set_new(job, "reference", json_pack("{s:s, s:f, s:i}", "samples", "auto", "target_psnr",
								spec->reference_target_psnr, "max_samples",
								spec->reference_samples));
	if (job && spec->is_suite && spec->timing_auto) /* each case's repeat follows from its frames */
		json_object_set_new(job, "timing", json_pack("{s:s}", "repeat", "auto"));
	aa_job_suite_to_json(spec, job);
	if (job && spec->shard_warmup >= 0) /* only when given: the canonical form of other jobs is as before */
		json_object_set_new(job, "shard", json_pack("{s:i}", "warmup", spec->shard_warmup));
	/* likewise: only when not the default, so that earlier jobs keep their canonical form and hash */
	if (job && spec->exr_frames)
		json_object_set_new(job, "exr_frames", json_true());
	if (job && !spec->viewer)
		json_object_set_new(job, "viewer", json_false());
	if (job && spec->debug_targets)
		json_object_set_new(job, "debug_targets", json_true());
	if (job && spec->over_threshold != AA_OVER_THRESHOLD_DEFAULT)
		json_object_set_new(job, "over_threshold", json_real(spec->over_threshold));
	return job;
}

/* The checks above, for the suite keys (engine/run/job_suite.c). */
int aa_job_parse_int(const json_t *v, const char *path, long long min, long long max, int *out, struct aa_error *err)
{
	return get_int(v, path, min, max, out, err);
}

int aa_job_parse_string(const json_t *v, const char *path, bool allow_empty, char *out, size_t size,
			struct aa_error *err)
{
	return get_string(v, path, allow_empty, out, size, err);
}

int aa_job_parse_keys(const json_t *obj, const char *path, const char *const *valid, struct aa_error *err)
{
	return check_keys(obj, path, valid, err);
}

int aa_job_parse_scene(const char *scene, const char *path, struct aa_error *err)
{
	return check_scene_syntax(scene, path, err);
}

int aa_timing_auto_repeat(int frames)
{
	if (frames < 1)
		frames = 1;
	const int repeat = (AA_MIN_TIMED_RENDERS + frames - 1) / frames;
	return repeat < 1 ? 1 : repeat > AA_MAX_REPEAT ? AA_MAX_REPEAT : repeat;
}
