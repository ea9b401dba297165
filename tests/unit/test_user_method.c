/* User methods without a GPU: SHA-256, method files refused with their file and field, parameters and
 * labels as for built-in methods, the needs the frame plan sees, job specs holding user methods, the
 * GLSL a pass is compiled from, and compiling through glslangValidator and the SPIR-V cache. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "types/job.h"
#include "methods/glsl_compile.h"
#include "methods/user_method.h"
#include "util/sha256.h"
#include "methods/methods.h"
#include "run/job_spec.h"

static void test_sha256(void **state)
{
	(void)state;
	/* FIPS 180-4 examples, and a message that fills a block's padding exactly (56 bytes) */
	static const struct {
		const char *text;
		const char *hex;
	} cases[] = {
		{"", "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855"},
		{"abc", "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"},
		{"abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq",
		 "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1"},
	};
	for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
		struct aa_sha256 h;
		uint8_t d[32];
		char hex[65];
		aa_sha256_init(&h);
		aa_sha256_update(&h, cases[i].text, strlen(cases[i].text));
		aa_sha256_final(&h, d);
		aa_sha256_digest_hex(d, hex);
		assert_string_equal(hex, cases[i].hex);
	}
	/* a million 'a', given in pieces that straddle blocks */
	struct aa_sha256 h;
	uint8_t d[32];
	char hex[65], chunk[1000];
	memset(chunk, 'a', sizeof chunk);
	aa_sha256_init(&h);
	for (int i = 0; i < 1000; i++)
		aa_sha256_update(&h, chunk, sizeof chunk);
	aa_sha256_final(&h, d);
	aa_sha256_digest_hex(d, hex);
	assert_string_equal(hex, "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

/* ---------------------------------------------------------------- method files from memory */

static json_t *files;
static struct aa_file_source source;

static void files_reset(void)
{
	json_decref(files);
	files = json_object();
	aa_file_source_json(files, &source);
}

static void file_put(const char *name, const char *text)
{
	json_object_set_new(files, name, json_string(text));
}

static const char *const good_method =
	"{\"name\": \"my-aa\", \"summary\": \"a test\",\n"
	" \"params\": [{\"name\": \"strength\", \"type\": \"float\", \"default\": 0.5, \"min\": 0, \"max\": 1},\n"
	"             {\"name\": \"taps\", \"type\": \"int\", \"default\": 4, \"min\": 1, \"max\": 8},\n"
	"             {\"name\": \"sharp\", \"type\": \"bool\", \"default\": false},\n"
	"             {\"name\": \"mode\", \"type\": \"enum\", \"choices\": [\"soft\", \"hard\"], \"default\": \"hard\"}],\n"
	" \"passes\": [{\"name\": \"edges\", \"shader\": \"edges.frag\", \"reads\": [\"colour\", \"depth\"], \"format\": \"r16f\"},\n"
	"            {\"name\": \"resolve\", \"shader\": \"sub/resolve.comp\",\n"
	"             \"reads\": [\"colour\", \"edges\", {\"input\": \"history\", \"filter\": \"linear\"}, \"velocity\"]}]}";

static void good_files(void)
{
	files_reset();
	file_put("m/my_aa.json", good_method);
	file_put("m/edges.frag", "#extension GL_EXT_samplerless_texture_functions : enable\nvoid main() { aa_write(vec4(1.0)); }\n");
	file_put("m/sub/resolve.comp", "void main() { aa_write(texelFetch(colour, aa_pixel, 0)); }\n");
}

static void test_good_file(void **state)
{
	(void)state;
	good_files();
	const struct aa_method *m = NULL;
	struct aa_method_params p;
	struct aa_error err = {0};
	assert_int_equal(aa_user_method_parse("file=m/my_aa.json, taps=6,mode=soft", &source, "methods[1]", &m, &p,
					      &err), 0);
	const struct aa_user_method *um = aa_user_method_of(m);
	assert_non_null(um);
	assert_true(aa_method_is_user(m));
	assert_string_equal(m->name, "my-aa");
	assert_int_equal(m->param_count, 4);
	assert_true(p.v[0] == 0.5 && p.v[1] == 6 && p.v[2] == 0 && p.v[3] == 0);
	/* what the frame plan sees: depth, velocity and history, nothing else */
	assert_int_equal(m->needs, AA_NEED_DEPTH | AA_NEED_VELOCITY | AA_NEED_HISTORY);
	assert_int_equal(um->pass_count, 2);
	assert_string_equal(um->passes[1].shader, "m/sub/resolve.comp"); /* from the method file's folder */
	assert_true(um->passes[1].compute && !um->passes[0].compute);
	assert_true(um->passes[1].kept && !um->passes[0].kept); /* history is the last pass's previous output */
	assert_int_equal(um->passes[1].reads[1].input, AA_USER_IN_PASS);
	assert_int_equal(um->passes[1].reads[2].input, AA_USER_IN_PREVIOUS);
	assert_true(um->passes[1].reads[2].linear);
	assert_string_equal(um->passes[1].reads[2].glsl_name, "history");
	/* labels as for built-ins: the name, then the non-default parameters; the spec text reads it again */
	char label[128], text[512];
	aa_method_label(m, &p, label, sizeof label);
	assert_string_equal(label, "my-aa:taps=6,mode=soft");
	aa_user_method_spec_text(m, &p, text, sizeof text);
	assert_string_equal(text, "user:file=m/my_aa.json,taps=6,mode=soft");
	/* ranges and names as for built-ins */
	const struct aa_method *m2 = NULL;
	assert_int_equal(aa_user_method_parse("file=m/my_aa.json,strength=1.5", &source, "methods[1]", &m2, &p, &err), -1);
	assert_non_null(strstr(err.message, "my-aa: strength=1.5 is not valid; valid range: 0 to 1"));
	assert_int_equal(aa_user_method_parse("file=m/my_aa.json,mode=medium", &source, "methods[1]", &m2, &p, &err), -1);
	assert_non_null(strstr(err.message, "valid values: soft, hard"));
	assert_null(m2);
	aa_method_unref(m);
}

/* Each bad method file is refused with the file, the field (or line) and what is wrong. */
static void test_bad_files(void **state)
{
	(void)state;
	static const struct {
		const char *json;
		const char *message;
	} cases[] = {
		{"{\"name\": \"x\", \"passes\": [{\"name\": \"a\", \"shader\": \"a.frag\",}]}", "bad.json:1:"},
		{"[]", "bad.json: a method file holds a JSON object"},
		{"{\"passes\": []}", "bad.json: name: missing"},
		{"{\"name\": \"fxaa\", \"passes\": [{\"name\": \"a\", \"shader\": \"a.frag\"}]}", "bad.json: name: \"fxaa\" is a built-in"},
		{"{\"name\": \"Big\", \"passes\": [{\"name\": \"a\", \"shader\": \"a.frag\"}]}", "bad.json: name: \"Big\": a lowercase"},
		{"{\"name\": \"x\", \"passes\": []}", "bad.json: passes: expected an array of 1 to 8"},
		{"{\"name\": \"x\", \"colour\": 1, \"passes\": [{\"name\": \"a\", \"shader\": \"a.frag\"}]}", "bad.json: unknown key \"colour\""},
		{"{\"name\": \"x\", \"passes\": [{\"name\": \"a\", \"shader\": \"a.frag\", \"reads\": [\"velocty\"]}]}",
		 "bad.json: passes[0].reads[0]: unknown input \"velocty\""},
		{"{\"name\": \"x\", \"passes\": [{\"name\": \"a\", \"shader\": \"a.frag\", \"reads\": [\"b\"]}, "
		 "{\"name\": \"b\", \"shader\": \"a.frag\"}]}", "bad.json: passes[0].reads[0]: unknown input \"b\""},
		{"{\"name\": \"x\", \"passes\": [{\"name\": \"a\", \"shader\": \"a.frag\", \"reads\": [\"previous:zz\"]}]}",
		 "bad.json: passes[0].reads[0]: previous:zz names no pass"},
		{"{\"name\": \"x\", \"passes\": [{\"name\": \"a\", \"shader\": \"a.frag\", \"reads\": [{\"input\": \"ids\", "
		 "\"filter\": \"linear\"}]}]}", "bad.json: passes[0].reads[0]: ids cannot be filtered"},
		{"{\"name\": \"x\", \"passes\": [{\"name\": \"a\", \"shader\": \"a.frag\", \"format\": \"rgba8\"}]}",
		 "bad.json: passes[0].format: the last pass is the method's output"},
		{"{\"name\": \"x\", \"passes\": [{\"name\": \"a\", \"shader\": \"a.glsl\"}]}", "bad.json: passes[0].stage: missing"},
		{"{\"name\": \"x\", \"passes\": [{\"name\": \"float\", \"shader\": \"a.frag\"}]}", "bad.json: passes[0].name: \"float\" is a GLSL keyword"},
		{"{\"name\": \"x\", \"passes\": [{\"name\": \"colour\", \"shader\": \"a.frag\"}]}", "bad.json: passes[0].name: \"colour\" is an input"},
		{"{\"name\": \"x\", \"passes\": [{\"name\": \"a\", \"shader\": \"missing.frag\"}]}",
		 "bad.json: passes[0].shader: missing.frag: not among the files"},
		{"{\"name\": \"x\", \"passes\": [{\"name\": \"a\", \"shader\": \"v.frag\"}]}", "v.frag:2: remove #version"},
		{"{\"name\": \"x\", \"params\": [{\"name\": \"s\", \"type\": \"float\", \"default\": 2, \"min\": 0, \"max\": 1}], "
		 "\"passes\": [{\"name\": \"a\", \"shader\": \"a.frag\"}]}", "bad.json: params[0].default: 2 is outside"},
		{"{\"name\": \"x\", \"params\": [{\"name\": \"s\", \"type\": \"float\", \"default\": 0.5}], "
		 "\"passes\": [{\"name\": \"a\", \"shader\": \"a.frag\"}]}", "bad.json: params[0].min: missing"},
		{"{\"name\": \"x\", \"params\": [{\"name\": \"s\", \"type\": \"enum\", \"choices\": [\"a\"], \"default\": \"b\"}], "
		 "\"passes\": [{\"name\": \"a\", \"shader\": \"a.frag\"}]}", "bad.json: params[0].default: expected one of the choices"},
		{"{\"name\": \"x\", \"params\": [{\"name\": \"file\", \"type\": \"bool\", \"default\": true}], "
		 "\"passes\": [{\"name\": \"a\", \"shader\": \"a.frag\"}]}", "bad.json: params[0].name: \"file\" is a GLSL keyword or a name"},
		{"{\"name\": \"x\", \"params\": [{\"name\": \"n\", \"type\": \"string\", \"default\": 1}], "
		 "\"passes\": [{\"name\": \"a\", \"shader\": \"a.frag\"}]}", "bad.json: params[0].type: \"string\" is not a type"},
	};
	for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
		files_reset();
		file_put("bad.json", cases[i].json);
		file_put("a.frag", "void main() { aa_write(vec4(0)); }\n");
		file_put("v.frag", "// a comment\n  #  version 450\nvoid main() {}\n");
		const struct aa_method *m = NULL;
		struct aa_method_params p;
		struct aa_error err = {0};
		if (aa_user_method_parse("file=bad.json", &source, "methods[2]", &m, &p, &err) == 0)
			fail_msg("case %zu accepted: %s", i, cases[i].json);
		assert_null(m);
		assert_string_equal(err.path, "methods[2]");
		if (!strstr(err.message, cases[i].message))
			fail_msg("case %zu: got \"%s\", want \"%s\"", i, err.message, cases[i].message);
	}
	/* no file, and a file that is not there */
	files_reset();
	const struct aa_method *m = NULL;
	struct aa_method_params p;
	struct aa_error err = {0};
	assert_int_equal(aa_user_method_parse("strength=1", &source, "methods[0]", &m, &p, &err), -1);
	assert_non_null(strstr(err.message, "user: needs its method file: user:file=FILE.json"));
	assert_int_equal(aa_user_method_parse("file=nowhere.json", &source, "methods[0]", &m, &p, &err), -1);
	assert_non_null(strstr(err.message, "nowhere.json: not among the files sent with the job"));
	/* without a file source (aa_job_spec_from_json) user methods are refused */
	assert_int_equal(aa_user_method_parse("file=x.json", NULL, "methods[0]", &m, &p, &err), -1);
	assert_non_null(strstr(err.message, "gives none"));
}

/* The limits follow the engine's (AA_MAX_PARAMS parameters; reads within a fragment pass's sources and a
 * compute pass's bindings) and the alpha rule follows how the scene is drawn: at the pixel centre once a
 * frame it is per pixel, as for none and fxaa, history or not; jittered it is per sample, as for taa. */
static int parse_text(const char *json, const char **message)
{
	static char msg[sizeof ((struct aa_error *)0)->message];
	files_reset();
	file_put("l.json", json);
	file_put("a.frag", "void main() { aa_write(vec4(0)); }\n");
	file_put("a.comp", "void main() { aa_write(vec4(0)); }\n");
	const struct aa_method *m = NULL;
	struct aa_method_params p;
	struct aa_error err = {0};
	int rc = aa_user_method_parse("file=l.json", &source, "methods[0]", &m, &p, &err);
	snprintf(msg, sizeof msg, "%s", err.message);
	*message = msg;
	aa_method_unref(m);
	return rc;
}

static void params_json(char *out, size_t size, int count)
{
	int n = snprintf(out, size, "{\"name\": \"lim\", \"params\": [");
	for (int i = 0; i < count; i++)
		n += snprintf(out + n, size - (size_t)n, "%s{\"name\": \"p%d\", \"type\": \"int\", \"default\": 1, "
			      "\"min\": 0, \"max\": 9}", i ? ", " : "", i);
	snprintf(out + n, size - (size_t)n, "], \"passes\": [{\"name\": \"a\", \"shader\": \"a.frag\"}]}");
}

/* A last pass (stage "frag" or "comp") that reads the five frame inputs and `earlier` passes plus `extra`. */
static void reads_json(char *out, size_t size, const char *stage, int extra)
{
	snprintf(out, size, "{\"name\": \"lim\", \"passes\": [{\"name\": \"p0\", \"shader\": \"a.frag\"}, "
		 "{\"name\": \"p1\", \"shader\": \"a.frag\"}, {\"name\": \"p2\", \"shader\": \"a.frag\"}, "
		 "{\"name\": \"last\", \"shader\": \"a.%s\", \"reads\": [\"colour\", \"depth\", \"velocity\", "
		 "\"normals\", \"ids\", \"p0\", \"p1\", \"p2\"%s]}]}", stage, extra ? ", \"previous:p0\"" : "");
}

static void test_limits_and_alpha(void **state)
{
	(void)state;
	char json[4096];
	const char *message;
	params_json(json, sizeof json, AA_MAX_PARAMS);
	assert_int_equal(parse_text(json, &message), 0);
	params_json(json, sizeof json, AA_MAX_PARAMS + 1);
	assert_int_equal(parse_text(json, &message), -1);
	assert_non_null(strstr(message, "l.json: params: expected an array of at most 12 parameters"));
	for (int compute = 0; compute < 2; compute++) {
		reads_json(json, sizeof json, compute ? "comp" : "frag", 0);
		if (parse_text(json, &message))
			fail_msg("8 reads in a %s pass: %s", compute ? "compute" : "fragment", message);
		reads_json(json, sizeof json, compute ? "comp" : "frag", 1);
		assert_int_equal(parse_text(json, &message), -1);
		assert_non_null(strstr(message, "l.json: passes[3].reads: 9 inputs; a pass reads at most 8"));
	}

	good_files(); /* history, no jitter */
	const struct aa_method *m = NULL;
	struct aa_method_params p;
	struct aa_error err = {0};
	assert_int_equal(aa_user_method_parse("file=m/my_aa.json", &source, "methods[0]", &m, &p, &err), 0);
	assert_string_equal(aa_alpha_rule_name(aa_method_alpha_rule(m, &p)), "per-pixel");
	aa_method_unref(m);
	files_reset();
	file_put("j.json", "{\"name\": \"jit\", \"jitter\": {\"sequence\": \"halton\", \"length\": 8}, "
		 "\"passes\": [{\"name\": \"a\", \"shader\": \"a.frag\"}]}");
	file_put("a.frag", "void main() { aa_write(vec4(0)); }\n");
	assert_int_equal(aa_user_method_parse("file=j.json", &source, "methods[0]", &m, &p, &err), 0);
	assert_string_equal(aa_alpha_rule_name(aa_method_alpha_rule(m, &p)), "per-sample");
	aa_method_unref(m);
}

/* Job specs: user methods in both forms, their labels kept apart, the canonical form reads them again,
 * and references are released. */
static void test_job_specs(void **state)
{
	(void)state;
	good_files();
	file_put("other.json", "{\"name\": \"my-aa\", \"passes\": [{\"name\": \"p\", \"shader\": \"m/edges.frag\", "
			      "\"format\": \"rgba16f\"}]}");
	struct aa_job_spec spec, back;
	struct aa_error err = {0};
	json_t *job = json_loads("{\"methods\": [\"none\", \"user:file=m/my_aa.json\", \"user:file=m/my_aa.json,taps=2\","
				 " {\"name\": \"user\", \"params\": {\"file\": \"m/my_aa.json\", \"sharp\": true}}]}", 0, NULL);
	assert_int_equal(aa_job_spec_from_json_files(job, &source, &spec, &err), 0);
	json_decref(job);
	assert_int_equal(spec.method_count, 4);
	assert_string_equal(spec.methods[1].label, "my-aa");
	assert_string_equal(spec.methods[2].label, "my-aa:taps=2");
	assert_string_equal(spec.methods[3].label, "my-aa:sharp=true");
	json_t *canon = aa_job_spec_to_json(&spec);
	json_t *methods = json_object_get(canon, "methods");
	assert_string_equal(json_string_value(json_array_get(methods, 3)), "user:file=m/my_aa.json,sharp=true");
	assert_int_equal(aa_job_spec_from_json_files(canon, &source, &back, &err), 0);
	json_decref(canon);
	for (int i = 0; i < 4; i++) {
		assert_string_equal(spec.methods[i].label, back.methods[i].label);
		assert_memory_equal(&spec.methods[i].params, &back.methods[i].params, sizeof spec.methods[i].params);
	}
	aa_job_spec_release(&back);
	aa_job_spec_release(&spec);

	/* the same file twice with the same parameters, as for built-ins; two files with one name */
	job = json_loads("{\"methods\": [\"user:file=m/my_aa.json\", \"user:file=m/my_aa.json\"]}", 0, NULL);
	assert_int_equal(aa_job_spec_from_json_files(job, &source, &spec, &err), -1);
	json_decref(job);
	assert_non_null(strstr(err.message, "same method and parameters as methods[0]"));
	job = json_loads("{\"methods\": [\"user:file=m/my_aa.json\", \"user:file=other.json\"]}", 0, NULL);
	assert_int_equal(aa_job_spec_from_json_files(job, &source, &spec, &err), -1);
	json_decref(job);
	assert_string_equal(err.path, "methods[1]");
	assert_non_null(strstr(err.message, "different user methods with the same label my-aa"));
	/* refused without files; a bad parameter after a good user method releases it (LeakSanitizer) */
	job = json_loads("{\"methods\": [\"user:file=m/my_aa.json\"]}", 0, NULL);
	assert_int_equal(aa_job_spec_from_json(job, &spec, &err), -1);
	json_decref(job);
	job = json_loads("{\"methods\": [\"user:file=m/my_aa.json\", \"ssaa:3\"]}", 0, NULL);
	assert_int_equal(aa_job_spec_from_json_files(job, &source, &spec, &err), -1);
	json_decref(job);
	job = json_loads("{\"methods\": [\"user:file=m/my_aa.json\"], \"frames\": 0}", 0, NULL);
	assert_int_equal(aa_job_spec_from_json_files(job, &source, &spec, &err), -1);
	json_decref(job);
	/* what the daemon refuses when user methods are off */
	json_t *items = json_loads("[\"user:file=a\", \" user \", {\"name\": \"user\"}, \"users\", \"ssaa\", 3]", 0, NULL);
	const bool user[] = {true, true, true, false, false, false};
	for (size_t i = 0; i < json_array_size(items); i++)
		assert_int_equal(aa_job_method_is_user(json_array_get(items, i)), user[i]);
	json_decref(items);
}

/* The GLSL a pass is compiled from: bindings in the order of reads, the parameters, #extension moved up
 * and the user's text from line 1. */
static void test_pass_glsl(void **state)
{
	(void)state;
	good_files();
	const struct aa_method *m = NULL;
	struct aa_method_params p;
	struct aa_error err = {0};
	assert_int_equal(aa_user_method_parse("file=m/my_aa.json", &source, "m", &m, &p, &err), 0);
	const struct aa_user_method *um = aa_user_method_of(m);
	size_t size;
	char *glsl = aa_user_pass_glsl(um, 0, &size);
	assert_non_null(glsl);
	assert_int_equal(strlen(glsl), size);
	assert_memory_equal(glsl, "#version 450\n#extension GL_EXT_samplerless_texture_functions : enable\n", 70);
	assert_non_null(strstr(glsl, "layout(set = 0, binding = 0) uniform sampler2D colour;\n"));
	assert_non_null(strstr(glsl, "layout(set = 0, binding = 1) uniform sampler2D depth;\n"));
	assert_non_null(strstr(glsl, "struct AaParams {\n\tfloat strength;\n\tint taps;\n\tbool sharp;\n\tint mode;\n};"));
	assert_non_null(strstr(glsl, "const int MODE_SOFT = 0;\nconst int MODE_HARD = 1;\n"));
	/* after #line 1 the user's text, its #extension line blanked so that lines keep their numbers */
	const char *body = strstr(glsl, "#line 1\n");
	assert_non_null(body);
	assert_string_equal(body + 8, "\nvoid main() { aa_write(vec4(1.0)); }\n");
	free(glsl);
	glsl = aa_user_pass_glsl(um, 1, &size);
	assert_non_null(strstr(glsl, "layout(set = 0, binding = 4, rgba16f) uniform writeonly image2D aa_output_image;"));
	assert_non_null(strstr(glsl, "layout(set = 0, binding = 2) uniform sampler2D history;"));
	assert_int_equal(aa_user_push_size(um), 44 + 4 * 4);
	free(glsl);
	aa_method_unref(m);
}

/* glslangValidator: a compile error names the user's file and line; a second compile of the same source
 * comes from the cache, which holds SPIR-V by content. */
static void test_compile(void **state)
{
	(void)state;
	char dir[] = "/tmp/aalab-test-cache.XXXXXX";
	assert_non_null(mkdtemp(dir));
	aa_glsl_set_cache_dir(dir);
	files_reset();
	file_put("c.json", "{\"name\": \"c\", \"passes\": [{\"name\": \"a\", \"shader\": \"shaders/a.frag\"}]}");
	file_put("shaders/a.frag", "// line 1\nvoid main()\n{\n\tfloat x = params_missing;\n\taa_write(vec4(x));\n}\n");
	const struct aa_method *m = NULL;
	struct aa_method_params p;
	struct aa_error err = {0};
	assert_int_equal(aa_user_method_parse("file=c.json", &source, "m", &m, &p, &err), 0);
	struct aa_user_method *um = (struct aa_user_method *)aa_user_method_of(m);
	assert_int_equal(aa_user_method_compile(um, &err), -1);
	assert_int_equal(err.code, AA_ERR_INVALID);
	if (strncmp(err.message, "shaders/a.frag:4: 'params_missing' : undeclared identifier", 58) != 0)
		fail_msg("compile error: %s", err.message);
	aa_method_unref(m);

	file_put("shaders/a.frag", "void main()\n{\n\taa_write(vec4(aa_uv, 0.0, 1.0));\n}\n");
	for (int round = 0; round < 2; round++) {
		assert_int_equal(aa_user_method_parse("file=c.json", &source, "m", &m, &p, &err), 0);
		um = (struct aa_user_method *)aa_user_method_of(m);
		assert_int_equal(aa_user_method_compile(um, &err), 0);
		assert_true(um->passes[0].spirv_size > 20 && um->passes[0].spirv_size % 4 == 0);
		assert_int_equal(um->passes[0].spirv[0], 0x07230203u);
		assert_int_equal(um->compiled_from_cache, round == 1);
		aa_method_unref(m);
	}
	/* one file in the cache, named by a SHA-256 */
	char cmd[200];
	snprintf(cmd, sizeof cmd, "test $(ls %s/spirv | grep -c '^[0-9a-f]\\{64\\}\\.spv$') -eq 1", dir);
	assert_int_equal(system(cmd), 0);
	snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
	assert_int_equal(system(cmd), 0);
	aa_glsl_set_cache_dir(NULL);
}

static int teardown(void **state)
{
	(void)state;
	json_decref(files);
	files = NULL;
	return 0;
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_sha256),
		cmocka_unit_test(test_good_file),
		cmocka_unit_test(test_bad_files),
		cmocka_unit_test(test_limits_and_alpha),
		cmocka_unit_test(test_job_specs),
		cmocka_unit_test(test_pass_glsl),
		cmocka_unit_test(test_compile),
	};
	return cmocka_run_group_tests(tests, NULL, teardown);
}
