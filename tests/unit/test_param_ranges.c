/* Every parameter of every registered method, generated from the method tables, without a GPU: each bound
 * and each valid value is accepted, the value just past each bound and every value outside an allowed list
 * or a choice list is refused with the parameter named, in the method-string form ("ssaa:samples=65") and
 * in the job file's object form ({"name": "ssaa", "params": {"samples": 65}}). The job's own numeric fields
 * get the same treatment. A new method or parameter is covered without touching this file. */
#include <float.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "run/engine.h"
#include "methods/methods.h"
#include "run/job_spec.h"

static int checked_accepts, checked_refusals;

/* The job {"methods": [value]} where value is the method string or the object form of one parameter. */
static int parse_job(const struct aa_method *m, const struct aa_param_def *d, const char *text, bool object,
		     struct aa_job_spec *spec, struct aa_error *err)
{
	json_t *method;
	if (object) {
		/* the value as JSON: numbers as numbers, booleans as booleans, choices as strings */
		json_t *value;
		json_error_t jerr;
		value = d->type == AA_PARAM_ENUM ? json_string(text) : json_loads(text, JSON_DECODE_ANY, &jerr);
		if (!value)
			value = json_string(text); /* "yes", "on", "nonesuch": strings, as a user would send them */
		method = json_pack("{s:s, s:{s:o}}", "name", m->name, "params", d->name, value);
	} else {
		char s[256];
		snprintf(s, sizeof s, "%s:%s=%s", m->name, d->name, text);
		method = json_string(s);
	}
	json_t *job = json_pack("{s:[o]}", "methods", method);
	memset(err, 0, sizeof *err);
	int rc = aa_job_spec_from_json(job, spec, err);
	json_decref(job);
	return rc;
}

static void expect_accepted(const struct aa_method *m, int i, const char *text, double want)
{
	const struct aa_param_def *d = &m->params[i];
	for (int object = 0; object < 2; object++) {
		struct aa_job_spec spec;
		struct aa_error err;
		if (parse_job(m, d, text, object, &spec, &err))
			fail_msg("%s %s=%s (%s form) refused: %s: %s", m->name, d->name, text, object ? "object" : "string",
				 err.path, err.message);
		assert_int_equal(spec.method_count, 1);
		assert_ptr_equal(spec.methods[0].method, m);
		if (spec.methods[0].params.v[i] != want)
			fail_msg("%s %s=%s read as %.17g, expected %.17g", m->name, d->name, text,
				 spec.methods[0].params.v[i], want);
		/* the canonical label parses back to the same parameters */
		const struct aa_method *back;
		struct aa_method_params p;
		if (aa_method_parse(spec.methods[0].label, "label", &back, &p, &err) || back != m ||
		    memcmp(&p, &spec.methods[0].params, sizeof p) != 0)
			fail_msg("%s %s=%s: label %s does not parse back", m->name, d->name, text, spec.methods[0].label);
		checked_accepts++;
	}
}

static void expect_refused(const struct aa_method *m, int i, const char *text)
{
	const struct aa_param_def *d = &m->params[i];
	for (int object = 0; object < 2; object++) {
		struct aa_job_spec spec;
		struct aa_error err;
		if (!parse_job(m, d, text, object, &spec, &err))
			fail_msg("%s %s=%s (%s form) accepted, read as %.17g", m->name, d->name, text,
				 object ? "object" : "string", spec.methods[0].params.v[i]);
		char path[128], named[160];
		if (object)
			snprintf(path, sizeof path, "methods[0].params.%s", d->name);
		else
			snprintf(path, sizeof path, "methods[0]");
		snprintf(named, sizeof named, "%s=", d->name);
		if (err.code != AA_ERR_INVALID || strcmp(err.path, path) != 0 || !strstr(err.message, named) ||
		    !strstr(err.message, "valid"))
			fail_msg("%s %s=%s (%s form): error %d at '%s': %s; expected invalid at '%s' naming %s and the "
				 "valid values", m->name, d->name, text, object ? "object" : "string", err.code, err.path,
				 err.message, path, d->name);
		checked_refusals++;
	}
}

static void text_of(double v, char *out, size_t size)
{
	snprintf(out, size, "%.17g", v);
}

static bool in_list(const int *allowed, long long v)
{
	for (int i = 0; allowed[i]; i++)
		if (allowed[i] == v)
			return true;
	return false;
}

static void check_int(const struct aa_method *m, int i)
{
	const struct aa_param_def *d = &m->params[i];
	char t[64];
	assert_true(d->min < d->max);
	assert_true(d->min == floor(d->min) && d->max == floor(d->max));
	if (d->allowed) {
		int lo = d->allowed[0], hi = d->allowed[0], n = 0;
		for (; d->allowed[n]; n++) {
			lo = d->allowed[n] < lo ? d->allowed[n] : lo;
			hi = d->allowed[n] > hi ? d->allowed[n] : hi;
			snprintf(t, sizeof t, "%d", d->allowed[n]);
			expect_accepted(m, i, t, d->allowed[n]);
		}
		/* the table's range is the span of its list, which describe/--json report */
		assert_true(n > 0 && lo == d->min && hi == d->max);
		for (long long v = (long long)d->min - 1; v <= (long long)d->max + 1; v++)
			if (!in_list(d->allowed, v)) {
				snprintf(t, sizeof t, "%lld", v);
				expect_refused(m, i, t);
			}
	} else {
		const long long lo = (long long)d->min, hi = (long long)d->max;
		const long long inside[] = {lo, lo + 1, (lo + hi) / 2, hi - 1, hi};
		for (size_t k = 0; k < sizeof inside / sizeof inside[0]; k++) {
			snprintf(t, sizeof t, "%lld", inside[k]);
			expect_accepted(m, i, t, (double)inside[k]);
		}
		const long long outside[] = {lo - 1, hi + 1, hi + 1000, lo - 1000};
		for (size_t k = 0; k < sizeof outside / sizeof outside[0]; k++) {
			snprintf(t, sizeof t, "%lld", outside[k]);
			expect_refused(m, i, t);
		}
	}
	expect_refused(m, i, "1.5");
	expect_refused(m, i, "ten");
}

static void check_float(const struct aa_method *m, int i)
{
	const struct aa_param_def *d = &m->params[i];
	char t[64];
	assert_true(d->min < d->max);
	/* one part in 10^9 past a bound: far from subnormals (which strtod refuses) and from rounding */
	const double eps_lo = 1e-9 * fmax(1.0, fabs(d->min)), eps_hi = 1e-9 * fmax(1.0, fabs(d->max));
	const double inside[] = {d->min, d->min + eps_lo, (d->min + d->max) / 2, d->max - eps_hi, d->max};
	for (size_t k = 0; k < sizeof inside / sizeof inside[0]; k++) {
		text_of(inside[k], t, sizeof t);
		expect_accepted(m, i, t, inside[k]);
	}
	const double outside[] = {d->min - eps_lo, d->max + eps_hi, nextafter(d->max, INFINITY), d->max + 1,
				  d->min - 1, d->max * 1000 + 1000};
	for (size_t k = 0; k < sizeof outside / sizeof outside[0]; k++) {
		text_of(outside[k], t, sizeof t);
		expect_refused(m, i, t);
	}
	expect_refused(m, i, "nan");
	expect_refused(m, i, "inf");
}

static void check_enum(const struct aa_method *m, int i)
{
	const struct aa_param_def *d = &m->params[i];
	int n = 0;
	char t[64];
	for (; d->choices && d->choices[n]; n++) {
		expect_accepted(m, i, d->choices[n], n);
		/* choices are case-insensitive */
		snprintf(t, sizeof t, "%s", d->choices[n]);
		for (char *c = t; *c; c++)
			*c = (char)(*c >= 'a' && *c <= 'z' ? *c - 32 : *c);
		expect_accepted(m, i, t, n);
	}
	assert_true(n >= 2);
	/* the table's range covers exactly the choices */
	assert_true(d->min == 0 && d->max == n - 1);
	expect_refused(m, i, "nonesuch");
	/* an index is not a choice (unless a choice is spelt that way) */
	for (int k = -1; k <= n; k++) {
		snprintf(t, sizeof t, "%d", k);
		bool is_choice = false;
		for (int c = 0; c < n; c++)
			is_choice = is_choice || strcmp(d->choices[c], t) == 0;
		if (!is_choice)
			expect_refused(m, i, t);
	}
}

static void check_bool(const struct aa_method *m, int i)
{
	const char *yes[] = {"true", "1", "yes", "on"}, *no[] = {"false", "0", "no", "off"};
	for (int k = 0; k < 4; k++) {
		expect_accepted(m, i, yes[k], 1);
		expect_accepted(m, i, no[k], 0);
	}
	expect_refused(m, i, "2");
	expect_refused(m, i, "maybe");
}

static void test_every_parameter(void **state)
{
	(void)state;
	int params = 0;
	for (int k = 0; k < aa_method_count; k++) {
		const struct aa_method *m = aa_methods[k];
		assert_true(m->param_count <= AA_MAX_PARAMS);
		assert_true(m->param_count == 0 || m->params);
		for (int i = 0; i < m->param_count; i++) {
			const struct aa_param_def *d = &m->params[i];
			/* the default is itself a valid value: written out, it parses back to itself */
			struct aa_method_params p;
			aa_method_defaults(m, &p);
			char text[64];
			aa_method_param_text(m, &p, i, text, sizeof text);
			expect_accepted(m, i, text, d->def);
			switch (d->type) {
			case AA_PARAM_INT: check_int(m, i); break;
			case AA_PARAM_FLOAT: check_float(m, i); break;
			case AA_PARAM_ENUM: check_enum(m, i); break;
			case AA_PARAM_BOOL: check_bool(m, i); break;
			}
			expect_refused(m, i, "");
			params++;
		}
	}
	printf("  %d parameters of %d methods: %d accepted and %d refused values checked\n", params, aa_method_count,
	       checked_accepts, checked_refusals);
	assert_true(params >= 20);
}

/* A method without parameters refuses any, naming the method. */
static void test_methods_without_parameters(void **state)
{
	(void)state;
	for (int k = 0; k < aa_method_count; k++) {
		const struct aa_method *m = aa_methods[k];
		if (m->param_count)
			continue;
		char text[64];
		snprintf(text, sizeof text, "%s:x=1", m->name);
		const struct aa_method *got;
		struct aa_method_params p;
		struct aa_error err = {0};
		assert_int_equal(aa_method_parse(text, "methods[0]", &got, &p, &err), -1);
		assert_string_equal(err.path, "methods[0]");
		assert_non_null(strstr(err.message, "takes no parameters"));
	}
}

/* The job's numeric fields: bounds accepted, one past refused with the field named; too large is a limit
 * (ask for less), too small is invalid. */
static void test_job_fields(void **state)
{
	(void)state;
	static const struct { const char *field, *path; long long min, max; } fields[] = {
		{"width", "width", 1, AA_MAX_SIZE},
		{"height", "height", 1, AA_MAX_SIZE},
		{"frames", "frames", 1, AA_MAX_FRAMES},
		{"first_frame", "first_frame", 0, 10000000},
	};
	for (size_t f = 0; f < sizeof fields / sizeof fields[0]; f++) {
		const long long values[] = {fields[f].min, fields[f].max, fields[f].min - 1, fields[f].max + 1};
		for (int k = 0; k < 4; k++) {
			json_t *job = json_pack("{s:I}", fields[f].field, (json_int_t)values[k]);
			struct aa_job_spec spec;
			struct aa_error err = {0};
			int rc = aa_job_spec_from_json(job, &spec, &err);
			json_decref(job);
			if (k < 2) {
				if (rc)
					fail_msg("%s = %lld refused: %s", fields[f].field, values[k], err.message);
				continue;
			}
			if (!rc || strcmp(err.path, fields[f].path) != 0 ||
			    err.code != (k == 3 ? AA_ERR_LIMIT : AA_ERR_INVALID))
				fail_msg("%s = %lld: rc %d, code %d, path '%s'", fields[f].field, values[k], rc, err.code,
					 err.path);
		}
	}
	/* reference.samples: 2..4096 and even */
	const struct { long long v; int code; } samples[] = {{2, 0}, {4096, 0}, {0, AA_ERR_INVALID},
		{4098, AA_ERR_LIMIT}, {3, AA_ERR_INVALID}, {4095, AA_ERR_INVALID}};
	for (size_t k = 0; k < sizeof samples / sizeof samples[0]; k++) {
		json_t *job = json_pack("{s:{s:I}}", "reference", "samples", (json_int_t)samples[k].v);
		struct aa_job_spec spec;
		struct aa_error err = {0};
		int rc = aa_job_spec_from_json(job, &spec, &err);
		json_decref(job);
		if (samples[k].code == 0 ? rc != 0 : (rc == 0 || (int)err.code != samples[k].code ||
						     strcmp(err.path, "reference.samples") != 0))
			fail_msg("reference.samples = %lld: rc %d, code %d, path '%s'", samples[k].v, rc, err.code, err.path);
	}
	/* size as text: each side 1..AA_MAX_SIZE */
	const struct { const char *text; int code; } sizes[] = {{"1x1", 0}, {"8192x8192", 0}, {"8193x1", AA_ERR_LIMIT},
		{"1x8193", AA_ERR_LIMIT}, {"0x10", AA_ERR_INVALID}, {"10x0", AA_ERR_INVALID}};
	for (size_t k = 0; k < sizeof sizes / sizeof sizes[0]; k++) {
		int w, h;
		struct aa_error err = {0};
		int rc = aa_parse_size(sizes[k].text, &w, &h, &err);
		if (sizes[k].code == 0 ? rc != 0 : (rc == 0 || (int)err.code != sizes[k].code ||
						   strcmp(err.path, "size") != 0))
			fail_msg("size %s: rc %d, code %d, path '%s'", sizes[k].text, rc, err.code, err.path);
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_every_parameter),
		cmocka_unit_test(test_methods_without_parameters),
		cmocka_unit_test(test_job_fields),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
