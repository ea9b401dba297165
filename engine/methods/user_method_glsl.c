/* The GLSL of a user method's pass (docs/user-methods.md): the declarations of the contract (push
 * constants, the inputs the pass reads, its output), then the user's source; and compiling every pass
 * through the SPIR-V cache (glsl_compile.c). */
#include <ctype.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gpu/gpu.h"
#include "methods/glsl_compile.h"
#include "methods/user_method.h"

uint32_t aa_user_push_size(const struct aa_user_method *um)
{
	return 44u + 4u * (uint32_t)um->method.param_count;
}

struct text {
	char *data;
	size_t size, cap;
	bool failed;
};

static void put(struct text *t, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void put(struct text *t, const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	int n = vsnprintf(NULL, 0, fmt, ap);
	va_end(ap);
	if (n < 0 || t->failed)
		return;
	if (t->size + (size_t)n + 1 > t->cap) {
		size_t cap = (t->size + (size_t)n + 1) * 2;
		char *d = realloc(t->data, cap);
		if (!d) {
			t->failed = true;
			return;
		}
		t->data = d;
		t->cap = cap;
	}
	va_start(ap, fmt);
	vsnprintf(t->data + t->size, t->cap - t->size, fmt, ap);
	va_end(ap);
	t->size += (size_t)n;
}

static bool is_extension_line(const char *p, size_t n)
{
	while (n && (*p == ' ' || *p == '\t'))
		p++, n--;
	if (!n || *p != '#')
		return false;
	p++, n--;
	while (n && (*p == ' ' || *p == '\t'))
		p++, n--;
	return n >= 9 && !strncmp(p, "extension", 9);
}

static const char *const input_types[] = {
	[AA_USER_IN_COLOUR] = "sampler2D", [AA_USER_IN_DEPTH] = "sampler2D", [AA_USER_IN_VELOCITY] = "sampler2D",
	[AA_USER_IN_NORMALS] = "sampler2D", [AA_USER_IN_IDS] = "usampler2D", [AA_USER_IN_PASS] = "sampler2D",
	[AA_USER_IN_PREVIOUS] = "sampler2D",
};

char *aa_user_pass_glsl(const struct aa_user_method *um, int i, size_t *size)
{
	const struct aa_user_pass *pass = &um->passes[i];
	const struct aa_method *m = &um->method;
	struct text t = {0};
	put(&t, "#version 450\n");
	/* #extension must come before any declaration: the user's are moved up, their lines left blank */
	for (const char *p = pass->source; *p;) {
		const char *end = strchr(p, '\n');
		size_t n = end ? (size_t)(end - p) : strlen(p);
		if (is_extension_line(p, n))
			put(&t, "%.*s\n", (int)n, p);
		p += n + (end != NULL);
	}
	put(&t, "// aalab user method \"%s\", pass \"%s\": the declarations of docs/user-methods.md\n", um->name,
	    pass->name);
	for (int r = 0; r < pass->read_count; r++)
		put(&t, "layout(set = 0, binding = %d) uniform %s %s;\n", r, input_types[pass->reads[r].input],
		    pass->reads[r].glsl_name);
	if (m->param_count > 0) {
		put(&t, "struct AaParams {\n");
		for (int k = 0; k < m->param_count; k++) {
			const struct aa_param_def *d = &m->params[k];
			put(&t, "\t%s %s;\n", d->type == AA_PARAM_FLOAT ? "float" : d->type == AA_PARAM_BOOL ? "bool" : "int",
			    d->name);
		}
		put(&t, "};\n");
	}
	put(&t, "layout(push_constant) uniform AaPush {\n"
		"\tvec4 aa_size;          // width, height, 1/width, 1/height in pixels\n"
		"\tvec2 aa_jitter;        // this frame's jitter in pixels (0 when the method does not jitter)\n"
		"\tvec2 aa_prev_jitter;   // the previous frame's jitter in pixels\n"
		"\tint aa_frame;          // frame index on the camera path\n"
		"\tint aa_history_frames; // frames since history began: 0 at the first frame and after a cut\n"
		"\tfloat aa_time;         // seconds on the camera path\n"
		"%s};\n", m->param_count > 0 ? "\tAaParams params;\n" : "");
	for (int k = 0; k < m->param_count; k++) {
		const struct aa_param_def *d = &m->params[k];
		for (int c = 0; d->type == AA_PARAM_ENUM && d->choices[c]; c++) {
			char name[2 * AA_USER_NAME_MAX + 4];
			snprintf(name, sizeof name, "%s_%s", d->name, d->choices[c]);
			for (char *p = name; *p; p++)
				*p = (char)toupper((unsigned char)*p);
			put(&t, "const int %s = %d;\n", name, c);
		}
	}
	if (pass->compute) {
		put(&t, "layout(local_size_x = 8, local_size_y = 8) in;\n"
			"layout(set = 0, binding = %d, %s) uniform writeonly image2D aa_output_image;\n"
			"#define aa_pixel ivec2(gl_GlobalInvocationID.xy)\n"
			"void aa_write(vec4 value) { imageStore(aa_output_image, aa_pixel, value); }\n",
		    pass->read_count, aa_user_format_name(pass->format));
	} else {
		put(&t, "layout(location = 0) out vec4 aa_output;\n"
			"#define aa_pixel ivec2(gl_FragCoord.xy)\n"
			"void aa_write(vec4 value) { aa_output = value; }\n");
	}
	put(&t, "#define aa_uv ((vec2(aa_pixel) + 0.5) * aa_size.zw)\n"
		"#define aa_history_valid (aa_history_frames > 0)\n"
		"ivec2 aa_clamp_pixel(ivec2 p) { return clamp(p, ivec2(0), ivec2(aa_size.xy) - 1); }\n"
		"float aa_luma(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }\n"
		"vec3 aa_to_srgb(vec3 c) { c = clamp(c, 0.0, 1.0); return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - "
		"0.055, step(0.0031308, c)); }\n"
		"vec3 aa_from_srgb(vec3 c) { return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), step(0.04045, c)); "
		"}\n");
	if (pass->compute)
		put(&t, "#define main aa_user_main\n");
	put(&t, "#line 1\n");
	for (const char *p = pass->source; *p;) {
		const char *end = strchr(p, '\n');
		size_t n = end ? (size_t)(end - p) : strlen(p);
		put(&t, "%.*s\n", is_extension_line(p, n) ? 0 : (int)n, p);
		p += n + (end != NULL);
	}
	if (pass->compute) /* invocations past the frame's edge (the last groups) do nothing */
		put(&t, "#undef main\nvoid main() { if (all(lessThan(aa_pixel, ivec2(aa_size.xy)))) aa_user_main(); }\n");
	if (t.failed) {
		free(t.data);
		return NULL;
	}
	*size = t.size;
	return t.data;
}

int aa_user_method_compile(struct aa_user_method *um, struct aa_error *err)
{
	if (um->compiled)
		return 0;
	double t0 = aa_now_ms();
	bool all_cached = true;
	for (int i = 0; i < um->pass_count; i++) {
		struct aa_user_pass *pass = &um->passes[i];
		size_t size;
		char *glsl = aa_user_pass_glsl(um, i, &size);
		if (!glsl)
			return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
		bool cached = false;
		int rc = aa_glsl_compile(glsl, size, pass->compute, pass->shader, &pass->spirv, &pass->spirv_size, &cached,
					 err);
		free(glsl);
		if (rc)
			return -1;
		all_cached &= cached;
	}
	um->compiled = true;
	um->compiled_from_cache = all_cached;
	um->compile_ms = aa_now_ms() - t0;
	return 0;
}
