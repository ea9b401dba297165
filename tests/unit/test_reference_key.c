/* The reference key without a GPU: changing any one of its inputs changes the key (so dropping a part
 * from it fails here), the same inputs give the same key, and the auto reference's levels. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "reference/reference_key.h"

static float offsets[64][2];
static const uint8_t uuid[16] = {1, 2, 3};

static void base(struct aa_reference_key_inputs *in)
{
	memset(in, 0, sizeof *in);
	in->scene_known = true;
	memset(in->scene_sha256, 0x11, 32);
	in->scene_files = 2;
	in->camera.position = (vec3){1, 2, 3};
	in->camera.target = (vec3){0, 0, 0};
	in->camera.up = (vec3){0, 1, 0};
	in->camera.fov_y_degrees = 50;
	in->camera.near_plane = 0.1f;
	in->camera.far_plane = 100;
	in->time = 0.5;
	in->width = 640;
	in->height = 360;
	in->levels[0] = 32;
	in->levels[1] = 64;
	in->level_count = 2;
	in->pattern = "owen-sobol";
	for (int i = 0; i < 64; i++) {
		offsets[i][0] = (float)i / 64 - 0.5f;
		offsets[i][1] = (float)((i * 7) % 64) / 64 - 0.5f;
	}
	in->offsets = (const float (*)[2])offsets;
	in->batch = 7;
	in->alpha_rule = "per-sample";
	in->lod_bias = -3;
	memset(in->shaders_sha256, 0x22, 32);
	in->shader_pipelines = 4;
	in->code = "sources sha256 0123, assimp 5.2.0, libpng 1.6.39";
	in->vendor_id = 0x10005;
	in->device_id = 0;
	in->device_name = "llvmpipe (LLVM 15.0.6, 256 bits)";
	in->pipeline_cache_uuid = uuid;
	in->driver_version = 1;
	in->api_version = (1u << 22) | (3u << 12) | 230u;
	in->driver_build = "llvmpipe Mesa 22.3.6 (LLVM 15.0.6)";
}

static void key_of(const struct aa_reference_key_inputs *in, uint8_t out[32])
{
	struct aa_reference_key key;
	aa_reference_key_make(in, &key);
	assert_int_equal(key.part_count, AA_REFERENCE_KEY_PARTS);
	memcpy(out, key.sha256, 32);
}

static void same_inputs_same_key(void **state)
{
	(void)state;
	struct aa_reference_key_inputs a, b;
	base(&a);
	base(&b);
	uint8_t ka[32], kb[32];
	key_of(&a, ka);
	key_of(&b, kb);
	assert_memory_equal(ka, kb, 32);
}

/* Each change is of one input only; each must give another key. */
static void each_part_changes_the_key(void **state)
{
	(void)state;
	static float other_offsets[64][2];
	static const uint8_t other_uuid[16] = {9};
	const char *names[] = {"scene bytes", "camera position", "camera fov", "projection", "camera origin", "time",
			       "width", "height", "samples", "levels", "auto", "pattern name", "pattern offsets",
			       "batch", "alpha rule", "lod bias", "shaders", "code", "vendor", "device id",
			       "device name", "driver version", "api version", "driver build", "pipeline cache uuid"};
	const int count = (int)(sizeof names / sizeof names[0]);
	struct aa_reference_key_inputs in;
	uint8_t k0[32], k[32];
	base(&in);
	key_of(&in, k0);
	for (int c = 0; c < count; c++) {
		base(&in);
		switch (c) {
		case 0: in.scene_sha256[31] ^= 1; break;
		case 1: in.camera.position.x += 0.001f; break;
		case 2: in.camera.fov_y_degrees = 51; break;
		case 3: in.camera.projection = AA_PROJECTION_ORTHOGRAPHIC; break;
		case 4: in.camera.origin[0] = 1024; break;
		case 5: in.time = 0.5 + 1.0 / 30; break;
		case 6: in.width = 642; break;
		case 7: in.height = 362; break;
		case 8: in.levels[0] = 16; in.levels[1] = 32; break;
		case 9: in.level_count = 3; in.levels[2] = 64; in.levels[1] = 32; in.levels[0] = 16; break;
		case 10: in.auto_samples = true; break;
		case 11: in.pattern = "scrambled"; break;
		case 12:
			memcpy(other_offsets, offsets, sizeof offsets);
			other_offsets[63][1] += 1.0f / 4096;
			in.offsets = (const float (*)[2])other_offsets;
			break;
		case 13: in.batch = 6; break;
		case 14: in.alpha_rule = "per-pixel"; break;
		case 15: in.lod_bias = -2.5f; break;
		case 16: in.shaders_sha256[0] ^= 0x80; break;
		case 17: in.code = "sources sha256 0124, assimp 5.2.0, libpng 1.6.39"; break;
		case 18: in.vendor_id = 0x10de; break;
		case 19: in.device_id = 0x2204; break;
		case 20: in.device_name = "llvmpipe (LLVM 15.0.6, 128 bits)"; break;
		case 21: in.driver_version = 2; break;
		case 22: in.api_version += 1; break;
		case 23: in.driver_build = "llvmpipe Mesa 23.0.0 (LLVM 15.0.6)"; break;
		case 24: in.pipeline_cache_uuid = other_uuid; break;
		}
		key_of(&in, k);
		if (memcmp(k, k0, 32) == 0)
			fail_msg("changing the %s leaves the reference key as it was", names[c]);
	}
}

static void parts_are_named(void **state)
{
	(void)state;
	struct aa_reference_key_inputs in;
	base(&in);
	struct aa_reference_key key;
	aa_reference_key_make(&in, &key);
	const char *expected[] = {"scene", "camera", "time", "size", "samples", "pattern", "accumulation",
				  "alpha-rule", "lod-bias", "shaders", "code", "device", "driver"};
	for (int i = 0; i < AA_REFERENCE_KEY_PARTS; i++)
		assert_string_equal(key.parts[i].name, expected[i]);
	assert_string_equal(key.parts[3].value, "640x360");
	assert_int_equal(strlen(key.hex), 64);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(same_inputs_same_key),
		cmocka_unit_test(each_part_changes_the_key),
		cmocka_unit_test(parts_are_named),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
