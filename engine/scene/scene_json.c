/* Scene-file validation helpers: typed readers with ranges and defaults that report the JSON path. */
#include "scene/scene_json.h"

#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image/image.h"
#include "util/suggest.h"

void sj_init(struct sj *s, const char *file, struct aa_error *err)
{
	s->err = err;
	snprintf(s->file, sizeof s->file, "%s", file ? file : "");
	s->path[0] = '\0';
	s->len = 0;
}

size_t sj_push_key(struct sj *s, const char *key)
{
	size_t mark = s->len;
	int n = snprintf(s->path + s->len, sizeof s->path - s->len, "%s%s", s->len ? "." : "", key);
	if (n > 0)
		s->len = strlen(s->path);
	return mark;
}

size_t sj_push_index(struct sj *s, size_t index)
{
	size_t mark = s->len;
	int n = snprintf(s->path + s->len, sizeof s->path - s->len, "[%zu]", index);
	if (n > 0)
		s->len = strlen(s->path);
	return mark;
}

void sj_pop(struct sj *s, size_t mark)
{
	if (mark <= s->len) {
		s->len = mark;
		s->path[mark] = '\0';
	}
}

static int sj_vfail(struct sj *s, enum aa_error_code code, const char *fmt, va_list ap)
{
	char msg[600];
	vsnprintf(msg, sizeof msg, fmt, ap);
	const char *sep1 = s->file[0] ? ": " : "";
	const char *sep2 = s->path[0] ? ": " : "";
	return aa_error_set(s->err, code, s->path, "%s%s%s%s%s", s->file, sep1, s->path, sep2, msg);
}

int sj_fail(struct sj *s, enum aa_error_code code, const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	sj_vfail(s, code, fmt, ap);
	va_end(ap);
	return -1;
}

int sj_fail_key(struct sj *s, const char *key, enum aa_error_code code, const char *fmt, ...)
{
	size_t mark = sj_push_key(s, key);
	va_list ap;
	va_start(ap, fmt);
	sj_vfail(s, code, fmt, ap);
	va_end(ap);
	sj_pop(s, mark);
	return -1;
}

const char *sj_describe(const json_t *v, char *buf, size_t size)
{
	if (!v)
		snprintf(buf, size, "nothing");
	else if (json_is_integer(v))
		snprintf(buf, size, "%lld", (long long)json_integer_value(v));
	else if (json_is_real(v))
		snprintf(buf, size, "%g", json_real_value(v));
	else if (json_is_string(v)) {
		const char *str = json_string_value(v);
		snprintf(buf, size, "\"%.40s%s\"", str, strlen(str) > 40 ? "..." : "");
	} else if (json_is_true(v))
		snprintf(buf, size, "true");
	else if (json_is_false(v))
		snprintf(buf, size, "false");
	else if (json_is_null(v))
		snprintf(buf, size, "null");
	else if (json_is_object(v))
		snprintf(buf, size, "an object");
	else
		snprintf(buf, size, "an array of %zu", json_array_size(v));
	return buf;
}

void sj_list_keys(const json_t *obj, char *buf, size_t size)
{
	size_t used = 0;
	const char *key;
	json_t *value;
	buf[0] = '\0';
	json_object_foreach((json_t *)obj, key, value) {
		(void)value;
		int n = snprintf(buf + used, size - used, "%s%s", used ? ", " : "", key);
		if (n < 0 || (size_t)n >= size - used)
			break;
		used += (size_t)n;
	}
	if (!used)
		snprintf(buf, size, "none");
}

int sj_expect_object(struct sj *s, const json_t *v)
{
	char got[64];
	if (json_is_object(v))
		return 0;
	return sj_fail(s, AA_ERR_INVALID, "expected an object, got %s", sj_describe(v, got, sizeof got));
}

int sj_check_keys(struct sj *s, const json_t *obj, const char *const *valid)
{
	if (sj_expect_object(s, obj))
		return -1;
	const char *key;
	json_t *value;
	json_object_foreach((json_t *)obj, key, value) {
		(void)value;
		bool ok = strcmp(key, "comment") == 0;
		for (int i = 0; valid[i] && !ok; i++)
			ok = strcmp(key, valid[i]) == 0;
		if (ok)
			continue;
		char list[400];
		size_t used = 0;
		for (int i = 0; valid[i]; i++) {
			int n = snprintf(list + used, sizeof list - used, "%s%s", i ? ", " : "", valid[i]);
			if (n > 0 && (size_t)n < sizeof list - used)
				used += (size_t)n;
		}
		const char *suggest = aa_suggest(key, valid, -1);
		if (suggest)
			return sj_fail_key(s, key, AA_ERR_INVALID, "unknown key '%s' (did you mean '%s'? valid keys: %s)",
					   key, suggest, list);
		return sj_fail_key(s, key, AA_ERR_INVALID, "unknown key '%s' (valid keys: %s)", key, list);
	}
	return 0;
}

int sj_require(struct sj *s, const json_t *obj, const char *key)
{
	if (json_object_get(obj, key))
		return 0;
	return sj_fail_key(s, key, AA_ERR_INVALID, "missing required key '%s'", key);
}

static void range_text(struct sj_range r, char *buf, size_t size)
{
	bool no_min = r.min <= -SJ_MAX_ABS, no_max = r.max >= SJ_MAX_ABS;
	if (no_min && no_max)
		snprintf(buf, size, "a number");
	else if (r.min == 0.0 && no_max)
		snprintf(buf, size, "%s", r.min_open ? "a positive number" : "a non-negative number");
	else if (no_max)
		snprintf(buf, size, "a number %s %g", r.min_open ? ">" : ">=", r.min);
	else if (r.min > 0.0 || (r.min == 0.0 && r.min_open))
		snprintf(buf, size, "a positive number in %c%g, %g%c", r.min_open ? '(' : '[', r.min, r.max,
			 r.max_open ? ')' : ']');
	else
		snprintf(buf, size, "a number in %c%g, %g%c", r.min_open ? '(' : '[', r.min, r.max,
			 r.max_open ? ')' : ']');
}

static bool in_range(double x, struct sj_range r)
{
	if (!isfinite(x) || fabs(x) > SJ_MAX_ABS)
		return false;
	if (r.min_open ? !(x > r.min) : !(x >= r.min))
		return false;
	return r.max_open ? x < r.max : x <= r.max;
}

/* Reads one number value (not a field) at the current path. */
static int number_value(struct sj *s, const json_t *v, struct sj_range r, double *out)
{
	char want[80], got[64];
	if (json_is_number(v) && in_range(json_number_value(v), r)) {
		*out = json_number_value(v);
		return 0;
	}
	double x = json_is_number(v) ? json_number_value(v) : 0.0;
	if ((x > SJ_MAX_ABS && r.max >= SJ_MAX_ABS) || (x < -SJ_MAX_ABS && r.min <= -SJ_MAX_ABS))
		return sj_fail(s, AA_ERR_INVALID, "expected a number no larger than %g in magnitude, got %s", SJ_MAX_ABS,
			       sj_describe(v, got, sizeof got));
	range_text(r, want, sizeof want);
	return sj_fail(s, AA_ERR_INVALID, "expected %s, got %s", want, sj_describe(v, got, sizeof got));
}

int sj_number(struct sj *s, const json_t *obj, const char *key, struct sj_range r, double def, double *out)
{
	const json_t *v = json_object_get(obj, key);
	if (!v) {
		*out = def;
		return 0;
	}
	size_t mark = sj_push_key(s, key);
	int rc = number_value(s, v, r, out);
	sj_pop(s, mark);
	return rc;
}

int sj_float(struct sj *s, const json_t *obj, const char *key, struct sj_range r, float def, float *out)
{
	double d;
	if (sj_number(s, obj, key, r, def, &d))
		return -1;
	*out = (float)d;
	return 0;
}

static int int_value(struct sj *s, const json_t *v, int min, int max, int *out)
{
	char got[64];
	double d = json_is_number(v) ? json_number_value(v) : NAN;
	if (isfinite(d) && d == floor(d) && d >= min && d <= max) {
		*out = (int)d;
		return 0;
	}
	return sj_fail(s, AA_ERR_INVALID, "expected an integer in [%d, %d], got %s", min, max,
		       sj_describe(v, got, sizeof got));
}

int sj_int(struct sj *s, const json_t *obj, const char *key, int min, int max, int def, int *out)
{
	const json_t *v = json_object_get(obj, key);
	if (!v) {
		*out = def;
		return 0;
	}
	size_t mark = sj_push_key(s, key);
	int rc = int_value(s, v, min, max, out);
	sj_pop(s, mark);
	return rc;
}

int sj_bool(struct sj *s, const json_t *obj, const char *key, bool def, bool *out)
{
	const json_t *v = json_object_get(obj, key);
	char got[64];
	if (!v) {
		*out = def;
		return 0;
	}
	if (!json_is_boolean(v))
		return sj_fail_key(s, key, AA_ERR_INVALID, "expected true or false, got %s",
				   sj_describe(v, got, sizeof got));
	*out = json_is_true(v);
	return 0;
}

int sj_string(struct sj *s, const json_t *obj, const char *key, const char *def, char *out, size_t size)
{
	const json_t *v = json_object_get(obj, key);
	char got[64];
	if (!v) {
		snprintf(out, size, "%s", def ? def : "");
		return 0;
	}
	if (!json_is_string(v))
		return sj_fail_key(s, key, AA_ERR_INVALID, "expected a string, got %s", sj_describe(v, got, sizeof got));
	if (json_string_length(v) >= size || strlen(json_string_value(v)) != json_string_length(v))
		return sj_fail_key(s, key, AA_ERR_INVALID, "string too long or contains NUL (at most %zu characters)",
				   size - 1);
	memcpy(out, json_string_value(v), json_string_length(v) + 1);
	return 0;
}

int sj_enum(struct sj *s, const json_t *obj, const char *key, const char *const *names, int def, int *out)
{
	const json_t *v = json_object_get(obj, key);
	if (!v) {
		*out = def;
		return 0;
	}
	if (json_is_string(v))
		for (int i = 0; names[i]; i++)
			if (strcmp(json_string_value(v), names[i]) == 0) {
				*out = i;
				return 0;
			}
	char list[300], got[64];
	size_t used = 0;
	list[0] = '\0';
	for (int i = 0; names[i]; i++) {
		int n = snprintf(list + used, sizeof list - used, "%s%s", i ? ", " : "", names[i]);
		if (n > 0 && (size_t)n < sizeof list - used)
			used += (size_t)n;
	}
	if (json_is_string(v))
		return sj_fail_key(s, key, AA_ERR_INVALID, "unknown value '%.60s' (expected one of: %s)",
				   json_string_value(v), list);
	return sj_fail_key(s, key, AA_ERR_INVALID, "expected one of: %s; got %s", list,
			   sj_describe(v, got, sizeof got));
}

/* An array of exactly n numbers (n > 1), or with allow_scalar a single number for all. */
static int numbers_value(struct sj *s, const json_t *v, int n, bool allow_scalar, struct sj_range r, double *out)
{
	char got[64], want[80];
	if (allow_scalar && json_is_number(v)) {
		if (number_value(s, v, r, &out[0]))
			return -1;
		for (int i = 1; i < n; i++)
			out[i] = out[0];
		return 0;
	}
	if (!json_is_array(v) || json_array_size(v) != (size_t)n) {
		range_text(r, want, sizeof want);
		bool any = strcmp(want, "a number") == 0;
		return sj_fail(s, AA_ERR_INVALID, "expected %san array of %d numbers%s%s%s, got %s",
			       allow_scalar ? "a number or " : "", n, any ? "" : " (each ", any ? "" : want, any ? "" : ")",
			       sj_describe(v, got, sizeof got));
	}
	for (int i = 0; i < n; i++) {
		size_t mark = sj_push_index(s, (size_t)i);
		int rc = number_value(s, json_array_get(v, (size_t)i), r, &out[i]);
		sj_pop(s, mark);
		if (rc)
			return -1;
	}
	return 0;
}

int sj_vec3_value(struct sj *s, const json_t *v, struct sj_range r, vec3 *out)
{
	double d[3];
	if (numbers_value(s, v, 3, false, r, d))
		return -1;
	*out = v3((float)d[0], (float)d[1], (float)d[2]);
	return 0;
}

int sj_vec3(struct sj *s, const json_t *obj, const char *key, struct sj_range r, vec3 def, vec3 *out)
{
	const json_t *v = json_object_get(obj, key);
	double d[3];
	if (!v) {
		*out = def;
		return 0;
	}
	size_t mark = sj_push_key(s, key);
	int rc = numbers_value(s, v, 3, false, r, d);
	sj_pop(s, mark);
	if (rc)
		return -1;
	*out = v3((float)d[0], (float)d[1], (float)d[2]);
	return 0;
}

/* As sj_vec3 in double: world positions, which floats would round to 1/16 unit at 600,000 (the
 * renderer subtracts the camera's position from them before they become floats). */
int sj_dvec3(struct sj *s, const json_t *obj, const char *key, struct sj_range r, const double def[3], double out[3])
{
	const json_t *v = json_object_get(obj, key);
	if (!v) {
		out[0] = def[0], out[1] = def[1], out[2] = def[2];
		return 0;
	}
	size_t mark = sj_push_key(s, key);
	int rc = numbers_value(s, v, 3, false, r, out);
	sj_pop(s, mark);
	return rc;
}

int sj_floats_or_scalar(struct sj *s, const json_t *obj, const char *key, int n, struct sj_range r,
			const float *def, float *out)
{
	const json_t *v = json_object_get(obj, key);
	double d[4];
	if (!v) {
		for (int i = 0; i < n; i++)
			out[i] = def[i];
		return 0;
	}
	size_t mark = sj_push_key(s, key);
	int rc = numbers_value(s, v, n, true, r, d);
	sj_pop(s, mark);
	if (rc)
		return -1;
	for (int i = 0; i < n; i++)
		out[i] = (float)d[i];
	return 0;
}

int sj_ints_or_scalar(struct sj *s, const json_t *obj, const char *key, int n, int min, int max,
		      const int *def, int *out)
{
	const json_t *v = json_object_get(obj, key);
	if (!v) {
		for (int i = 0; i < n; i++)
			out[i] = def[i];
		return 0;
	}
	size_t mark = sj_push_key(s, key);
	int rc = 0;
	if (json_is_number(v)) {
		rc = int_value(s, v, min, max, &out[0]);
		for (int i = 1; i < n; i++)
			out[i] = out[0];
	} else if (json_is_array(v) && json_array_size(v) == (size_t)n) {
		for (int i = 0; i < n && !rc; i++) {
			size_t m2 = sj_push_index(s, (size_t)i);
			rc = int_value(s, json_array_get(v, (size_t)i), min, max, &out[i]);
			sj_pop(s, m2);
		}
	} else {
		char got[64];
		rc = sj_fail(s, AA_ERR_INVALID, "expected an integer or an array of %d integers in [%d, %d], got %s",
			     n, min, max, sj_describe(v, got, sizeof got));
	}
	sj_pop(s, mark);
	return rc;
}

static int hex_digit(char c)
{
	if (c >= '0' && c <= '9')
		return c - '0';
	if (c >= 'a' && c <= 'f')
		return c - 'a' + 10;
	if (c >= 'A' && c <= 'F')
		return c - 'A' + 10;
	return -1;
}

static int color_value(struct sj *s, const json_t *v, bool with_alpha, float out[4])
{
	char got[64];
	out[3] = 1.0f;
	if (json_is_string(v)) {
		const char *h = json_string_value(v);
		size_t len = strlen(h);
		bool ok = h[0] == '#' && (len == 7 || (with_alpha && len == 9));
		for (size_t i = 1; ok && i < len; i++)
			ok = hex_digit(h[i]) >= 0;
		if (ok) {
			for (size_t c = 0; c < (len - 1) / 2; c++) {
				float byte = (float)(hex_digit(h[1 + 2 * c]) * 16 + hex_digit(h[2 + 2 * c])) / 255.0f;
				out[c] = c < 3 ? aa_srgb_to_linear(byte) : byte;
			}
			return 0;
		}
	} else if (json_is_array(v) && (json_array_size(v) == 3 || (with_alpha && json_array_size(v) == 4))) {
		double d[4];
		if (numbers_value(s, v, (int)json_array_size(v), false, SJ_CLOSED(0.0, 1.0), d))
			return -1;
		for (size_t c = 0; c < json_array_size(v); c++)
			out[c] = (float)d[c];
		return 0;
	}
	return sj_fail(s, AA_ERR_INVALID,
		       "expected a colour: \"#RRGGBB%s\" (sRGB) or [r, g, b%s] (linear, each in [0, 1]), got %s",
		       with_alpha ? "[AA]" : "", with_alpha ? "[, a]" : "", sj_describe(v, got, sizeof got));
}

int sj_color(struct sj *s, const json_t *obj, const char *key, const float def[4], bool with_alpha,
	     float out[4])
{
	const json_t *v = json_object_get(obj, key);
	if (!v) {
		memcpy(out, def, 4 * sizeof(float));
		return 0;
	}
	size_t mark = sj_push_key(s, key);
	int rc = color_value(s, v, with_alpha, out);
	sj_pop(s, mark);
	return rc;
}

int sj_resolve_file(struct sj *s, const char *base_dir, const char *rel, char *out, size_t size)
{
	if (!rel[0])
		return sj_fail(s, AA_ERR_INVALID, "empty file name");
	if (!base_dir)
		return sj_fail(s, AA_ERR_INVALID,
			       "file '%s' cannot be resolved: this scene was not loaded from a directory", rel);
	if (rel[0] == '/' || rel[0] == '\\')
		return sj_fail(s, AA_ERR_INVALID,
			       "absolute paths are not allowed ('%s'): give a path relative to the scene file", rel);
	/* Reject ".." as a whole component anywhere ("a/../b", "../x", "x/.."). */
	for (const char *p = rel; *p;) {
		size_t n = strcspn(p, "/\\");
		if (n == 2 && p[0] == '.' && p[1] == '.')
			return sj_fail(s, AA_ERR_INVALID,
				       "'..' is not allowed in file paths ('%s'): files must stay in the scene's directory",
				       rel);
		p += n;
		if (*p)
			p++;
	}
	char joined[PATH_MAX], real_base[PATH_MAX], real_file[PATH_MAX];
	int n = snprintf(joined, sizeof joined, "%s/%s", base_dir, rel);
	if (n < 0 || (size_t)n >= sizeof joined)
		return sj_fail(s, AA_ERR_INVALID, "file path too long ('%s')", rel);
	if (!realpath(base_dir, real_base))
		return sj_fail(s, AA_ERR_NOT_FOUND, "scene directory '%s' not found", base_dir);
	if (!realpath(joined, real_file))
		return sj_fail(s, AA_ERR_NOT_FOUND, "file '%s' not found in the scene file's folder", rel);
	/* A symlink inside the directory must not lead out of it either. */
	size_t bl = strlen(real_base);
	if (strncmp(real_file, real_base, bl) != 0 || (real_file[bl] != '/' && strcmp(real_base, "/") != 0))
		return sj_fail(s, AA_ERR_INVALID, "file '%s' resolves outside the scene's directory", rel);
	if (strlen(real_file) >= size)
		return sj_fail(s, AA_ERR_INVALID, "file path too long ('%s')", rel);
	memcpy(out, real_file, strlen(real_file) + 1);
	aa_scene_source_read(out);
	return 0;
}

int sj_parse_error(struct aa_error *err, const char *display, const json_error_t *je)
{
	return aa_error_set(err, AA_ERR_INVALID, "", "%s:%d:%d: invalid JSON: %s", display, je->line, je->column,
			    je->text);
}
