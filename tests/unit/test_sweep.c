/* Sweeps in a job's methods (docs/job-format.md, "Sweeps"): "fxaa:preset=10|20|39", "msaa:2|4|8" and the
 * object form's lists expand into one method per configuration, the cartesian product in the order
 * written (the last parameter fastest); the limit of a job's methods (AA_MAX_METHODS) counts configurations
 * and its error names the entry and the parameter past it; bad sweeps are refused with the entry's path. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "types/job.h"
#include "run/job_spec.h"
#include "run/method_sweep.h"

static int parse_text(const char *text, struct aa_job_spec *spec, struct aa_error *err)
{
	json_error_t jerr;
	json_t *j = json_loads(text, 0, &jerr);
	if (!j)
		fail_msg("test JSON does not parse: %s: %s", text, jerr.text);
	memset(err, 0, sizeof *err);
	const int rc = aa_job_spec_from_json(j, spec, err);
	json_decref(j);
	return rc;
}

/* The job's labels, space-separated. */
static const char *labels(const struct aa_job_spec *s)
{
	static char out[2048];
	out[0] = '\0';
	for (int i = 0; i < s->method_count; i++)
		snprintf(out + strlen(out), sizeof out - strlen(out), "%s%s", i ? " " : "", s->methods[i].label);
	return out;
}

static void expect_labels(const char *job, const char *want)
{
	struct aa_job_spec s;
	struct aa_error err;
	if (parse_text(job, &s, &err) != 0)
		fail_msg("%s refused: %s: %s", job, err.path, err.message);
	assert_string_equal(labels(&s), want);
	aa_job_spec_release(&s);
}

static void expect_error(const char *job, enum aa_error_code code, const char *path, const char *part)
{
	struct aa_job_spec s;
	struct aa_error err;
	if (parse_text(job, &s, &err) == 0)
		fail_msg("%s accepted as %s", job, labels(&s));
	assert_int_equal(err.code, code);
	assert_string_equal(err.path, path);
	if (!strstr(err.message, part))
		fail_msg("%s: message \"%s\" lacks \"%s\"", job, err.message, part);
}

static void test_expansion(void **state)
{
	(void)state;
	expect_labels("{\"methods\": [\"none\", \"fxaa:preset=10|20|39\", \"msaa:2|4|8\"]}",
		      "none fxaa:preset=10 fxaa:preset=20 fxaa:preset=39 msaa:2 msaa:4 msaa:8");
	/* the product in the order written, the last parameter fastest; defaults (preset 12, subpix 0.75) leave
	 * the label */
	expect_labels("{\"methods\": [\"fxaa:preset=12|39,subpix=0.5|1\"]}",
		      "fxaa:subpix=0.5 fxaa:subpix=1 fxaa:preset=39,subpix=0.5 fxaa:preset=39,subpix=1");
	expect_labels("{\"methods\": [\"fxaa:subpix=0.5|1,preset=12|39\"]}",
		      "fxaa:subpix=0.5 fxaa:preset=39,subpix=0.5 fxaa:subpix=1 fxaa:preset=39,subpix=1");
	/* a value with one item is no sweep; whitespace around values is ignored */
	expect_labels("{\"methods\": [\"msaa: 2 | 8 , path=virtual\", \"fxaa:preset=39\"]}",
		      "msaa:2,path=virtual msaa:8,path=virtual fxaa:preset=39");
	/* the object form: a list is a sweep, a scalar the same in every configuration */
	expect_labels("{\"methods\": [{\"name\": \"msaa\", \"params\": {\"samples\": [2, 4, 8]}}]}",
		      "msaa:2 msaa:4 msaa:8");
	expect_labels("{\"methods\": [{\"name\": \"fxaa\", \"params\": {\"preset\": [10, 39], \"subpix\": 0.5}}]}",
		      "fxaa:preset=10,subpix=0.5 fxaa:preset=39,subpix=0.5");
	expect_labels("{\"methods\": [{\"name\": \"fxaa\", \"params\": {\"preset\": [10], \"subpix\": [0, 1]}}]}",
		      "fxaa:preset=10,subpix=0 fxaa:preset=10,subpix=1");
	expect_labels("{\"methods\": [{\"name\": \"fxaa\", \"params\": {\"preset\": [10, 39], \"subpix\": [0, 1]}}]}",
		      "fxaa:preset=10,subpix=0 fxaa:preset=10,subpix=1 fxaa:preset=39,subpix=0 fxaa:preset=39,subpix=1");
}

/* A sweep is the methods it names: the same canonical form and hash, and the canonical form parses back. */
static void test_same_job(void **state)
{
	(void)state;
	struct aa_job_spec a, b, c;
	struct aa_error err;
	assert_int_equal(parse_text("{\"methods\": [\"none\", \"msaa:2|4|8\"]}", &a, &err), 0);
	assert_int_equal(parse_text("{\"methods\": [\"none\", \"msaa:2\", \"msaa:4\", \"msaa:8\"]}", &b, &err), 0);
	char ha[80], hb[80];
	aa_job_hash(&a, ha, sizeof ha);
	aa_job_hash(&b, hb, sizeof hb);
	assert_string_equal(ha, hb);
	json_t *j = aa_job_spec_to_json(&a);
	assert_int_equal(json_array_size(json_object_get(j, "methods")), 4);
	assert_string_equal(json_string_value(json_array_get(json_object_get(j, "methods"), 3)), "msaa:8");
	memset(&err, 0, sizeof err);
	assert_int_equal(aa_job_spec_from_json(j, &c, &err), 0);
	json_decref(j);
	assert_string_equal(labels(&c), labels(&a));
	for (int i = 0; i < a.method_count; i++) {
		assert_ptr_equal(a.methods[i].method, c.methods[i].method);
		assert_memory_equal(&a.methods[i].params, &c.methods[i].params, sizeof a.methods[i].params);
	}
}

/* "fxaa:subpix=0|0.01|...": a sweep of count values, after the methods in before. */
static const char *subpix_job(const char *before, int count, const char *after)
{
	static char job[4096];
	snprintf(job, sizeof job, "{\"methods\": [%s\"fxaa:subpix=", before);
	for (int k = 0; k < count; k++)
		snprintf(job + strlen(job), sizeof job - strlen(job), "%s%g", k ? "|" : "", k / 1000.0);
	snprintf(job + strlen(job), sizeof job - strlen(job), "\"%s]}", after);
	return job;
}

/* AA_MAX_METHODS in all, each configuration counted: as many fit, one more does not, and the error names
 * the entry (the object form: the parameter) and the parameter whose values pass the limit. */
static void test_limit(void **state)
{
	(void)state;
	const int max = AA_MAX_METHODS;
	char want[512];
	struct aa_job_spec s;
	struct aa_error err;
	assert_int_equal(parse_text(subpix_job("\"none\", ", max - 1, ""), &s, &err), 0);
	assert_int_equal(s.method_count, max);
	snprintf(want, sizeof want, "fxaa:subpix=%g", (max - 2) / 1000.0);
	assert_string_equal(s.methods[max - 1].label, want);
	snprintf(want, sizeof want, "fxaa: subpix lists %d values, which makes the sweep %d configurations; the job "
		 "has room for %d (1 taken by the methods before it)", max, max, max - 1);
	expect_error(subpix_job("\"none\", ", max, ""), AA_ERR_LIMIT, "methods[1]", want);
	snprintf(want, sizeof want, "subpix lists %d values, which makes the sweep %d configurations; the job has "
		 "room for %d: a job compares at most %d methods", max + 1, max + 1, max, max);
	expect_error(subpix_job("", max + 1, ""), AA_ERR_LIMIT, "methods[0]", want);
	/* the product passes the limit at the second parameter: that one is named */
	snprintf(want, sizeof want, "subpix lists %d values, which makes the sweep %d configurations; the job has "
		 "room for %d (2 taken", max / 2, 2 * (max / 2), max - 2);
	char job[512];
	snprintf(job, sizeof job, "{\"methods\": [\"none\", \"ssaa\", \"fxaa:preset=12|39,subpix=");
	for (int k = 0; k < max / 2; k++)
		snprintf(job + strlen(job), sizeof job - strlen(job), "%s%g", k ? "|" : "", k / 1000.0);
	snprintf(job + strlen(job), sizeof job - strlen(job), "\"]}");
	expect_error(job, AA_ERR_LIMIT, "methods[2]", want);
	snprintf(job, sizeof job, "{\"methods\": [{\"name\": \"fxaa\", \"params\": {\"preset\": [10, 39], \"subpix\": [");
	for (int k = 0; k < max / 2 + 1; k++)
		snprintf(job + strlen(job), sizeof job - strlen(job), "%s%g", k ? ", " : "", k / 1000.0);
	snprintf(job + strlen(job), sizeof job - strlen(job), "]}}]}");
	snprintf(want, sizeof want, "subpix lists %d values, which makes the sweep %d", max / 2 + 1, 2 * (max / 2 + 1));
	expect_error(job, AA_ERR_LIMIT, "methods[0].params.subpix", want);
	/* a method that is no sweep after a sweep that filled the job */
	snprintf(want, sizeof want, "the job has %d methods before this one", max);
	expect_error(subpix_job("", max, ", \"none\""), AA_ERR_LIMIT, "methods[1]", want);
}

static void test_refused(void **state)
{
	(void)state;
	/* every configuration is validated as a method of its own, with the entry's path */
	expect_error("{\"methods\": [\"none\", \"fxaa:preset=10|11x\"]}", AA_ERR_INVALID, "methods[1]",
		     "preset=11x is not valid");
	expect_error("{\"methods\": [{\"name\": \"msaa\", \"params\": {\"samples\": [2, 3]}}]}", AA_ERR_INVALID,
		     "methods[0].params.samples", "samples=3 is not valid");
	expect_error("{\"methods\": [{\"name\": \"msaa\", \"params\": {\"samples\": [2, [4]]}}]}", AA_ERR_INVALID,
		     "methods[0].params.samples", "expected a number, string or boolean");
	/* duplicates: within a sweep, and against another entry */
	expect_error("{\"methods\": [\"msaa:4|4\"]}", AA_ERR_INVALID, "methods[0]", "the sweep names msaa:4 twice");
	expect_error("{\"methods\": [\"fxaa:subpix=0.5|0.50\"]}", AA_ERR_INVALID, "methods[0]",
		     "the sweep names fxaa:subpix=0.5 twice");
	expect_error("{\"methods\": [\"msaa:4\", \"none\", \"msaa:2|4\"]}", AA_ERR_INVALID, "methods[2]",
		     "same method and parameters as methods[0] (msaa:4), which this sweep also names");
	expect_error("{\"methods\": [\"msaa:2|4\", \"msaa:4\"]}", AA_ERR_INVALID, "methods[1]",
		     "same method and parameters as methods[0] (msaa:4); list it once");
	/* '|' between methods or in a name, empty values, an empty list, '|' in the object form */
	expect_error("{\"methods\": [\"fxaa|smaa\"]}", AA_ERR_INVALID, "methods[0]", "not methods");
	expect_error("{\"methods\": [\"msaa|ssaa:4\"]}", AA_ERR_INVALID, "methods[0]", "not methods");
	expect_error("{\"methods\": [\"fxaa:pre|set=10\"]}", AA_ERR_INVALID, "methods[0]", "not parameter names");
	expect_error("{\"methods\": [\"msaa:2||4\"]}", AA_ERR_INVALID, "methods[0]", "an empty value in a sweep");
	expect_error("{\"methods\": [\"msaa:2|\"]}", AA_ERR_INVALID, "methods[0]", "an empty value in a sweep");
	expect_error("{\"methods\": [{\"name\": \"msaa\", \"params\": {\"samples\": []}}]}", AA_ERR_INVALID,
		     "methods[0].params.samples", "an empty list");
	expect_error("{\"methods\": [{\"name\": \"msaa\", \"params\": {\"samples\": \"2|4\"}}]}", AA_ERR_INVALID,
		     "methods[0].params.samples", "a sweep is a list of values");
	/* user methods are read from their files: not swept */
	expect_error("{\"methods\": [\"user:file=x.json,strength=0.1|0.2\"]}", AA_ERR_INVALID, "methods[0]",
		     "a user method cannot be swept");
	expect_error("{\"methods\": [{\"name\": \"user\", \"params\": {\"file\": \"x.json\", \"strength\": [1, 2]}}]}",
		     AA_ERR_INVALID, "methods[0].params.strength", "a user method cannot be swept");
}

/* The expansion alone: an item that is no sweep comes back as it is. */
static void test_expand_plain(void **state)
{
	(void)state;
	struct aa_error err = {0};
	json_t *item = json_string("fxaa:preset=39"), *list = aa_method_sweep_expand(item, "methods[0]", 16, &err);
	assert_non_null(list);
	assert_int_equal(json_array_size(list), 1);
	assert_ptr_equal(json_array_get(list, 0), item);
	json_decref(list);
	json_decref(item);
	item = json_string("msaa:2|4|8");
	list = aa_method_sweep_expand(item, "methods[0]", 3, &err);
	assert_int_equal(json_array_size(list), 3);
	assert_string_equal(json_string_value(json_array_get(list, 2)), "msaa:8");
	json_decref(list);
	assert_null(aa_method_sweep_expand(item, "methods[0]", 2, &err));
	assert_int_equal(err.code, AA_ERR_LIMIT);
	json_decref(item);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_expansion),
		cmocka_unit_test(test_same_job),
		cmocka_unit_test(test_limit),
		cmocka_unit_test(test_refused),
		cmocka_unit_test(test_expand_plain),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
