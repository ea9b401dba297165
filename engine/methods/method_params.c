/* Parses method strings ("ssaa", "ssaa:16", "fxaa:preset=39,subpix=0.75") against a method's params table
 * and writes the canonical label and the text of each value back. */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "types/method.h"
#include "methods/methods.h"
#include "util/suggest.h"
#include "util/json_text.h"

static bool has_range(const struct aa_param_def *d);

/* Number of entries of m's table that fit in struct aa_method_params. */
static int param_count(const struct aa_method *m)
{
	return m->param_count < AA_MAX_PARAMS ? m->param_count : AA_MAX_PARAMS;
}

/* Copies user text into a message: bounded, control characters shown as '?', so that a message stays
 * one readable line whatever the input. */
static const char *shown(const char *text, char *buf, size_t size)
{
	size_t n = 0;
	const size_t limit = size > 48 ? 48 : size - 1;
	for (; text[n] && n < limit; n++)
		buf[n] = iscntrl((unsigned char)text[n]) ? '?' : text[n];
	if (text[n] && n >= 3) {
		buf[n - 3] = buf[n - 2] = buf[n - 1] = '.';
	}
	buf[n] = '\0';
	return buf;
}

/* Sets err to path and "method: message"; callers print "path: message" as for every aa_error. */
static int __attribute__((format(printf, 5, 6)))
fail(struct aa_error *err, enum aa_error_code code, const char *path, const char *method, const char *fmt, ...)
{
	char msg[640];
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(msg, sizeof msg, fmt, ap);
	va_end(ap);
	return aa_error_set(err, code, path, "%s%s%s", method ? method : "", method ? ": " : "", msg);
}

static void append(char *out, size_t size, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static void append(char *out, size_t size, const char *fmt, ...)
{
	size_t used = strlen(out);
	if (used + 1 >= size)
		return;
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(out + used, size - used, fmt, ap);
	va_end(ap);
}

/* Shortest "%.*g" text that reads back as exactly v, so labels round-trip through the parser. */
static void format_double(double v, char *out, size_t size)
{
	for (int prec = 1; prec <= 17; prec++) {
		snprintf(out, size, "%.*g", prec, v);
		if (strtod(out, NULL) == v)
			return;
	}
}

/* "valid values: 4, 9, 16" or "valid range: 0 to 1": what the user may write for parameter d. */
static void describe_valid(const struct aa_param_def *d, char *out, size_t size)
{
	char a[32], b[32];
	out[0] = '\0';
	switch (d->type) {
	case AA_PARAM_INT:
		if (d->allowed) {
			append(out, size, "valid values: ");
			for (int i = 0; d->allowed[i] != 0; i++)
				append(out, size, "%s%d", i ? ", " : "", d->allowed[i]);
		} else if (has_range(d)) {
			append(out, size, "valid range: %.0f to %.0f (an integer)", d->min, d->max);
		} else {
			append(out, size, "valid values: any integer");
		}
		break;
	case AA_PARAM_FLOAT:
		if (has_range(d)) {
			format_double(d->min, a, sizeof a);
			format_double(d->max, b, sizeof b);
			append(out, size, "valid range: %s to %s", a, b);
		} else {
			append(out, size, "valid values: any decimal number");
		}
		break;
	case AA_PARAM_ENUM:
		append(out, size, "valid values: ");
		for (int i = 0; d->choices && d->choices[i]; i++)
			append(out, size, "%s%s", i ? ", " : "", d->choices[i]);
		break;
	case AA_PARAM_BOOL:
		append(out, size, "valid values: true, false (or 1, 0, yes, no, on, off)");
		break;
	}
}

static void list_param_names(const struct aa_method *m, char *out, size_t size)
{
	out[0] = '\0';
	for (int i = 0; i < param_count(m); i++)
		append(out, size, "%s%s", i ? ", " : "", m->params[i].name);
}

/* Strict integer: optional sign and decimal digits only, no overflow. */
static bool parse_int(const char *s, long long *out)
{
	const char *p = s + (*s == '+' || *s == '-');
	if (!*p)
		return false;
	for (; *p; p++)
		if (!isdigit((unsigned char)*p))
			return false;
	errno = 0;
	*out = strtoll(s, NULL, 10);
	return errno == 0;
}

/* Decimal number only: strtod would also take "nan", "inf" and hex, none of which a parameter means. */
static bool parse_float(const char *s, double *out)
{
	if (!*s || strspn(s, "0123456789+-.eE") != strlen(s))
		return false;
	char *end;
	errno = 0;
	*out = strtod(s, &end);
	return *end == '\0' && errno == 0 && isfinite(*out);
}

static bool parse_bool(const char *s, double *out)
{
	static const char *const yes[] = { "true", "1", "yes", "on" }, *const no[] = { "false", "0", "no", "off" };
	for (size_t i = 0; i < sizeof yes / sizeof yes[0]; i++) {
		if (strcasecmp(s, yes[i]) == 0)
			return *out = 1, true;
		if (strcasecmp(s, no[i]) == 0)
			return *out = 0, true;
	}
	return false;
}

/* A table that leaves min and max at 0 sets no range (an INT with an allowed list needs none). */
static bool has_range(const struct aa_param_def *d)
{
	return d->min != 0 || d->max != 0;
}

/* Converts value to the stored double of parameter d; false when it is not one of the valid values. */
static bool parse_value(const struct aa_param_def *d, const char *value, double *out)
{
	switch (d->type) {
	case AA_PARAM_INT: {
		long long v;
		if (!parse_int(value, &v))
			return false;
		if (!d->allowed && has_range(d) && ((double)v < d->min || (double)v > d->max))
			return false;
		if (d->allowed) {
			int i = 0;
			while (d->allowed[i] != 0 && d->allowed[i] != v)
				i++;
			if (d->allowed[i] == 0)
				return false;
		}
		*out = (double)v;
		return true;
	}
	case AA_PARAM_FLOAT:
		return parse_float(value, out) && (!has_range(d) || (*out >= d->min && *out <= d->max));
	case AA_PARAM_ENUM:
		for (int i = 0; d->choices && d->choices[i]; i++)
			if (strcasecmp(value, d->choices[i]) == 0)
				return *out = i, true;
		return false;
	case AA_PARAM_BOOL:
		return parse_bool(value, out);
	}
	return false;
}

void aa_method_defaults(const struct aa_method *m, struct aa_method_params *params)
{
	memset(params, 0, sizeof *params);
	for (int i = 0; i < param_count(m); i++)
		params->v[i] = m->params[i].def;
}

int aa_method_set_param(const struct aa_method *m, struct aa_method_params *params, const char *key,
			const char *value, const char *path, struct aa_error *err)
{
	char k[64], v[64], valid[512];
	const int i = aa_method_param_index(m, key);
	if (i < 0 || i >= AA_MAX_PARAMS) {
		if (param_count(m) == 0)
			return fail(err, AA_ERR_INVALID, path, m->name, "takes no parameters (got \"%s\")",
				    shown(key, k, sizeof k));
		const char *names[AA_MAX_PARAMS];
		for (int p = 0; p < param_count(m); p++)
			names[p] = m->params[p].name;
		char mean[96];
		aa_suggest_text(key, names, param_count(m), mean, sizeof mean);
		list_param_names(m, valid, sizeof valid);
		return fail(err, AA_ERR_INVALID, path, m->name, "unknown parameter \"%s\"%s; valid parameters: %s",
			    shown(key, k, sizeof k), mean, valid);
	}
	const struct aa_param_def *d = &m->params[i];
	double parsed;
	if (!parse_value(d, value, &parsed)) {
		describe_valid(d, valid, sizeof valid);
		return fail(err, AA_ERR_INVALID, path, m->name, "%s=%s is not valid; %s", d->name,
			    shown(value, v, sizeof v), valid);
	}
	params->v[i] = parsed;
	return 0;
}


int aa_method_parse_params(const struct aa_method *m, const char *list, const char *path,
			   struct aa_method_params *params, struct aa_error *err)
{
	char buf[AA_METHOD_TEXT_MAX], shown_buf[64], names[512];
	aa_method_defaults(m, params);
	if (strlen(list) >= sizeof buf)
		return fail(err, AA_ERR_INVALID, path, m->name, "parameter list is longer than %zu bytes",
			    sizeof buf - 1);
	memcpy(buf, list, strlen(list) + 1);
	if (*aa_trim(buf) == '\0')
		return fail(err, AA_ERR_INVALID, path, m->name,
			    "nothing after ':'; write %s alone for its defaults", m->name);

	bool seen[AA_MAX_PARAMS] = { false };
	char *save = NULL;
	/* strtok_r would skip empty items silently; walk commas by hand so "a=1,,b=2" is reported. */
	for (char *item = buf; item; item = save) {
		char *comma = strchr(item, ',');
		save = comma ? comma + 1 : NULL;
		if (comma)
			*comma = '\0';
		item = aa_trim(item);
		if (*item == '\0')
			return fail(err, AA_ERR_INVALID, path, m->name, "empty item in parameter list");

		const char *key, *value;
		char *eq = strchr(item, '=');
		if (eq) {
			*eq = '\0';
			key = aa_trim(item);
			value = aa_trim(eq + 1);
			if (*key == '\0')
				return fail(err, AA_ERR_INVALID, path, m->name, "missing parameter name before '=%s'",
					    shown(value, shown_buf, sizeof shown_buf));
		} else if (aa_method_param_index(m, item) >= 0) {
			return fail(err, AA_ERR_INVALID, path, m->name, "%s needs a value: write %s=VALUE", item, item);
		} else if (m->main_param) {
			key = m->main_param; /* a bare value sets the main parameter ("ssaa:16") */
			value = item;
		} else if (param_count(m) == 0) {
			return fail(err, AA_ERR_INVALID, path, m->name, "takes no parameters (got \"%s\")",
				    shown(item, shown_buf, sizeof shown_buf));
		} else {
			list_param_names(m, names, sizeof names);
			return fail(err, AA_ERR_INVALID, path, m->name,
				    "has no main parameter, so \"%s\" needs a name: write key=value with one of: %s",
				    shown(item, shown_buf, sizeof shown_buf), names);
		}

		const int i = aa_method_param_index(m, key);
		if (i >= 0 && i < AA_MAX_PARAMS && seen[i])
			return fail(err, AA_ERR_INVALID, path, m->name, "%s is given twice", key);
		if (aa_method_set_param(m, params, key, value, path, err) < 0)
			return -1;
		seen[i] = true; /* set_param succeeded, so i is a valid index */
	}
	return 0;
}

int aa_method_parse(const char *text, const char *path, const struct aa_method **method,
		    struct aa_method_params *params, struct aa_error *err)
{
	char buf[AA_METHOD_TEXT_MAX], shown_buf[64], known[512];
	if (!text || strlen(text) >= sizeof buf)
		return fail(err, AA_ERR_INVALID, path, NULL, "method text is missing or longer than %zu bytes",
			    sizeof buf - 1);
	memcpy(buf, text, strlen(text) + 1);
	char *colon = strchr(buf, ':');
	if (colon)
		*colon = '\0';
	const char *name = aa_trim(buf);
	if (*name == '\0')
		return fail(err, AA_ERR_INVALID, path, NULL, "method name is empty; known methods: %s",
			    (aa_method_list_names(known, sizeof known), known));

	if (!strcmp(name, "user")) /* job_spec.c reads user methods, with their files */
		return fail(err, AA_ERR_INVALID, path, NULL, "user: a user method is read from its method file, "
			    "user:file=FILE.json, in a job's methods (docs/user-methods.md)");
	const struct aa_method *m = aa_method_find(name);
	if (!m) {
		char mean[96];
		aa_method_suggest(name, mean, sizeof mean);
		aa_method_list_names(known, sizeof known);
		return fail(err, AA_ERR_NOT_FOUND, path, NULL, "unknown method \"%s\"%s; known methods: %s",
			    shown(name, shown_buf, sizeof shown_buf), mean, known);
	}
	if (colon) {
		if (aa_method_parse_params(m, colon + 1, path, params, err) < 0)
			return -1;
	} else {
		aa_method_defaults(m, params);
	}
	*method = m;
	return 0;
}

void aa_method_list_names(char *out, size_t size)
{
	out[0] = '\0';
	for (int i = 0; i < aa_method_count; i++)
		append(out, size, "%s%s", i ? ", " : "", aa_methods[i]->name);
	append(out, size, ", user:file=FILE.json (docs/user-methods.md)");
}

void aa_method_suggest(const char *name, char *out, size_t size)
{
	const char *names[64 + 1];
	int n = 0;
	for (int i = 0; i < aa_method_count && n < 64; i++)
		names[n++] = aa_methods[i]->name;
	names[n++] = "user";
	aa_suggest_text(name, names, n, out, size);
}

void aa_method_param_text(const struct aa_method *m, const struct aa_method_params *p, int i, char *out,
			  size_t size)
{
	if (size == 0)
		return;
	out[0] = '\0';
	if (i < 0 || i >= param_count(m))
		return;
	const struct aa_param_def *d = &m->params[i];
	const double v = p->v[i];
	switch (d->type) {
	case AA_PARAM_INT:
		snprintf(out, size, "%lld", isfinite(v) ? (long long)llround(v) : 0LL);
		break;
	case AA_PARAM_FLOAT:
		format_double(v, out, size);
		break;
	case AA_PARAM_ENUM: {
		/* Guard the index: params may come from a caller that bypassed the parser. */
		int n = 0;
		while (d->choices && d->choices[n])
			n++;
		const int idx = isfinite(v) ? (int)v : -1;
		snprintf(out, size, "%s", idx >= 0 && idx < n ? d->choices[idx] : "?");
		break;
	}
	case AA_PARAM_BOOL:
		snprintf(out, size, "%s", v != 0 ? "true" : "false");
		break;
	}
}

void aa_method_label(const struct aa_method *m, const struct aa_method_params *p, char *out, size_t size)
{
	char value[64];
	if (size == 0)
		return;
	snprintf(out, size, "%s", m->name);
	bool first = true;
	/* The main parameter is what the method is about (ssaa:16, msaa:4): always shown, as a bare value. */
	int main_index = m->main_param ? aa_method_param_index(m, m->main_param) : -1;
	if (main_index >= 0) {
		aa_method_param_text(m, p, main_index, value, sizeof value);
		append(out, size, ":%s", value);
		first = false;
	}
	for (int i = 0; i < param_count(m); i++) {
		if (i == main_index || p->v[i] == m->params[i].def)
			continue;
		aa_method_param_text(m, p, i, value, sizeof value);
		append(out, size, "%c%s=%s", first ? ':' : ',', m->params[i].name, value);
		first = false;
	}
}
