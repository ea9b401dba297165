/* Method files (docs/user-methods.md): reading and checking one into a struct aa_user_method, its
 * parameters parsed from the method string like a built-in's, and references. The GLSL each pass is
 * compiled from is user_method_glsl.c's. */
#include <ctype.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <jansson.h>
#include <vulkan/vulkan.h>

#include "gpu/gpu.h"
#include "util/sha256.h"
#include "util/json_text.h"
#include "methods/glsl_compile.h"
#include "methods/user_method.h"
#include "methods/methods.h"

/* ---------------------------------------------------------------- tables */

static const struct {
	const char *name;
	VkFormat vk;
} formats[] = {
	{"rgba16f", VK_FORMAT_R16G16B16A16_SFLOAT}, {"rgba32f", VK_FORMAT_R32G32B32A32_SFLOAT},
	{"rgba8", VK_FORMAT_R8G8B8A8_UNORM},        {"r16f", VK_FORMAT_R16_SFLOAT},
	{"rg16f", VK_FORMAT_R16G16_SFLOAT},         {"r32f", VK_FORMAT_R32_SFLOAT},
};
#define FORMAT_COUNT ((int)(sizeof formats / sizeof formats[0]))

uint32_t aa_user_format_vk(int format)
{
	return format >= 0 && format < FORMAT_COUNT ? (uint32_t)formats[format].vk : (uint32_t)VK_FORMAT_UNDEFINED;
}

const char *aa_user_format_name(int format)
{
	return format >= 0 && format < FORMAT_COUNT ? formats[format].name : "?";
}

/* The fixed inputs: what a pass writes in "reads" and what its shader calls them. */
static const struct {
	const char *name;
	enum aa_user_input input;
} fixed_inputs[] = {
	{"colour", AA_USER_IN_COLOUR}, {"color", AA_USER_IN_COLOUR}, {"depth", AA_USER_IN_DEPTH},
	{"velocity", AA_USER_IN_VELOCITY}, {"normals", AA_USER_IN_NORMALS}, {"ids", AA_USER_IN_IDS},
};
#define FIXED_INPUT_COUNT ((int)(sizeof fixed_inputs / sizeof fixed_inputs[0]))

/* GLSL keywords and reserved words (GLSL 4.60, section 3.6) a pass or parameter name must not be, since
 * names become GLSL identifiers. */
static const char *const glsl_words[] = {
	"const", "uniform", "buffer", "shared", "attribute", "varying", "coherent", "volatile", "restrict",
	"readonly", "writeonly", "atomic_uint", "layout", "centroid", "flat", "smooth", "noperspective", "patch",
	"sample", "invariant", "precise", "break", "continue", "do", "for", "while", "switch", "case", "default",
	"if", "else", "subroutine", "in", "out", "inout", "int", "void", "bool", "true", "false", "float", "double",
	"discard", "return", "uint", "lowp", "mediump", "highp", "precision", "struct", "common", "partition",
	"active", "asm", "class", "union", "enum", "typedef", "template", "this", "resource", "goto", "inline",
	"noinline", "public", "static", "extern", "external", "interface", "long", "short", "half", "fixed",
	"unsigned", "superp", "input", "output", "filter", "sizeof", "cast", "namespace", "using", "main",
	"texture", "demote", "params", "history", "file", "alpha_to_coverage", NULL,
};

/* ---------------------------------------------------------------- errors */

/* "FILE: FIELD: message", with the job's path (methods[2]) in err->path. */
static int __attribute__((format(printf, 5, 6)))
bad(struct aa_error *err, const char *path, const char *file, const char *field, const char *fmt, ...)
{
	char msg[600];
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(msg, sizeof msg, fmt, ap);
	va_end(ap);
	return aa_error_set(err, AA_ERR_INVALID, path, "%s: %s%s%s", file, field, *field ? ": " : "", msg);
}

struct ctx {
	const char *path;   /* the job field */
	const char *file;   /* the method file */
	struct aa_error *err;
};

static int check_keys(struct ctx *c, const json_t *obj, const char *field, const char *const *valid)
{
	const char *key;
	json_t *value;
	json_object_foreach((json_t *)obj, key, value) {
		int i = 0;
		while (valid[i] && strcmp(valid[i], key) != 0)
			i++;
		if (valid[i])
			continue;
		char list[256] = "", k[48];
		for (i = 0; valid[i]; i++)
			snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", i ? ", " : "", valid[i]);
		return bad(c->err, c->path, c->file, field, "unknown key \"%s\"; valid keys: %s", aa_shown_text(key, k, sizeof k),
			   list);
	}
	return 0;
}

/* A string of 1..size-1 bytes without control characters. */
static int get_string(struct ctx *c, const json_t *v, const char *field, char *out, size_t size)
{
	if (!json_is_string(v))
		return bad(c->err, c->path, c->file, field, "expected a string, got %s", aa_json_type_name(v));
	const char *s = json_string_value(v);
	size_t n = json_string_length(v);
	if (n == 0 || n >= size)
		return bad(c->err, c->path, c->file, field, "must be 1 to %zu bytes long", size - 1);
	for (size_t i = 0; i < n; i++)
		if (iscntrl((unsigned char)s[i]) || s[i] == '\0')
			return bad(c->err, c->path, c->file, field, "contains a control character");
	memcpy(out, s, n + 1);
	return 0;
}

/* An identifier the shader can use: a letter, then letters, digits and '_'; lowercase; not a GLSL word,
 * not reserved by GLSL (gl_, __) or by the contract (aa_). */
static int check_identifier(struct ctx *c, const char *name, const char *field)
{
	bool ok = islower((unsigned char)name[0]);
	for (const char *p = name; ok && *p; p++)
		ok = islower((unsigned char)*p) || isdigit((unsigned char)*p) || *p == '_';
	if (!ok)
		return bad(c->err, c->path, c->file, field, "\"%s\" is not a name: a lowercase letter, then lowercase "
			   "letters, digits and '_'", name);
	if (!strncmp(name, "gl_", 3) || !strncmp(name, "aa_", 3) || strstr(name, "__"))
		return bad(c->err, c->path, c->file, field, "\"%s\": names starting with gl_ or aa_, or holding __, are "
			   "reserved", name);
	for (int i = 0; glsl_words[i]; i++)
		if (!strcmp(glsl_words[i], name))
			return bad(c->err, c->path, c->file, field, "\"%s\" is a GLSL keyword or a name the contract uses; "
				   "choose another", name);
	return 0;
}

/* ---------------------------------------------------------------- parameters */

static int get_number(struct ctx *c, const json_t *v, const char *field, bool integer, double *out)
{
	if (integer ? !json_is_integer(v) : !json_is_number(v))
		return bad(c->err, c->path, c->file, field, "expected %s, got %s", integer ? "an integer" : "a number",
			   aa_json_type_name(v));
	*out = json_number_value(v);
	/* push constants carry 32-bit values */
	if (integer && (*out < -2147483648.0 || *out > 2147483647.0))
		return bad(c->err, c->path, c->file, field, "%.0f does not fit a 32-bit int", *out);
	if (!integer && (*out < -3.0e38 || *out > 3.0e38))
		return bad(c->err, c->path, c->file, field, "%g does not fit a 32-bit float", *out);
	return 0;
}

static int parse_param(struct ctx *c, struct aa_user_method *um, int i, const json_t *p)
{
	static const char *const keys[] = {"name", "type", "default", "min", "max", "choices", "help", NULL};
	static const char *const types[] = {"float", "int", "bool", "enum", NULL};
	char field[64], f[96], type[16];
	snprintf(field, sizeof field, "params[%d]", i);
	if (!json_is_object(p))
		return bad(c->err, c->path, c->file, field, "expected an object {\"name\", \"type\", \"default\", ...}, "
			   "got %s", aa_json_type_name(p));
	if (check_keys(c, p, field, keys))
		return -1;
	struct aa_param_def *d = &um->params[i];
	snprintf(f, sizeof f, "%s.name", field);
	const json_t *v = json_object_get(p, "name");
	if (!v)
		return bad(c->err, c->path, c->file, f, "missing");
	if (get_string(c, v, f, um->param_names[i], sizeof um->param_names[i]) ||
	    check_identifier(c, um->param_names[i], f))
		return -1;
	for (int k = 0; k < i; k++)
		if (!strcmp(um->param_names[k], um->param_names[i]))
			return bad(c->err, c->path, c->file, f, "\"%s\" is also params[%d]", um->param_names[i], k);
	d->name = um->param_names[i];
	snprintf(f, sizeof f, "%s.type", field);
	if (!(v = json_object_get(p, "type")))
		return bad(c->err, c->path, c->file, f, "missing; one of float, int, bool, enum");
	if (get_string(c, v, f, type, sizeof type))
		return -1;
	int t = 0;
	while (types[t] && strcmp(types[t], type))
		t++;
	if (!types[t])
		return bad(c->err, c->path, c->file, f, "\"%s\" is not a type; one of float, int, bool, enum", type);
	d->type = t == 0 ? AA_PARAM_FLOAT : t == 1 ? AA_PARAM_INT : t == 2 ? AA_PARAM_BOOL : AA_PARAM_ENUM;
	const json_t *def = json_object_get(p, "default"), *min = json_object_get(p, "min"),
		     *max = json_object_get(p, "max"), *choices = json_object_get(p, "choices");
	snprintf(f, sizeof f, "%s.default", field);
	if (!def)
		return bad(c->err, c->path, c->file, f, "missing: every parameter has a default");
	if (d->type != AA_PARAM_ENUM && choices)
		return bad(c->err, c->path, c->file, field, "\"choices\" is for enum parameters");
	if (d->type == AA_PARAM_FLOAT || d->type == AA_PARAM_INT) {
		bool integer = d->type == AA_PARAM_INT;
		char fmin[96], fmax[96];
		snprintf(fmin, sizeof fmin, "%s.min", field);
		snprintf(fmax, sizeof fmax, "%s.max", field);
		if (!min || !max)
			return bad(c->err, c->path, c->file, min ? fmax : fmin, "missing: numeric parameters have a range "
				   "(min and max)");
		if (get_number(c, min, fmin, integer, &d->min) || get_number(c, max, fmax, integer, &d->max) ||
		    get_number(c, def, f, integer, &d->def))
			return -1;
		if (!(d->min < d->max))
			return bad(c->err, c->path, c->file, fmax, "max (%g) must be above min (%g)", d->max, d->min);
		if (d->def < d->min || d->def > d->max)
			return bad(c->err, c->path, c->file, f, "%g is outside min..max (%g to %g)", d->def, d->min, d->max);
	} else {
		if (min || max)
			return bad(c->err, c->path, c->file, field, "min and max are for float and int parameters");
	}
	if (d->type == AA_PARAM_BOOL) {
		if (!json_is_boolean(def))
			return bad(c->err, c->path, c->file, f, "expected true or false, got %s", aa_json_type_name(def));
		d->def = json_is_true(def);
	}
	if (d->type == AA_PARAM_ENUM) {
		char fc[96];
		snprintf(fc, sizeof fc, "%s.choices", field);
		size_t n = json_array_size(choices);
		if (!json_is_array(choices) || n < 1 || n > 16)
			return bad(c->err, c->path, c->file, fc, "expected an array of 1 to 16 names");
		size_t bytes = 0;
		for (size_t k = 0; k < n; k++)
			bytes += json_string_length(json_array_get(choices, k)) + 1;
		um->choice_text[i] = calloc(1, bytes + 1);
		um->choices[i] = calloc(n + 1, sizeof *um->choices[i]);
		if (!um->choice_text[i] || !um->choices[i])
			return aa_error_set(c->err, AA_ERR_INTERNAL, c->path, "out of memory");
		char *at = um->choice_text[i];
		d->def = -1;
		for (size_t k = 0; k < n; k++) {
			char fk[112], name[AA_USER_NAME_MAX + 1];
			snprintf(fk, sizeof fk, "%s[%zu]", fc, k);
			if (get_string(c, json_array_get(choices, k), fk, name, sizeof name) ||
			    check_identifier(c, name, fk))
				return -1;
			for (size_t j = 0; j < k; j++)
				if (!strcmp(um->choices[i][j], name))
					return bad(c->err, c->path, c->file, fk, "\"%s\" is listed twice", name);
			memcpy(at, name, strlen(name) + 1);
			um->choices[i][k] = at;
			at += strlen(name) + 1;
			if (json_is_string(def) && !strcmp(json_string_value(def), name))
				d->def = (double)k;
		}
		d->choices = (const char *const *)um->choices[i];
		if (d->def < 0)
			return bad(c->err, c->path, c->file, f, "expected one of the choices as a string");
	}
	snprintf(f, sizeof f, "%s.help", field);
	if ((v = json_object_get(p, "help")) && get_string(c, v, f, um->param_help[i], sizeof um->param_help[i]))
		return -1;
	d->help = um->param_help[i];
	return 0;
}

/* ---------------------------------------------------------------- passes */

static int find_pass(const struct aa_user_method *um, const char *name)
{
	for (int i = 0; i < um->pass_count; i++)
		if (!strcmp(um->passes[i].name, name))
			return i;
	return -1;
}

/* Checks a shader's text: the prelude brings #version, and there is no file system to #include from. */
static int check_source(struct ctx *c, const struct aa_user_pass *pass)
{
	if (strlen(pass->source) != pass->source_size)
		return aa_error_set(c->err, AA_ERR_INVALID, c->path, "%s: holds a NUL byte; a shader is text", pass->shader);
	int line = 1;
	for (const char *p = pass->source; *p; line++) {
		const char *end = strchr(p, '\n'), *q = p;
		while (*q == ' ' || *q == '\t')
			q++;
		if (*q == '#') {
			q++;
			while (*q == ' ' || *q == '\t')
				q++;
			if (!strncmp(q, "version", 7))
				return aa_error_set(c->err, AA_ERR_INVALID, c->path, "%s:%d: remove #version: aalab adds "
						    "\"#version 450\" and the declarations of docs/user-methods.md",
						    pass->shader, line);
			if (!strncmp(q, "include", 7))
				return aa_error_set(c->err, AA_ERR_INVALID, c->path, "%s:%d: #include is not supported: "
						    "a pass is one shader file", pass->shader, line);
		}
		if (!end)
			break;
		p = end + 1;
	}
	return 0;
}

/* One entry of "reads": "colour", "history", "previous:NAME", an earlier pass's NAME, or an object
 * {"input": ..., "filter": "nearest"|"linear"}. Passes named later than this one are not known yet, so
 * previous: names are checked once every pass is read (resolve_previous). */
static int parse_read(struct ctx *c, struct aa_user_method *um, int pi, int ri, const json_t *v,
		      char pending[][AA_USER_NAME_MAX + 1])
{
	struct aa_user_read *r = &um->passes[pi].reads[ri];
	char field[96], input[AA_USER_NAME_MAX + 16] = "", filter[16] = "nearest";
	snprintf(field, sizeof field, "passes[%d].reads[%d]", pi, ri);
	if (json_is_object(v)) {
		static const char *const keys[] = {"input", "filter", NULL};
		char f[112];
		if (check_keys(c, v, field, keys))
			return -1;
		snprintf(f, sizeof f, "%s.input", field);
		const json_t *in = json_object_get(v, "input"), *fl = json_object_get(v, "filter");
		if (!in)
			return bad(c->err, c->path, c->file, f, "missing");
		if (get_string(c, in, f, input, sizeof input))
			return -1;
		snprintf(f, sizeof f, "%s.filter", field);
		if (fl && get_string(c, fl, f, filter, sizeof filter))
			return -1;
		if (strcmp(filter, "nearest") && strcmp(filter, "linear"))
			return bad(c->err, c->path, c->file, f, "\"%s\": expected nearest or linear", filter);
	} else if (json_is_string(v)) {
		if (get_string(c, v, field, input, sizeof input))
			return -1;
	} else {
		return bad(c->err, c->path, c->file, field, "expected an input name or {\"input\": ..., \"filter\": ...}, "
			   "got %s", aa_json_type_name(v));
	}
	r->linear = !strcmp(filter, "linear");
	pending[ri][0] = '\0';
	int k = 0;
	while (k < FIXED_INPUT_COUNT && strcmp(fixed_inputs[k].name, input))
		k++;
	if (k < FIXED_INPUT_COUNT) {
		r->input = fixed_inputs[k].input;
		snprintf(r->glsl_name, sizeof r->glsl_name, "%s", input);
		if (r->linear && (r->input == AA_USER_IN_IDS || r->input == AA_USER_IN_DEPTH))
			return bad(c->err, c->path, c->file, field, "%s cannot be filtered; read it with filter nearest", input);
	} else if (!strcmp(input, "history")) {
		r->input = AA_USER_IN_PREVIOUS;
		r->pass = -1; /* the last pass, once the passes are known */
		snprintf(r->glsl_name, sizeof r->glsl_name, "history");
	} else if (!strncmp(input, "previous:", 9)) {
		r->input = AA_USER_IN_PREVIOUS;
		if (check_identifier(c, input + 9, field))
			return -1;
		if (strlen(input + 9) > AA_USER_NAME_MAX)
			return bad(c->err, c->path, c->file, field, "previous:%s names no pass", input + 9);
		snprintf(pending[ri], AA_USER_NAME_MAX + 1, "%.*s", AA_USER_NAME_MAX, input + 9);
		snprintf(r->glsl_name, sizeof r->glsl_name, "previous_%s", input + 9);
	} else {
		int p = find_pass(um, input);
		if (p < 0 || p >= pi) {
			char known[200] = "";
			for (int j = 0; j < pi; j++)
				snprintf(known + strlen(known), sizeof known - strlen(known), ", %s", um->passes[j].name);
			return bad(c->err, c->path, c->file, field, "unknown input \"%s\"; inputs: colour, depth, velocity, "
				   "normals, ids, history, previous:PASS%s%s", input, *known ? ", and the earlier passes" : "",
				   known);
		}
		r->input = AA_USER_IN_PASS;
		r->pass = p;
		snprintf(r->glsl_name, sizeof r->glsl_name, "%s", input);
	}
	for (int j = 0; j < ri; j++)
		if (!strcmp(um->passes[pi].reads[j].glsl_name, r->glsl_name))
			return bad(c->err, c->path, c->file, field, "\"%s\" is also reads[%d]", input, j);
	return 0;
}

static int parse_pass(struct ctx *c, struct aa_user_method *um, const struct aa_file_source *src, int i,
		      const json_t *p, char pending[][AA_USER_MAX_READS][AA_USER_NAME_MAX + 1])
{
	static const char *const keys[] = {"name", "shader", "stage", "reads", "format", NULL};
	static const char *const reserved[] = {"scene", "shadow", NULL};
	struct aa_user_pass *pass = &um->passes[i];
	char field[48], f[64], shader[AA_USER_PATH_MAX], text[16];
	snprintf(field, sizeof field, "passes[%d]", i);
	if (!json_is_object(p))
		return bad(c->err, c->path, c->file, field, "expected an object {\"name\", \"shader\", \"reads\", "
			   "\"format\"}, got %s", aa_json_type_name(p));
	if (check_keys(c, p, field, keys))
		return -1;
	const json_t *v;
	snprintf(f, sizeof f, "%s.name", field);
	if (!(v = json_object_get(p, "name")))
		return bad(c->err, c->path, c->file, f, "missing");
	if (get_string(c, v, f, pass->name, sizeof pass->name) || check_identifier(c, pass->name, f))
		return -1;
	for (int k = 0; reserved[k]; k++)
		if (!strcmp(pass->name, reserved[k]))
			return bad(c->err, c->path, c->file, f, "\"%s\" names the engine's own pass; choose another", pass->name);
	for (int k = 0; k < FIXED_INPUT_COUNT; k++)
		if (!strcmp(pass->name, fixed_inputs[k].name))
			return bad(c->err, c->path, c->file, f, "\"%s\" is an input's name; choose another", pass->name);
	if (find_pass(um, pass->name) >= 0)
		return bad(c->err, c->path, c->file, f, "\"%s\" names an earlier pass too", pass->name);

	snprintf(f, sizeof f, "%s.shader", field);
	if (!(v = json_object_get(p, "shader")))
		return bad(c->err, c->path, c->file, f, "missing: the GLSL file of this pass (.frag or .comp)");
	if (get_string(c, v, f, shader, sizeof shader))
		return -1;
	aa_file_join(c->file, shader, pass->shader, sizeof pass->shader);
	const char *dot = strrchr(shader, '.');
	int stage = dot && !strcmp(dot, ".frag") ? 0 : dot && !strcmp(dot, ".comp") ? 1 : -1;
	snprintf(f, sizeof f, "%s.stage", field);
	if ((v = json_object_get(p, "stage"))) {
		if (get_string(c, v, f, text, sizeof text))
			return -1;
		stage = !strcmp(text, "fragment") ? 0 : !strcmp(text, "compute") ? 1 : -2;
		if (stage == -2)
			return bad(c->err, c->path, c->file, f, "\"%s\": expected fragment or compute", text);
	}
	if (stage < 0)
		return bad(c->err, c->path, c->file, f, "missing: %s ends in neither .frag nor .comp; give \"stage\": "
			   "\"fragment\" or \"compute\"", shader);
	pass->compute = stage == 1;

	snprintf(f, sizeof f, "%s.format", field);
	pass->format = 0;
	if ((v = json_object_get(p, "format"))) {
		if (get_string(c, v, f, text, sizeof text))
			return -1;
		pass->format = -1;
		for (int k = 0; k < FORMAT_COUNT; k++)
			if (!strcmp(formats[k].name, text))
				pass->format = k;
		if (pass->format < 0)
			return bad(c->err, c->path, c->file, f, "\"%s\": expected rgba16f, rgba32f, rgba8, r16f, rg16f or "
				   "r32f", text);
	}

	snprintf(f, sizeof f, "%s.reads", field);
	const json_t *reads = json_object_get(p, "reads");
	if (reads && !json_is_array(reads))
		return bad(c->err, c->path, c->file, f, "expected an array of inputs, got %s", aa_json_type_name(reads));
	if (json_array_size(reads) > AA_USER_MAX_READS)
		return bad(c->err, c->path, c->file, f, "%zu inputs; a pass reads at most %d", json_array_size(reads),
			   AA_USER_MAX_READS);
	pass->read_count = (int)json_array_size(reads);
	um->pass_count = i; /* the earlier passes, which reads may name */
	for (int r = 0; r < pass->read_count; r++)
		if (parse_read(c, um, i, r, json_array_get(reads, r), pending[i]))
			return -1;
	um->pass_count = i + 1;

	if (src->read(src->ctx, pass->shader, &pass->source, &pass->source_size, c->err)) {
		snprintf(c->err->path, sizeof c->err->path, "%s", c->path);
		aa_error_prefix(c->err, "%s: %s.shader", c->file, field);
		return -1;
	}
	return check_source(c, pass);
}

/* previous:NAME may name any pass, this one or a later one; "history" is the last pass's output. */
static int resolve_previous(struct ctx *c, struct aa_user_method *um,
			    char pending[][AA_USER_MAX_READS][AA_USER_NAME_MAX + 1])
{
	for (int i = 0; i < um->pass_count; i++)
		for (int r = 0; r < um->passes[i].read_count; r++) {
			struct aa_user_read *rd = &um->passes[i].reads[r];
			if (rd->input != AA_USER_IN_PREVIOUS)
				continue;
			rd->pass = pending[i][r][0] ? find_pass(um, pending[i][r]) : um->pass_count - 1;
			if (rd->pass < 0) {
				char field[64];
				snprintf(field, sizeof field, "passes[%d].reads[%d]", i, r);
				return bad(c->err, c->path, c->file, field, "previous:%s names no pass", pending[i][r]);
			}
			um->passes[rd->pass].kept = true;
		}
	return 0;
}

/* ---------------------------------------------------------------- the method */

static void user_method_free(struct aa_user_method *um)
{
	for (int i = 0; i < AA_USER_MAX_PASSES; i++) {
		free(um->passes[i].source);
		free(um->passes[i].spirv);
	}
	for (int i = 0; i < AA_MAX_PARAMS; i++) {
		free(um->choice_text[i]);
		free(um->choices[i]);
	}
	free(um);
}

static unsigned needs_of(const struct aa_user_method *um)
{
	unsigned needs = 0;
	for (int i = 0; i < um->pass_count; i++)
		for (int r = 0; r < um->passes[i].read_count; r++)
			switch (um->passes[i].reads[r].input) {
			case AA_USER_IN_DEPTH: needs |= AA_NEED_DEPTH; break;
			case AA_USER_IN_VELOCITY: needs |= AA_NEED_VELOCITY; break;
			case AA_USER_IN_NORMALS: needs |= AA_NEED_GBUFFER; break;
			case AA_USER_IN_IDS: needs |= AA_NEED_IDS; break;
			case AA_USER_IN_PREVIOUS: needs |= AA_NEED_HISTORY; break;
			case AA_USER_IN_COLOUR:
			case AA_USER_IN_PASS: break;
			}
	return needs;
}

static void hash_method(struct aa_user_method *um, const char *text, size_t size)
{
	struct aa_sha256 h;
	uint8_t digest[32];
	aa_sha256_init(&h);
	aa_sha256_update(&h, text, size);
	for (int i = 0; i < um->pass_count; i++) {
		aa_sha256_update(&h, um->passes[i].shader, strlen(um->passes[i].shader) + 1);
		aa_sha256_update(&h, um->passes[i].source, um->passes[i].source_size);
	}
	aa_sha256_final(&h, digest);
	aa_sha256_digest_hex(digest, um->sha256);
}

static int parse_method(struct ctx *c, struct aa_user_method *um, const struct aa_file_source *src, const char *text,
			size_t size)
{
	static const char *const keys[] = {"name", "summary", "params", "jitter", "passes", NULL};
	json_error_t jerr;
	json_t *root = json_loadb(text, size, JSON_REJECT_DUPLICATES, &jerr);
	if (!root)
		return aa_error_set(c->err, AA_ERR_INVALID, c->path, "%s:%d:%d: %s", c->file, jerr.line, jerr.column,
				    jerr.text);
	int rc = -1;
	if (!json_is_object(root)) {
		bad(c->err, c->path, c->file, "", "a method file holds a JSON object, not %s", aa_json_type_name(root));
		goto out;
	}
	if (check_keys(c, root, "", keys))
		goto out;
	const json_t *v = json_object_get(root, "name");
	if (!v) {
		bad(c->err, c->path, c->file, "name", "missing: the method's name, its label in results");
		goto out;
	}
	if (get_string(c, v, "name", um->name, sizeof um->name))
		goto out;
	bool name_ok = islower((unsigned char)um->name[0]);
	for (const char *p = um->name; name_ok && *p; p++)
		name_ok = islower((unsigned char)*p) || isdigit((unsigned char)*p) || *p == '-' || *p == '_' || *p == '.';
	if (!name_ok) {
		bad(c->err, c->path, c->file, "name", "\"%s\": a lowercase letter, then lowercase letters, digits, '-', "
		    "'_' and '.'", um->name);
		goto out;
	}
	if (aa_method_find(um->name) || !strcmp(um->name, "reference") || !strcmp(um->name, "user")) {
		bad(c->err, c->path, c->file, "name", "\"%s\" is a built-in method's name; choose another, so that results "
		    "tell them apart", um->name);
		goto out;
	}
	if ((v = json_object_get(root, "summary")) && get_string(c, v, "summary", um->summary, sizeof um->summary))
		goto out;
	if ((v = json_object_get(root, "params"))) {
		if (!json_is_array(v) || json_array_size(v) > AA_MAX_PARAMS) {
			bad(c->err, c->path, c->file, "params", "expected an array of at most %d parameters", AA_MAX_PARAMS);
			goto out;
		}
		for (size_t i = 0; i < json_array_size(v); i++)
			if (parse_param(c, um, (int)i, json_array_get(v, i)))
				goto out;
		um->method.param_count = (int)json_array_size(v);
	}
	if ((v = json_object_get(root, "jitter"))) {
		static const char *const jkeys[] = {"sequence", "length", NULL};
		const json_t *seq = json_object_get(v, "sequence"), *len = json_object_get(v, "length");
		if (!json_is_object(v)) {
			bad(c->err, c->path, c->file, "jitter", "expected {\"sequence\": \"halton\", \"length\": 8 or 16}");
			goto out;
		}
		if (check_keys(c, v, "jitter", jkeys))
			goto out;
		if (!json_is_string(seq) || strcmp(json_string_value(seq), "halton")) {
			bad(c->err, c->path, c->file, "jitter.sequence", "expected \"halton\" (Halton(2,3), as taa)");
			goto out;
		}
		um->jitter_length = len ? (int)json_integer_value(len) : 16;
		if ((len && !json_is_integer(len)) || (um->jitter_length != 8 && um->jitter_length != 16)) {
			bad(c->err, c->path, c->file, "jitter.length", "expected 8 or 16 points per cycle");
			goto out;
		}
	}
	const json_t *passes = json_object_get(root, "passes");
	size_t n = json_array_size(passes);
	if (!json_is_array(passes) || n < 1 || n > AA_USER_MAX_PASSES) {
		bad(c->err, c->path, c->file, "passes", "expected an array of 1 to %d passes", AA_USER_MAX_PASSES);
		goto out;
	}
	char pending[AA_USER_MAX_PASSES][AA_USER_MAX_READS][AA_USER_NAME_MAX + 1];
	for (size_t i = 0; i < n; i++)
		if (parse_pass(c, um, src, (int)i, json_array_get(passes, i), pending))
			goto out;
	if (resolve_previous(c, um, pending))
		goto out;
	const int last = um->pass_count - 1;
	if (um->passes[last].format != 0 && um->passes[last].format != 1) {
		char field[48];
		snprintf(field, sizeof field, "passes[%d].format", last);
		bad(c->err, c->path, c->file, field, "the last pass is the method's output: rgba16f or rgba32f (linear "
		    "colour), not %s", aa_user_format_name(um->passes[last].format));
		goto out;
	}
	rc = 0;
out:
	json_decref(root);
	return rc;
}

int aa_user_method_load(const char *file, const struct aa_file_source *src, const char *path,
			struct aa_user_method **out, struct aa_error *err)
{
	if (!src || !src->read)
		return aa_error_set(err, AA_ERR_INVALID, path, "user methods read a method file, and this caller gives "
				    "none (docs/user-methods.md)");
	if (strlen(file) >= AA_USER_PATH_MAX)
		return aa_error_set(err, AA_ERR_LIMIT, path, "user: file names are at most %d bytes", AA_USER_PATH_MAX - 1);
	struct aa_user_method *um = calloc(1, sizeof *um);
	if (!um)
		return aa_error_set(err, AA_ERR_INTERNAL, path, "out of memory");
	atomic_init(&um->refs, 1);
	snprintf(um->file, sizeof um->file, "%s", file);
	char *text = NULL;
	size_t size = 0;
	struct ctx c = {.path = path, .file = file, .err = err};
	if (src->read(src->ctx, file, &text, &size, err)) {
		snprintf(err->path, sizeof err->path, "%s", path);
		aa_error_prefix(err, "user");
		user_method_free(um);
		return -1;
	}
	if (parse_method(&c, um, src, text, size)) {
		free(text);
		user_method_free(um);
		return -1;
	}
	hash_method(um, text, size);
	free(text);
	if (!um->summary[0])
		snprintf(um->summary, sizeof um->summary, "user method, %d pass%s", um->pass_count,
			 um->pass_count > 1 ? "es" : "");
	snprintf(um->seed, sizeof um->seed, "user method file %s", um->file);
	um->method = aa_user_method_functions;
	um->method.name = um->name;
	um->method.summary = um->summary;
	um->method.seed = um->seed;
	um->method.params = um->params;
	for (int i = 0; i < AA_MAX_PARAMS && um->params[i].name; i++)
		um->method.param_count = i + 1;
	um->method.needs = needs_of(um);
	/* the scene is drawn once a frame at one sample a pixel: at the pixel centre alpha is tested once per
	 * pixel, as for none and fxaa; jittered, every frame tests a new sample point, as for taa */
	um->method.alpha_rule = um->jitter_length ? AA_ALPHA_PER_SAMPLE : AA_ALPHA_PER_PIXEL;
	*out = um;
	return 0;
}

bool aa_method_is_user(const struct aa_method *m)
{
	return m && m->create_self == aa_user_method_create;
}

const struct aa_user_method *aa_user_method_of(const struct aa_method *m)
{
	/* method is the first member, so the method's address is the user method's */
	return aa_method_is_user(m) ? (const struct aa_user_method *)(const void *)m : NULL;
}

void aa_method_ref(const struct aa_method *m)
{
	if (aa_method_is_user(m))
		atomic_fetch_add(&((struct aa_user_method *)(void *)m)->refs, 1);
}

void aa_method_unref(const struct aa_method *m)
{
	if (aa_method_is_user(m) && atomic_fetch_sub(&((struct aa_user_method *)(void *)m)->refs, 1) == 1)
		user_method_free((struct aa_user_method *)(void *)m);
}

int aa_user_method_parse(const char *list, const struct aa_file_source *src, const char *path,
			 const struct aa_method **method, struct aa_method_params *params, struct aa_error *err)
{
	char buf[AA_METHOD_TEXT_MAX], rest[AA_METHOD_TEXT_MAX] = "", file[AA_USER_PATH_MAX] = "";
	if (strlen(list) >= sizeof buf)
		return aa_error_set(err, AA_ERR_INVALID, path, "user: the parameter list is longer than %zu bytes",
				    sizeof buf - 1);
	memcpy(buf, list, strlen(list) + 1);
	/* file=... is the user method's own item; the others are the method file's parameters */
	char *save = NULL;
	for (char *item = buf; item; item = save) {
		char *comma = strchr(item, ',');
		save = comma ? comma + 1 : NULL;
		if (comma)
			*comma = '\0';
		while (isspace((unsigned char)*item))
			item++;
		size_t n = strlen(item);
		while (n && isspace((unsigned char)item[n - 1]))
			item[--n] = '\0';
		char *eq = strchr(item, '=');
		size_t key = eq ? (size_t)(eq - item) : n;
		while (key && isspace((unsigned char)item[key - 1]))
			key--;
		if (key == 4 && !strncmp(item, "file", 4)) {
			const char *value = eq ? eq + 1 : "";
			while (isspace((unsigned char)*value))
				value++;
			if (file[0])
				return aa_error_set(err, AA_ERR_INVALID, path, "user: file is given twice");
			if (!*value || strlen(value) >= sizeof file)
				return aa_error_set(err, AA_ERR_INVALID, path, "user: file=FILE.json names the method file "
						    "(at most %zu bytes)", sizeof file - 1);
			snprintf(file, sizeof file, "%s", value);
			continue;
		}
		snprintf(rest + strlen(rest), sizeof rest - strlen(rest), "%s%s", rest[0] ? "," : "", item);
	}
	if (!file[0])
		return aa_error_set(err, AA_ERR_INVALID, path, "user: needs its method file: user:file=FILE.json"
				    "[,PARAM=VALUE...] (docs/user-methods.md)");
	struct aa_user_method *um;
	if (aa_user_method_load(file, src, path, &um, err))
		return -1;
	if (rest[0] ? aa_method_parse_params(&um->method, rest, path, params, err) :
		      (aa_method_defaults(&um->method, params), 0)) {
		aa_method_unref(&um->method);
		return -1;
	}
	*method = &um->method;
	return 0;
}

void aa_user_method_spec_text(const struct aa_method *m, const struct aa_method_params *p, char *out, size_t size)
{
	const struct aa_user_method *um = aa_user_method_of(m);
	if (!um || size == 0) {
		if (size)
			out[0] = '\0';
		return;
	}
	int n = snprintf(out, size, "user:file=%s", um->file);
	for (int i = 0; i < m->param_count && n >= 0 && (size_t)n < size; i++) {
		if (p->v[i] == m->params[i].def)
			continue;
		char value[64];
		aa_method_param_text(m, p, i, value, sizeof value);
		n += snprintf(out + n, size - (size_t)n, ",%s=%s", m->params[i].name, value);
	}
}
