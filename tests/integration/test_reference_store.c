/* The reference store end to end on the GPU: a job served from the store gives the same metrics to the
 * byte as one without it; changing one byte of a texture, the size, N, the reported driver version or a
 * shader's SPIR-V makes the lookup miss; an auto reference with a higher target goes on from the stored
 * sum and gives the bits of a run that rendered it whole. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "fixture.h"
#include "image/image.h"
#include "results/results.h"
#include "run/engine_internal.h"

static char dir[256], store_dir[300];
static const char *const none[] = {"none"};

static int setup(void **state)
{
	snprintf(dir, sizeof dir, "/tmp/aalab-test-refstore-XXXXXX");
	if (!mkdtemp(dir))
		return -1;
	snprintf(store_dir, sizeof store_dir, "%s/store", dir);
	if (fixture_setup(state))
		return -1;
	struct aa_error err = {0};
	return aa_engine_set_reference_cache(fixture_engine, store_dir, 0, &err);
}

static int teardown(void **state)
{
	char cmd[300];
	snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
	if (system(cmd) != 0)
		return -1;
	return fixture_teardown(state);
}

/* Everything results.json says of quality: each method's metrics and per-frame metrics, and the
 * reference's convergence, as JSON text. */
static char *quality_text(const struct aa_job_result *r)
{
	json_t *doc = aa_results_to_json(r), *q = json_array(), *m;
	size_t i, k;
	json_t *f;
	json_array_foreach(json_object_get(doc, "methods"), i, m) {
		json_array_append(q, json_object_get(m, "metrics"));
		json_array_foreach(json_object_get(m, "frames"), k, f) {
			/* every figure of the frame but this run's times */
			json_t *copy = json_deep_copy(f);
			json_object_del(copy, "gpu_ms");
			json_object_del(copy, "cpu_ms");
			json_object_del(copy, "passes");
			json_array_append_new(q, copy);
		}
	}
	json_t *ref = json_object_get(doc, "reference");
	json_array_append(q, json_object_get(ref, "convergence_mse"));
	json_array_foreach(json_object_get(ref, "per_frame"), k, f) {
		json_array_append(q, json_object_get(f, "convergence_mse"));
		json_array_append(q, json_object_get(f, "samples"));
	}
	char *text = json_dumps(q, JSON_COMPACT | JSON_REAL_PRECISION(17));
	json_decref(q);
	json_decref(doc);
	return text;
}

static struct aa_reference_cache_result run(const struct aa_job_spec *spec, char **quality)
{
	struct aa_job_result *r = fixture_run(spec, NULL, NULL, NULL);
	struct aa_reference_cache_result c = r->reference.cache;
	if (quality)
		*quality = quality_text(r);
	fixture_free(r);
	return c;
}

static void served_from_store_is_identical(void **state)
{
	(void)state;
	struct aa_job_spec spec;
	fixture_spec(&spec, "thin-wires", none, 1, 64, 36, 3, 8);
	char *without, *first, *second;
	struct aa_error err = {0};
	assert_int_equal(aa_engine_set_reference_cache(fixture_engine, NULL, 0, &err), 0);
	struct aa_reference_cache_result c = run(&spec, &without);
	assert_false(c.used);
	assert_int_equal(aa_engine_set_reference_cache(fixture_engine, store_dir, 0, &err), 0);
	c = run(&spec, &first);
	assert_int_equal(c.misses, 3);
	assert_int_equal(c.hits, 0);
	assert_true(c.bytes_written > 3 * 64 * 36 * 32);
	c = run(&spec, &second);
	assert_int_equal(c.hits, 3);
	assert_int_equal(c.misses, 0);
	assert_true(c.bytes_read > 3 * 64 * 36 * 32); /* the entries' files: sums and headers */
	assert_string_equal(first, without);
	assert_string_equal(second, without);
	free(without);
	free(first);
	free(second);
}

/* Each change, alone, after a run that stored the frame: the next run misses. */
static void misses(const struct aa_job_spec *spec, const char *what)
{
	struct aa_reference_cache_result c = run(spec, NULL);
	if (c.misses != spec->frames || c.hits != 0)
		fail_msg("after a change of %s: %d hits, %d misses", what, c.hits, c.misses);
}

static void stored(const struct aa_job_spec *spec)
{
	run(spec, NULL);
	struct aa_reference_cache_result c = run(spec, NULL);
	assert_int_equal(c.hits, spec->frames);
}

static void write_texture(const char *path, uint8_t first_byte)
{
	struct aa_image_rgba8 img;
	assert_int_equal(aa_image_rgba8_alloc(&img, 16, 16), 0);
	for (int i = 0; i < 16 * 16 * 4; i++)
		img.pixels[i] = (uint8_t)(i * 37);
	img.pixels[0] = first_byte;
	struct aa_error err = {0};
	assert_int_equal(aa_image_write_png(path, &img, &err), 0);
	aa_image_rgba8_free(&img);
}

static void texture_byte(void **state)
{
	(void)state;
	char scene[400], png[400];
	snprintf(scene, sizeof scene, "%s/textured.json", dir);
	snprintf(png, sizeof png, "%s/tiles.png", dir);
	FILE *f = fopen(scene, "w");
	assert_non_null(f);
	fputs("{\"name\": \"textured\", \"textures\": {\"t\": {\"file\": \"tiles.png\"}},\n"
	      " \"materials\": {\"m\": {\"texture\": \"t\", \"unlit\": true}},\n"
	      " \"objects\": [{\"name\": \"quad\", \"mesh\": {\"type\": \"plane\", \"size\": [4, 4]}, \"material\": \"m\"}],\n"
	      " \"camera\": {\"position\": [0, 3, 3], \"target\": [0, 0, 0], \"fov\": 50}}\n", f);
	fclose(f);
	write_texture(png, 10);
	struct aa_job_spec spec;
	fixture_spec(&spec, scene, none, 1, 64, 36, 1, 8);
	stored(&spec);
	write_texture(png, 11); /* one byte of one texel */
	misses(&spec, "one byte of a texture");
}

static void size_and_samples(void **state)
{
	(void)state;
	struct aa_job_spec spec;
	fixture_spec(&spec, "thin-wires", none, 1, 64, 36, 1, 8);
	stored(&spec);
	spec.width = 66;
	misses(&spec, "the size");
	spec.width = 64;
	spec.reference_samples = 16;
	misses(&spec, "N");
}

static void driver_version(void **state)
{
	(void)state;
	struct aa_job_spec spec;
	fixture_spec(&spec, "moving-sphere", none, 1, 64, 36, 1, 8);
	stored(&spec);
	uint32_t *v = &fixture_engine->gpu.properties.driverVersion;
	(*v)++; /* what another build of the driver reports */
	misses(&spec, "the driver version");
	(*v)--;
	struct aa_reference_cache_result c = run(&spec, NULL);
	assert_int_equal(c.hits, 1);
}

/* scene.frag with one byte of a debug name changed: the same code, other SPIR-V bytes. A new engine, so
 * that its pipelines are made from it. */
static void shader_spirv(void **state)
{
	(void)state;
	struct aa_job_spec spec;
	fixture_spec(&spec, "hard-edges", none, 1, 64, 36, 1, 8);
	stored(&spec);
	const struct aa_shader_code *code = aa_shader_find("scene.frag");
	assert_non_null(code);
	uint32_t *words = malloc(code->size);
	memcpy(words, code->words, code->size);
	size_t n = code->size / 4, at = 5;
	bool changed = false;
	while (at < n && !changed) {
		const uint32_t count = words[at] >> 16, opcode = words[at] & 0xffff;
		if (opcode == 5 /* OpName */ && count >= 3) {
			words[at + 2] ^= 0x20; /* the name's first letter, its case */
			changed = true;
		}
		at += count ? count : 1;
	}
	assert_true(changed);
	struct aa_shader_code other = {"scene.frag", words, code->size};
	assert_int_equal(aa_shader_substitute("scene.frag", &other), 0);
	struct aa_engine *saved = fixture_engine, *engine;
	struct aa_engine_options eo = {0};
	struct aa_error err = {0};
	assert_int_equal(aa_engine_create(&eo, &engine, &err), 0);
	assert_int_equal(aa_engine_set_reference_cache(engine, store_dir, 0, &err), 0);
	fixture_engine = engine;
	misses(&spec, "the SPIR-V of scene.frag");
	fixture_engine = saved;
	aa_engine_destroy(engine);
	aa_shader_substitute("scene.frag", NULL);
	free(words);
}

/* A target of 30 dB stores its levels; 45 dB then goes on from them and gives what a run without a
 * store gives. */
static void auto_goes_on(void **state)
{
	(void)state;
	struct aa_job_spec spec;
	fixture_spec(&spec, "thin-wires", none, 1, 64, 36, 2, 64);
	spec.reference_auto = true;
	spec.reference_target_psnr = 45;
	struct aa_error err = {0};
	char *without, *with;
	assert_int_equal(aa_engine_set_reference_cache(fixture_engine, NULL, 0, &err), 0);
	run(&spec, &without);
	assert_int_equal(aa_engine_set_reference_cache(fixture_engine, store_dir, 0, &err), 0);
	spec.reference_target_psnr = 20;
	struct aa_reference_cache_result c = run(&spec, NULL);
	assert_int_equal(c.misses, 2);
	spec.reference_target_psnr = 45;
	c = run(&spec, &with);
	assert_int_equal(c.continued, 2);
	assert_string_equal(with, without);
	c = run(&spec, NULL);
	assert_int_equal(c.hits, 2);
	spec.reference_target_psnr = 20; /* a lower target: its levels are stored too */
	c = run(&spec, NULL);
	assert_int_equal(c.hits, 2);
	free(without);
	free(with);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(served_from_store_is_identical),
		cmocka_unit_test(texture_byte),
		cmocka_unit_test(size_and_samples),
		cmocka_unit_test(driver_version),
		cmocka_unit_test(shader_spirv),
		cmocka_unit_test(auto_goes_on),
	};
	return fixture_status(cmocka_run_group_tests(tests, setup, teardown));
}
