/* Job spec parsing and validation, method strings of every parameter type, and the spec's JSON round trip. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "types/job.h"
#include "methods/methods.h"
#include "run/job_spec.h"

/* A method table with every parameter type, standing in for fxaa/smaa/rsaa, which the registry may not
 * list yet. Tests reach it through aa_method_parse_params and aa_method_set_param. */
static const int preset_allowed[] = { 10, 12, 15, 20, 23, 25, 26, 29, 39, 0 };
static const char *const quality_choices[] = { "low", "medium", "high", "ultra", NULL };
static const struct aa_param_def fake_params[] = {
	{ .name = "preset", .type = AA_PARAM_INT, .def = 39, .min = 10, .max = 39, .allowed = preset_allowed },
	{ .name = "subpix", .type = AA_PARAM_FLOAT, .def = 0.75, .min = 0, .max = 1 },
	{ .name = "quality", .type = AA_PARAM_ENUM, .def = 2, .min = 0, .max = 3, .choices = quality_choices },
	{ .name = "auth", .type = AA_PARAM_BOOL, .def = 0, .min = 0, .max = 1 },
	{ .name = "steps", .type = AA_PARAM_INT, .def = 8, .min = 1, .max = 32 },
};
static const struct aa_method fake_fxaa = { .name = "fxaa", .params = fake_params, .param_count = 5,
					    .main_param = "preset" };
static const struct aa_method fake_smaa = { .name = "smaa", .params = fake_params + 2, .param_count = 1,
					    .main_param = "quality" };
static const struct aa_method fake_rsaa = { .name = "rsaa", .params = fake_params, .param_count = 5 };

/* Field by field: struct padding is not part of the value. */
static void assert_spec_equal(const struct aa_job_spec *a, const struct aa_job_spec *b)
{
	assert_string_equal(a->scene, b->scene);
	assert_string_equal(a->path, b->path);
	assert_int_equal(a->width, b->width);
	assert_int_equal(a->height, b->height);
	assert_int_equal(a->frames, b->frames);
	assert_int_equal(a->first_frame, b->first_frame);
	assert_int_equal(a->reference_samples, b->reference_samples);
	assert_int_equal(a->timing_repeat, b->timing_repeat);
	assert_int_equal(a->keep_frames, b->keep_frames);
	assert_string_equal(a->name, b->name);
	assert_int_equal(a->method_count, b->method_count);
	for (int i = 0; i < a->method_count; i++) {
		assert_ptr_equal(a->methods[i].method, b->methods[i].method);
		assert_memory_equal(&a->methods[i].params, &b->methods[i].params, sizeof a->methods[i].params);
		assert_string_equal(a->methods[i].label, b->methods[i].label);
	}
}

/* An error as users see it: "path: message" (the message does not repeat the path). */
static const char *displayed(const struct aa_error *err)
{
	static char buf[sizeof err->path + sizeof err->message + 4];
	if (err->path[0] && strncmp(err->message, err->path, strlen(err->path)) == 0)
		fail_msg("message repeats its path: %s", err->message);
	snprintf(buf, sizeof buf, "%s%s%s", err->path, err->path[0] ? ": " : "", err->message);
	return buf;
}

static json_t *load(const char *text)
{
	json_error_t jerr;
	json_t *j = json_loads(text, 0, &jerr);
	if (!j)
		fail_msg("test JSON does not parse: %s: %s", text, jerr.text);
	return j;
}

static int parse_text(const char *text, struct aa_job_spec *spec, struct aa_error *err)
{
	json_t *j = load(text);
	memset(err, 0, sizeof *err);
	const int rc = aa_job_spec_from_json(j, spec, err);
	json_decref(j);
	return rc;
}

static void test_defaults(void **state)
{
	(void)state;
	struct aa_job_spec s;
	aa_job_spec_defaults(&s);
	assert_string_equal(s.scene, "thin-wires");
	assert_string_equal(s.path, "default");
	assert_int_equal(s.width, 640);
	assert_int_equal(s.height, 360);
	assert_int_equal(s.frames, 1);
	assert_int_equal(s.first_frame, 0);
	assert_int_equal(s.reference_samples, 64);
	assert_int_equal(s.timing_repeat, 1); /* a spec made in code times once */
	assert_false(s.timing_auto);
	assert_true(s.keep_frames);
	assert_int_equal(s.method_count, 2);
	assert_string_equal(s.methods[0].method->name, "none");
	assert_string_equal(s.methods[0].label, "none");
	assert_string_equal(s.methods[1].label, "ssaa:16");
	assert_string_equal(s.name, "");

	/* An empty job object means all defaults, but for timing.repeat "auto": 5 repeats of one frame give
	 * each method 5 timed renders; 2 of three frames give 6, 1 of five frames 5 */
	struct aa_job_spec p;
	struct aa_error err;
	assert_int_equal(parse_text("{}", &p, &err), 0);
	assert_true(p.timing_auto);
	assert_int_equal(p.timing_repeat, 5);
	s.timing_auto = true;
	s.timing_repeat = 5;
	assert_spec_equal(&s, &p);
	assert_int_equal(parse_text("{\"frames\": 3}", &p, &err), 0);
	assert_int_equal(p.timing_repeat, 2);
	assert_int_equal(parse_text("{\"frames\": 5}", &p, &err), 0);
	assert_int_equal(p.timing_repeat, 1);
	assert_int_equal(parse_text("{\"frames\": 4, \"timing\": {\"repeat\": \"auto\"}}", &p, &err), 0);
	assert_int_equal(p.timing_repeat, 2);
	assert_int_equal(parse_text("{\"frames\": 1, \"timing\": {\"repeat\": 1}}", &p, &err), 0);
	assert_int_equal(p.timing_repeat, 1);
	assert_false(p.timing_auto);
}

static void test_good_job(void **state)
{
	(void)state;
	struct aa_job_spec s;
	struct aa_error err;
	int rc = parse_text("{\"scene\": \"thin-wires\", \"path\": \"orbit\", \"size\": \"320x180\", \"frames\": 8,"
			    " \"first_frame\": 4, \"reference\": {\"samples\": 16},"
			    " \"methods\": [\"none\", \"ssaa:4\", {\"name\": \"ssaa\", \"params\": {\"samples\": 9}},"
			    "               \" ssaa : samples = 36 \", \"ssaa\"],"
			    " \"keep_frames\": false, \"name\": \"nightly <1>\", \"timing\": {\"repeat\": 5}}",
			    &s, &err);
	assert_int_equal(rc, 0);
	assert_int_equal(s.timing_repeat, 5);
	assert_string_equal(s.path, "orbit");
	assert_int_equal(s.width, 320);
	assert_int_equal(s.height, 180);
	assert_int_equal(s.frames, 8);
	assert_int_equal(s.first_frame, 4);
	assert_int_equal(s.reference_samples, 16);
	assert_false(s.keep_frames);
	assert_string_equal(s.name, "nightly <1>");
	assert_int_equal(s.method_count, 5);
	assert_string_equal(s.methods[0].label, "none");
	assert_string_equal(s.methods[1].label, "ssaa:4");
	assert_true(s.methods[1].params.v[0] == 4);
	assert_string_equal(s.methods[2].label, "ssaa:9");
	assert_string_equal(s.methods[3].label, "ssaa:36");
	assert_string_equal(s.methods[4].label, "ssaa:16"); /* the main parameter is always shown */

	/* The other size forms, and a scene given as a file path. */
	assert_int_equal(parse_text("{\"size\": [1, 8192], \"scene\": \"../scenes/x.json\"}", &s, &err), 0);
	assert_int_equal(s.width, 1);
	assert_int_equal(s.height, 8192);
	assert_string_equal(s.scene, "../scenes/x.json");
	assert_int_equal(parse_text("{\"width\": 100, \"height\": 50, \"scene\": \"/abs/dir/s.json\"}", &s, &err), 0);
	assert_int_equal(s.width, 100);
	assert_int_equal(s.height, 50);
	/* Object form: a real number for an integer parameter is fine when it is whole. */
	assert_int_equal(parse_text("{\"methods\": [{\"name\": \"ssaa\", \"params\": {\"samples\": 25.0}}]}", &s, &err), 0);
	assert_string_equal(s.methods[0].label, "ssaa:25");
	assert_int_equal(parse_text("{\"reference\": {\"samples\": 4096}, \"frames\": 100000}", &s, &err), 0);
}

struct bad_case {
	const char *json;
	enum aa_error_code code;
	const char *path;
	const char *message; /* a substring of the displayed "path: message" */
};

static const struct bad_case bad_cases[] = {
	{ "[]", AA_ERR_INVALID, "", "a job must be a JSON object" },
	{ "{\"colour\": 1}", AA_ERR_INVALID, "colour", "colour: unknown key; valid keys: scene, path, size" },
	{ "{\"scene\": 5}", AA_ERR_INVALID, "scene", "scene: expected a string, got an integer" },
	{ "{\"scene\": \"\"}", AA_ERR_INVALID, "scene", "scene: must not be empty" },
	{ "{\"scene\": \"../../etc/passwd\"}", AA_ERR_INVALID, "scene", "neither a scene name" },
	{ "{\"scene\": \"a/b\"}", AA_ERR_INVALID, "scene", "path to a .json scene file" },
	{ "{\"scene\": \"..\"}", AA_ERR_INVALID, "scene", "neither a scene name" },
	{ "{\"scene\": \"wire\\u0001s\"}", AA_ERR_INVALID, "scene", "scene: contains a control character at byte 4" },
	{ "{\"path\": \"\"}", AA_ERR_INVALID, "path", "path: must not be empty" },
	{ "{\"path\": \"a\\nb\"}", AA_ERR_INVALID, "path", "control character" },
	{ "{\"path\": \"0123456789012345678901234567890123456789012345678901234567890123456789\"}", AA_ERR_LIMIT,
	  "path", "path: is 70 bytes long; the limit is 63" },
	{ "{\"size\": \"-3x10\"}", AA_ERR_INVALID, "size", "size: \"-3x10\" is not a size; write WIDTHxHEIGHT" },
	{ "{\"size\": \"0x10\"}", AA_ERR_INVALID, "size", "width is out of range" },
	{ "{\"size\": \"640x9000\"}", AA_ERR_LIMIT, "size", "height is out of range; width and height must each be from 1 to 8192" },
	{ "{\"size\": [640]}", AA_ERR_INVALID, "size", "of the wrong length" },
	{ "{\"size\": [640, \"360\"]}", AA_ERR_INVALID, "size[1]", "size[1]: expected an integer, got a string" },
	{ "{\"size\": true}", AA_ERR_INVALID, "size", "expected \"WIDTHxHEIGHT\" or [width, height], got a boolean" },
	{ "{\"size\": \"64x64\", \"width\": 8}", AA_ERR_INVALID, "size", "not both" },
	{ "{\"width\": 0}", AA_ERR_INVALID, "width", "width: 0 is out of range; valid range: 1 to 8192" },
	{ "{\"height\": 1.5}", AA_ERR_INVALID, "height", "expected an integer, got a number" },
	{ "{\"frames\": 0}", AA_ERR_INVALID, "frames", "frames: 0 is out of range; valid range: 1 to 100000" },
	{ "{\"frames\": 100001}", AA_ERR_LIMIT, "frames", "frames: 100001 is out of range" },
	{ "{\"frames\": \"8\"}", AA_ERR_INVALID, "frames", "expected an integer, got a string" },
	{ "{\"first_frame\": -1}", AA_ERR_INVALID, "first_frame", "first_frame: -1 is out of range" },
	{ "{\"reference\": 64}", AA_ERR_INVALID, "reference", "reference: expected an object" },
	{ "{\"reference\": {\"samples\": 63}}", AA_ERR_INVALID, "reference.samples", "reference.samples: 63 is odd" },
	{ "{\"reference\": {\"samples\": 1}}", AA_ERR_INVALID, "reference.samples", "valid range: 2 to 4096" },
	{ "{\"reference\": {\"samples\": 8192}}", AA_ERR_LIMIT, "reference.samples", "8192 is out of range" },
	{ "{\"reference\": {\"sample\": 8}}", AA_ERR_INVALID, "reference.sample",
	  "unknown key (did you mean 'samples'?); valid keys: samples" },
	{ "{\"frame\": 8}", AA_ERR_INVALID, "frame", "frame: unknown key (did you mean 'frames'?); valid keys: scene" },
	{ "{\"methods\": [\"smma\"]}", AA_ERR_NOT_FOUND, "methods[0]", "unknown method \"smma\" (did you mean 'smaa'?)" },
	{ "{\"methods\": [\"fxaa:preest=12\"]}", AA_ERR_INVALID, "methods[0]",
	  "fxaa: unknown parameter \"preest\" (did you mean 'preset'?); valid parameters: preset" },
	{ "{\"reference\": {\"samples\": \"many\"}}", AA_ERR_INVALID, "reference.samples", "expected an even integer or \"auto\"" },
	{ "{\"reference\": {\"samples\": \"auto\", \"target_psnr\": 10}}", AA_ERR_INVALID, "reference.target_psnr", "10 is out of range; valid range: 20 to 80 dB" },
	{ "{\"reference\": {\"samples\": \"auto\", \"target_psnr\": \"45\"}}", AA_ERR_INVALID, "reference.target_psnr", "expected a number of dB, got a string" },
	{ "{\"reference\": {\"samples\": \"auto\", \"max_samples\": 100}}", AA_ERR_INVALID, "reference.max_samples", "100 is not a power of two" },
	{ "{\"reference\": {\"samples\": \"auto\", \"max_samples\": 4}}", AA_ERR_INVALID, "reference.max_samples", "4 is out of range; valid range: 8 to 4096" },
	{ "{\"reference\": {\"samples\": 16, \"target_psnr\": 45}}", AA_ERR_INVALID, "reference.target_psnr", "applies only with \"samples\": \"auto\"" },
	{ "{\"methods\": []}", AA_ERR_INVALID, "methods", "methods: the list is empty" },
	{ "{\"methods\": \"ssaa\"}", AA_ERR_INVALID, "methods", "expected an array of methods" },
	{ "{\"methods\": [\"n\",\"n\",\"n\",\"n\",\"n\",\"n\",\"n\",\"n\",\"n\",\"n\",\"n\",\"n\",\"n\",\"n\",\"n\",\"n\",\"n\","
	  "\"n\",\"n\",\"n\",\"n\",\"n\",\"n\",\"n\",\"n\"]}",
	  AA_ERR_LIMIT, "methods", "25 methods; a job compares at most 24" },
	{ "{\"methods\": [\"nosuch-aa\"]}", AA_ERR_NOT_FOUND, "methods[0]",
	  "methods[0]: unknown method \"nosuch-aa\"; known methods: " },
	{ "{\"methods\": [\"none\", \"ssaa:7\"]}", AA_ERR_INVALID, "methods[1]",
	  "methods[1]: ssaa: samples=7 is not valid; valid values: 4, 9, 16, 25, 36, 49, 64" },
	{ "{\"methods\": [\"ssaa:count=4\"]}", AA_ERR_INVALID, "methods[0]",
	  "methods[0]: ssaa: unknown parameter \"count\"; valid parameters: samples" },
	{ "{\"methods\": [\"ssaa:4,samples=9\"]}", AA_ERR_INVALID, "methods[0]", "ssaa: samples is given twice" },
	{ "{\"methods\": [\"none:4\"]}", AA_ERR_INVALID, "methods[0]", "methods[0]: none: takes no parameters" },
	{ "{\"methods\": [\"ssaa:\"]}", AA_ERR_INVALID, "methods[0]", "nothing after ':'" },
	{ "{\"methods\": [\"\"]}", AA_ERR_INVALID, "methods[0]", "method name is empty" },
	{ "{\"methods\": [\"ssaa:4\", \"ssaa:samples=4\"]}", AA_ERR_INVALID, "methods[1]",
	  "methods[1]: same method and parameters as methods[0] (ssaa:4); list it once" },
	{ "{\"methods\": [\"ssaa\", \"ssaa:16\"]}", AA_ERR_INVALID, "methods[1]", "as methods[0] (ssaa:16)" },
	{ "{\"methods\": [42]}", AA_ERR_INVALID, "methods[0]", "expected a method string" },
	{ "{\"methods\": [{\"params\": {}}]}", AA_ERR_INVALID, "methods[0].name", "methods[0].name: missing" },
	{ "{\"methods\": [{\"name\": \"ssaa:4\"}]}", AA_ERR_INVALID, "methods[0].name", "give the bare name" },
	{ "{\"methods\": [{\"name\": \"ssaa\", \"samples\": 4}]}", AA_ERR_INVALID, "methods[0].samples",
	  "unknown key; valid keys: name, params" },
	{ "{\"methods\": [{\"name\": \"ssaa\", \"params\": {\"samples\": 5}}]}", AA_ERR_INVALID,
	  "methods[0].params.samples", "methods[0].params.samples: ssaa: samples=5 is not valid" },
	{ "{\"methods\": [{\"name\": \"ssaa\", \"params\": {\"samples\": [[4]]}}]}", AA_ERR_INVALID,
	  "methods[0].params.samples", "expected a number, string or boolean, got an array" },
	{ "{\"methods\": [{\"name\": \"ssaa\", \"params\": [4]}]}", AA_ERR_INVALID, "methods[0].params",
	  "expected an object of parameter values" },
	{ "{\"methods\": [{\"name\": \"nosuch-aa\"}]}", AA_ERR_NOT_FOUND, "methods[0].name",
	  "unknown method \"nosuch-aa\"; known methods: " },
	{ "{\"keep_frames\": 1}", AA_ERR_INVALID, "keep_frames", "keep_frames: expected true or false, got an integer" },
	{ "{\"timing\": 5}", AA_ERR_INVALID, "timing", "timing: expected an object like {\"repeat\": 5}" },
	{ "{\"timing\": {\"repeats\": 5}}", AA_ERR_INVALID, "timing.repeats",
	  "unknown key (did you mean 'repeat'?); valid keys: repeat" },
	{ "{\"timing\": {\"repeat\": 0}}", AA_ERR_INVALID, "timing.repeat", "0 is out of range; valid range: 1 to 100" },
	{ "{\"timing\": {\"repeat\": \"3\"}}", AA_ERR_INVALID, "timing.repeat", "expected an integer or \"auto\", got the string \"3\"" },
	{ "{\"timing\": {\"repeat\": 1.5}}", AA_ERR_INVALID, "timing.repeat", "expected an integer, got a number with a fraction" },
	{ "{\"frames\": 2000, \"timing\": {\"repeat\": 51}}", AA_ERR_LIMIT, "timing.repeat",
	  "2000 frames x 51 repeats is over 100000 timed renders per method" },
	{ "{\"name\": null}", AA_ERR_INVALID, "name", "name: expected a string, got null" },
};

static void test_bad_jobs(void **state)
{
	(void)state;
	for (size_t i = 0; i < sizeof bad_cases / sizeof bad_cases[0]; i++) {
		const struct bad_case *c = &bad_cases[i];
		struct aa_job_spec s, before;
		struct aa_error err;
		aa_job_spec_defaults(&s);
		before = s;
		if (parse_text(c->json, &s, &err) == 0)
			fail_msg("accepted bad job %s", c->json);
		if (err.code != c->code || strcmp(err.path, c->path) != 0 || !strstr(displayed(&err), c->message))
			fail_msg("job %s\n  got      %s [%s] %s\n  expected %s [%s] ...%s...", c->json,
				 aa_error_code_name(err.code), err.path, displayed(&err), aa_error_code_name(c->code),
				 c->path, c->message);
		/* A refused job leaves the spec as it was. */
		assert_spec_equal(&s, &before);
	}
}

static void test_parse_size(void **state)
{
	(void)state;
	struct aa_error err = { 0 };
	int w = 0, h = 0;
	assert_int_equal(aa_parse_size("640x360", &w, &h, &err), 0);
	assert_int_equal(w, 640);
	assert_int_equal(h, 360);
	assert_int_equal(aa_parse_size("8192X1", &w, &h, &err), 0);
	assert_int_equal(w, 8192);
	static const char *const bad[] = { "-3x10", "640", "640x", "x360", "0x10", "10x0", "640x360x2", "6.5x3",
					   " 640x360", "640 x 360", "99999999999999999999x1", "", "8193x1" };
	for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
		w = h = -7;
		memset(&err, 0, sizeof err);
		if (aa_parse_size(bad[i], &w, &h, &err) == 0)
			fail_msg("accepted size \"%s\"", bad[i]);
		assert_string_equal(err.path, "size");
		assert_true(strncmp(displayed(&err), "size: \"", 7) == 0);
		assert_int_equal(w, -7); /* untouched on error */
	}
	assert_int_equal(aa_parse_size(NULL, &w, &h, &err), -1);
}

static void test_fake_method_all_types(void **state)
{
	(void)state;
	struct aa_method_params p;
	struct aa_error err = { 0 };
	char label[AA_LABEL_MAX], text[64];

	/* Defaults give the name and the main parameter; each type is written back in its own form. */
	aa_method_defaults(&fake_fxaa, &p);
	aa_method_label(&fake_fxaa, &p, label, sizeof label);
	assert_string_equal(label, "fxaa:39");
	aa_method_param_text(&fake_fxaa, &p, 1, text, sizeof text);
	assert_string_equal(text, "0.75");
	aa_method_param_text(&fake_fxaa, &p, 2, text, sizeof text);
	assert_string_equal(text, "high");
	aa_method_param_text(&fake_fxaa, &p, 3, text, sizeof text);
	assert_string_equal(text, "false");

	assert_int_equal(aa_method_parse_params(&fake_fxaa, " 12 , subpix=0.5,quality = ULTRA, auth=yes, steps=+3",
						"methods[2]", &p, &err), 0);
	assert_true(p.v[0] == 12 && p.v[1] == 0.5 && p.v[2] == 3 && p.v[3] == 1 && p.v[4] == 3);
	aa_method_label(&fake_fxaa, &p, label, sizeof label);
	assert_string_equal(label, "fxaa:12,subpix=0.5,quality=ultra,auth=true,steps=3");

	/* Only non-default parameters appear, in table order whatever the input order. */
	assert_int_equal(aa_method_parse_params(&fake_fxaa, "auth=1,preset=39,subpix=0.1", "", &p, &err), 0);
	aa_method_label(&fake_fxaa, &p, label, sizeof label);
	assert_string_equal(label, "fxaa:39,subpix=0.1,auth=true");

	/* A label parses back to exactly the same values, floats included. */
	assert_int_equal(aa_method_set_param(&fake_fxaa, &p, "subpix", "0.3333333333333333", "", &err), 0);
	aa_method_label(&fake_fxaa, &p, label, sizeof label);
	struct aa_method_params back;
	assert_int_equal(aa_method_parse_params(&fake_fxaa, strchr(label, ':') + 1, "", &back, &err), 0);
	assert_memory_equal(&p, &back, sizeof p);

	/* An enum main parameter takes a bare name. */
	assert_int_equal(aa_method_parse_params(&fake_smaa, "low", "", &p, &err), 0);
	aa_method_label(&fake_smaa, &p, label, sizeof label);
	assert_string_equal(label, "smaa:low");
	assert_int_equal(aa_method_parse_params(&fake_smaa, "low", "", &back, &err), 0);
	assert_memory_equal(&p, &back, sizeof p);

	/* rsaa-like: no main parameter, all four types by key. */
	assert_int_equal(aa_method_parse_params(&fake_rsaa, "steps=8,auth=on,quality=medium,subpix=1e-1", "", &p, &err), 0);
	aa_method_label(&fake_rsaa, &p, label, sizeof label);
	assert_string_equal(label, "rsaa:subpix=0.1,quality=medium,auth=true");
}

struct param_error {
	const struct aa_method *method;
	const char *list;
	const char *message; /* exact */
};

static void test_fake_method_errors(void **state)
{
	(void)state;
	static const struct param_error cases[] = {
		{ &fake_fxaa, "preset=7",
		  "methods[0]: fxaa: preset=7 is not valid; valid values: 10, 12, 15, 20, 23, 25, 26, 29, 39" },
		{ &fake_fxaa, "7", "methods[0]: fxaa: preset=7 is not valid; valid values: 10, 12, 15, 20, 23, 25, 26, 29, 39" },
		{ &fake_fxaa, "preset=12.0",
		  "methods[0]: fxaa: preset=12.0 is not valid; valid values: 10, 12, 15, 20, 23, 25, 26, 29, 39" },
		{ &fake_fxaa, "subpix=1.5", "methods[0]: fxaa: subpix=1.5 is not valid; valid range: 0 to 1" },
		{ &fake_fxaa, "subpix=nan", "methods[0]: fxaa: subpix=nan is not valid; valid range: 0 to 1" },
		{ &fake_fxaa, "subpix=0x1p-1", "methods[0]: fxaa: subpix=0x1p-1 is not valid; valid range: 0 to 1" },
		{ &fake_fxaa, "subpix=", "methods[0]: fxaa: subpix= is not valid; valid range: 0 to 1" },
		{ &fake_fxaa, "quality=extreme",
		  "methods[0]: fxaa: quality=extreme is not valid; valid values: low, medium, high, ultra" },
		{ &fake_fxaa, "auth=maybe",
		  "methods[0]: fxaa: auth=maybe is not valid; valid values: true, false (or 1, 0, yes, no, on, off)" },
		{ &fake_fxaa, "steps=0", "methods[0]: fxaa: steps=0 is not valid; valid range: 1 to 32 (an integer)" },
		{ &fake_fxaa, "steps=99999999999999999999",
		  "methods[0]: fxaa: steps=99999999999999999999 is not valid; valid range: 1 to 32 (an integer)" },
		{ &fake_fxaa, "speed=2",
		  "methods[0]: fxaa: unknown parameter \"speed\"; valid parameters: preset, subpix, quality, auth, steps" },
		{ &fake_fxaa, "subpix=0.5,subpix=0.5", "methods[0]: fxaa: subpix is given twice" },
		{ &fake_fxaa, "12,preset=12", "methods[0]: fxaa: preset is given twice" },
		{ &fake_fxaa, "subpix", "methods[0]: fxaa: subpix needs a value: write subpix=VALUE" },
		{ &fake_fxaa, "=3", "methods[0]: fxaa: missing parameter name before '=3'" },
		{ &fake_fxaa, "preset=12,,auth=1", "methods[0]: fxaa: empty item in parameter list" },
		{ &fake_rsaa, "8",
		  "methods[0]: rsaa: has no main parameter, so \"8\" needs a name: write key=value with one of: "
		  "preset, subpix, quality, auth, steps" },
	};
	for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
		struct aa_method_params p;
		struct aa_error err = { 0 };
		if (aa_method_parse_params(cases[i].method, cases[i].list, "methods[0]", &p, &err) == 0)
			fail_msg("accepted \"%s\"", cases[i].list);
		assert_int_equal(err.code, AA_ERR_INVALID);
		assert_string_equal(err.path, "methods[0]");
		assert_string_equal(displayed(&err), cases[i].message);
	}
	/* The message itself starts with the method. */
	struct aa_method_params p;
	struct aa_error err = { 0 };
	aa_method_defaults(&fake_fxaa, &p);
	assert_int_equal(aa_method_set_param(&fake_fxaa, &p, "quality", "huge", NULL, &err), -1);
	assert_string_equal(err.message, "fxaa: quality=huge is not valid; valid values: low, medium, high, ultra");
	assert_true(p.v[2] == 2); /* unchanged */
}

static void test_method_parse_registry(void **state)
{
	(void)state;
	const struct aa_method *m = NULL;
	struct aa_method_params p;
	struct aa_error err = { 0 };
	char label[AA_LABEL_MAX];
	assert_int_equal(aa_method_parse("  ssaa  ", "methods[0]", &m, &p, &err), 0);
	assert_string_equal(m->name, "ssaa");
	assert_true(p.v[0] == 16);
	assert_int_equal(aa_method_parse("ssaa:64", "m", &m, &p, &err), 0);
	aa_method_label(m, &p, label, sizeof label);
	assert_string_equal(label, "ssaa:64");
	assert_int_equal(aa_method_parse("none", "m", &m, &p, &err), 0);
	assert_string_equal(m->name, "none");

	/* The message lists every registered method, whichever the registry holds, and user methods. */
	char expected[1024] = "methods[3]: unknown method \"nosuch-aa\"; known methods: ";
	for (int i = 0; i < aa_method_count; i++)
		snprintf(expected + strlen(expected), sizeof expected - strlen(expected), "%s%s", i ? ", " : "",
			 aa_methods[i]->name);
	snprintf(expected + strlen(expected), sizeof expected - strlen(expected),
		 ", user:file=FILE.json (docs/user-methods.md)");
	m = NULL;
	assert_int_equal(aa_method_parse("nosuch-aa:preset=39", "methods[3]", &m, &p, &err), -1);
	assert_null(m);
	assert_int_equal(err.code, AA_ERR_NOT_FOUND);
	assert_string_equal(err.path, "methods[3]");
	assert_string_equal(displayed(&err), expected);
	assert_int_equal(aa_method_parse(NULL, "x", &m, &p, &err), -1);
	char longtext[AA_METHOD_TEXT_MAX + 8];
	memset(longtext, 'a', sizeof longtext - 1);
	longtext[sizeof longtext - 1] = '\0';
	assert_int_equal(aa_method_parse(longtext, "x", &m, &p, &err), -1);
	assert_non_null(strstr(err.message, "longer than"));
}

static void test_round_trip(void **state)
{
	(void)state;
	struct aa_job_spec s, back;
	struct aa_error err;
	assert_int_equal(parse_text("{\"scene\": \"scenes/wires.json\", \"path\": \"static\", \"size\": [320, 200],"
				    " \"frames\": 3, \"first_frame\": 7, \"reference\": {\"samples\": 128},"
				    " \"methods\": [\"ssaa:4\", \"none\", {\"name\": \"ssaa\"}], \"keep_frames\": false,"
				    " \"timing\": {\"repeat\": 7},"
				    " \"name\": \"r\\u00e9sum\\u00e9\"}",
				    &s, &err),
			 0);
	json_t *j = aa_job_spec_to_json(&s);
	assert_non_null(j);
	assert_string_equal(json_string_value(json_object_get(j, "size")), "320x200");
	assert_string_equal(json_string_value(json_array_get(json_object_get(j, "methods"), 0)), "ssaa:4");
	char *text = json_dumps(j, 0);
	json_decref(j);
	memset(&back, 0xab, sizeof back);
	assert_int_equal(parse_text(text, &back, &err), 0);
	free(text);
	assert_spec_equal(&s, &back);

	/* Defaults survive the trip too. */
	aa_job_spec_defaults(&s);
	j = aa_job_spec_to_json(&s);
	memset(&err, 0, sizeof err);
	assert_int_equal(aa_job_spec_from_json(j, &back, &err), 0);
	json_decref(j);
	assert_spec_equal(&s, &back);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_defaults),
		cmocka_unit_test(test_good_job),
		cmocka_unit_test(test_bad_jobs),
		cmocka_unit_test(test_parse_size),
		cmocka_unit_test(test_fake_method_all_types),
		cmocka_unit_test(test_fake_method_errors),
		cmocka_unit_test(test_method_parse_registry),
		cmocka_unit_test(test_round_trip),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
