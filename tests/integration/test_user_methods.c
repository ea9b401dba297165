/* User methods on the GPU: a pass-through user method is measured exactly as the built-in `copy` (the
 * same images, metrics, passes and memory); the contract's values reach the shader (parameters of every
 * type, frame size, jitter, frame index, history and pixel coordinates, in fragment and compute passes);
 * the frame plan runs only what a method reads; a compile error fails the job with file and line; and
 * timing repeats leave a user method's history alone, as for built-in temporal methods. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "fixture.h"
#include "methods/glsl_compile.h"
#include "methods/user_method.h"
#include "methods/jitter.h"
#include "run/job_spec.h"

static json_t *files;

static void put(const char *name, const char *text)
{
	json_object_set_new(files, name, json_string(text));
}

/* A job of method strings over the files above. */
static void spec_of(struct aa_job_spec *spec, const char *scene, const char *methods_json, int w, int h, int frames,
		    int first_frame, int repeat)
{
	char text[1024];
	snprintf(text, sizeof text, "{\"scene\": \"%s\", \"size\": [%d, %d], \"frames\": %d, \"first_frame\": %d, "
		 "\"reference\": {\"samples\": 4}, \"timing\": {\"repeat\": %d}, \"methods\": %s}",
		 scene, w, h, frames, first_frame, repeat, methods_json);
	json_t *job = json_loads(text, 0, NULL);
	assert_non_null(job);
	struct aa_file_source src;
	aa_file_source_json(files, &src);
	struct aa_error err = {0};
	if (aa_job_spec_from_json_files(job, &src, spec, &err))
		fail_msg("%s: %s", err.path, err.message);
	json_decref(job);
}

/* Every scored frame's 8-bit image and linear colour, per method. */
#define MAX_FRAMES 4
struct frames {
	uint8_t *image[AA_MAX_METHODS][MAX_FRAMES];
	float *linear[AA_MAX_METHODS][MAX_FRAMES];
	size_t pixels;
};

static int keep_frames(const struct aa_event *ev, void *user)
{
	struct frames *f = user;
	if (ev->type != AA_EVENT_METHOD_FRAME || ev->frame_ordinal >= MAX_FRAMES)
		return 0;
	f->pixels = (size_t)ev->image->width * ev->image->height;
	uint8_t **img = &f->image[ev->method_index][ev->frame_ordinal];
	float **lin = &f->linear[ev->method_index][ev->frame_ordinal];
	*img = realloc(*img, f->pixels * 4);
	*lin = realloc(*lin, f->pixels * 4 * sizeof(float));
	memcpy(*img, ev->image->pixels, f->pixels * 4);
	memcpy(*lin, ev->linear->pixels, f->pixels * 4 * sizeof(float));
	return 0;
}

static void frames_free(struct frames *f)
{
	for (int m = 0; m < AA_MAX_METHODS; m++)
		for (int k = 0; k < MAX_FRAMES; k++) {
			free(f->image[m][k]);
			free(f->linear[m][k]);
		}
}

static const struct aa_plan_entry *plan_entry(const struct aa_job_result *r, const char *pass)
{
	for (int i = 0; i < r->plan_count; i++)
		if (!strcmp(r->plan[i].pass, pass))
			return &r->plan[i];
	fail_msg("no %s in the plan", pass);
	return NULL;
}

/* `copy` is one scene pass and a full-screen texelFetch copy into RGBA16F; so is this user method. */
static void test_passthrough_is_copy(void **state)
{
	(void)state;
	put("pass.json", "{\"name\": \"passthrough\", \"passes\": [{\"name\": \"copy\", \"shader\": \"pass.frag\", "
			 "\"reads\": [\"colour\"]}]}");
	put("pass.frag", "void main() { aa_write(texelFetch(colour, aa_pixel, 0)); }\n");
	struct aa_job_spec spec;
	/* hard-edges has a shadow-casting light: both methods pay for the shadow map alike */
	spec_of(&spec, "hard-edges", "[\"copy\", \"user:file=pass.json\"]", 96, 54, 2, 0, 1);
	struct frames f = {0};
	struct aa_job_result *r = fixture_run(&spec, NULL, keep_frames, &f);
	const struct aa_method_result *copy = &r->methods[0], *user = &r->methods[1];
	assert_string_equal(user->label, "passthrough");
	for (int k = 0; k < 2; k++) {
		assert_memory_equal(f.image[0][k], f.image[1][k], f.pixels * 4);
		assert_true(copy->frames[k].metrics.mse == user->frames[k].metrics.mse);
		assert_true(copy->frames[k].metrics.ssim == user->frames[k].metrics.ssim);
		assert_int_equal(user->frames[k].nonfinite, 0);
		/* the same passes, timed by the same spans */
		assert_int_equal(copy->frames[k].pass_count, user->frames[k].pass_count);
		for (int p = 0; p < copy->frames[k].pass_count; p++)
			assert_string_equal(copy->frames[k].passes[p].name, user->frames[k].passes[p].name);
	}
	assert_int_equal(user->frames[0].pass_count, 3); /* shadow-map, scene, copy */
	assert_string_equal(user->frames[0].passes[2].name, "copy");
	/* the same images: scene colour and depth, and an RGBA16F output */
	assert_int_equal(copy->memory_bytes, user->memory_bytes);
	assert_int_equal(user->memory_count, 3);
	/* nothing extra in the plan */
	assert_false(plan_entry(r, "velocity")->ran);
	assert_false(plan_entry(r, "model-ids")->ran);
	assert_false(plan_entry(r, "history")->ran);
	printf("copy %.3f ms, passthrough %.3f ms (GPU, frame 1: one sample each)\n", copy->frames[1].gpu_ms,
	       user->frames[1].gpu_ms);
	fixture_free(r);
	frames_free(&f);
	aa_job_spec_release(&spec);
}

/* The values of docs/user-methods.md, written out by the shaders and read back exactly (RGBA32F):
 * row 0 the parameters, row 1 the jitter, row 2 aa_size, and every other pixel its coordinates, frame
 * index, history count and the previous frame's value, from a compute pass. */
static void test_contract_values(void **state)
{
	(void)state;
	put("values.json",
	    "{\"name\": \"values\", \"jitter\": {\"sequence\": \"halton\", \"length\": 8},\n"
	    " \"params\": [{\"name\": \"f\", \"type\": \"float\", \"default\": 0.5, \"min\": -1, \"max\": 1},\n"
	    "   {\"name\": \"i\", \"type\": \"int\", \"default\": 1, \"min\": -10, \"max\": 10},\n"
	    "   {\"name\": \"b\", \"type\": \"bool\", \"default\": false},\n"
	    "   {\"name\": \"e\", \"type\": \"enum\", \"choices\": [\"zero\", \"one\", \"two\"], \"default\": \"zero\"}],\n"
	    " \"passes\": [{\"name\": \"head\", \"shader\": \"head.frag\", \"reads\": [\"velocity\"], \"format\": \"rgba32f\"},\n"
	    "   {\"name\": \"coords\", \"shader\": \"coords.comp\", \"reads\": [\"head\", \"previous:coords\"],\n"
	    "    \"format\": \"rgba32f\"}]}");
	put("head.frag",
	    "void main()\n{\n"
	    "\tvec4 v = texelFetch(velocity, aa_pixel, 0) * 0.0;\n"
	    "\tif (aa_pixel.y == 0)\n"
	    "\t\taa_write(v + vec4(params.f, float(params.i), params.b ? 1.0 : 0.0, params.e == E_TWO ? 2.0 : -1.0));\n"
	    "\telse if (aa_pixel.y == 1)\n"
	    "\t\taa_write(v + vec4(aa_jitter, aa_prev_jitter));\n"
	    "\telse\n"
	    "\t\taa_write(v + aa_size);\n}\n");
	put("coords.comp",
	    "void main()\n{\n"
	    "\tif (aa_pixel.y < 3) {\n\t\taa_write(texelFetch(head, aa_pixel, 0));\n\t\treturn;\n\t}\n"
	    "\tfloat previous = texelFetch(previous_coords, aa_pixel, 0).b;\n"
	    "\taa_write(vec4(aa_pixel, float(aa_frame * 10 + aa_history_frames), previous));\n}\n");
	struct aa_job_spec spec;
	/* 37x21: neither side a multiple of the compute pass's 8x8 groups */
	spec_of(&spec, "thin-wires", "[\"user:file=values.json,f=-0.25,i=-3,b=true,e=two\"]", 37, 21, 2, 5, 1);
	assert_string_equal(spec.methods[0].label, "values:f=-0.25,i=-3,b=true,e=two");
	struct frames f = {0};
	struct aa_job_result *r = fixture_run(&spec, NULL, keep_frames, &f);
	const int w = 37, h = 21;
	for (int k = 0; k < 2; k++) {
		const float *px = f.linear[0][k];
		const int frame = 5 + k;
		float jitter[2], prev[2];
		aa_jitter_halton(frame, 8, jitter);
		aa_jitter_halton(frame - 1, 8, prev);
		const float row0[4] = {-0.25f, -3.0f, 1.0f, 2.0f}, row1[4] = {jitter[0], jitter[1], prev[0], prev[1]};
		const float row2[4] = {(float)w, (float)h, 1.0f / w, 1.0f / h};
		for (int c = 0; c < 4; c++) {
			assert_true(px[(0 * w + 7) * 4 + c] == row0[c]);
			assert_true(px[(1 * w + 30) * 4 + c] == row1[c]);
			assert_true(px[(2 * w + 36) * 4 + c] == row2[c]);
		}
		for (int y = 3; y < h; y++)
			for (int x = 0; x < w; x++) {
				const float *p = &px[(y * w + x) * 4];
				/* pixel (0, 0) is the top-left; frame 5 has no history (what its previous image
				 * holds is undefined: the warm-up's frame), frame 6 one frame, and sees frame 5's */
				if (p[0] != x || p[1] != y || p[2] != frame * 10 + k || (k && p[3] != 50.0f))
					fail_msg("frame %d pixel (%d, %d): %g %g %g %g", frame, x, y, p[0], p[1], p[2], p[3]);
			}
	}
	/* reading velocity makes the velocity pass run, and the method pays for the image */
	const struct aa_plan_entry *v = plan_entry(r, "velocity");
	assert_true(v->ran);
	assert_non_null(strstr(v->reason, "values:f=-0.25"));
	assert_true(plan_entry(r, "history")->ran);
	assert_false(plan_entry(r, "model-ids")->ran);
	const struct aa_method_result *m = &r->methods[0];
	bool velocity = false, coords_b = false;
	for (int i = 0; i < m->memory_count; i++) {
		velocity |= !strcmp(m->memory[i].name, "scene velocity");
		coords_b |= !strcmp(m->memory[i].name, "coords B");
	}
	assert_true(velocity && coords_b);
	assert_string_equal(m->frames[0].passes[1].name, "head");
	assert_string_equal(m->frames[0].passes[2].name, "coords");
	fixture_free(r);
	frames_free(&f);
	aa_job_spec_release(&spec);
}

/* A shader that does not compile fails the job as bad input, naming the file and the line. */
static void test_compile_error(void **state)
{
	(void)state;
	put("broken.json", "{\"name\": \"broken\", \"passes\": [{\"name\": \"a\", \"shader\": \"broken.frag\", "
			   "\"reads\": [\"colour\"]}]}");
	put("broken.frag", "void main()\n{\n\taa_write(texelFetch(colour, aa_pixel, 0))\n}\n");
	struct aa_job_spec spec;
	spec_of(&spec, "thin-wires", "[\"none\", \"user:file=broken.json\"]", 32, 18, 1, 0, 1);
	struct aa_job_result *r = NULL;
	struct aa_error err = {0};
	assert_int_equal(aa_job_run(fixture_engine, &spec, NULL, NULL, &r, &err), -1);
	assert_null(r);
	assert_int_equal(err.code, AA_ERR_INVALID);
	if (!strstr(err.message, "broken.frag:4: ") || !strstr(err.message, "syntax error"))
		fail_msg("%s", err.message);
	aa_job_spec_release(&spec);
}

/* With timing.repeat, a user method with history re-times on a second instance: its scored frames are
 * those of a run without repeats. */
static void test_repeat_keeps_history(void **state)
{
	(void)state;
	put("blend.json", "{\"name\": \"blend\", \"jitter\": {\"sequence\": \"halton\", \"length\": 8}, "
			  "\"passes\": [{\"name\": \"mix\", \"shader\": \"blend.frag\", \"reads\": [\"colour\", \"history\"]}]}");
	put("blend.frag", "void main()\n{\n\tvec4 c = texelFetch(colour, aa_pixel, 0);\n"
			  "\tfloat w = 1.0 / float(aa_history_frames + 1);\n"
			  "\taa_write(aa_history_valid ? mix(texelFetch(history, aa_pixel, 0), c, w) : c);\n}\n");
	struct frames once = {0}, thrice = {0};
	struct aa_job_spec spec;
	spec_of(&spec, "thin-wires", "[\"user:file=blend.json\"]", 48, 27, 3, 0, 1);
	fixture_free(fixture_run(&spec, NULL, keep_frames, &once));
	aa_job_spec_release(&spec);
	spec_of(&spec, "thin-wires", "[\"user:file=blend.json\"]", 48, 27, 3, 0, 3);
	struct aa_job_result *r = fixture_run(&spec, NULL, keep_frames, &thrice);
	assert_int_equal(r->methods[0].timed_count, 9);
	for (int k = 0; k < 3; k++)
		assert_memory_equal(once.image[0][k], thrice.image[0][k], once.pixels * 4);
	/* and the history does something: frame 2 is not frame 0 */
	assert_memory_not_equal(once.image[0][0], once.image[0][2], once.pixels * 4);
	fixture_free(r);
	aa_job_spec_release(&spec);
	frames_free(&once);
	frames_free(&thrice);
}

static int setup(void **state)
{
	files = json_object();
	aa_glsl_set_cache_dir(""); /* compile every time: a test leaves nothing behind */
	return fixture_setup(state);
}

static int teardown(void **state)
{
	json_decref(files);
	return fixture_teardown(state);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_passthrough_is_copy),
		cmocka_unit_test(test_contract_values),
		cmocka_unit_test(test_compile_error),
		cmocka_unit_test(test_repeat_keeps_history),
	};
	return fixture_status(cmocka_run_group_tests(tests, setup, teardown));
}
