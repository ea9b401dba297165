/* Matrix helpers: reversed-Z projections, inversion, and the jitter convention. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "util/mat4.h"
#include "reference/reference.h"
#include "util/halton.h"

static void test_reversed_z_perspective(void **state)
{
	(void)state;
	mat4 p = mat4_perspective_reversed_z(1.0f, 16.0f / 9.0f, 0.1f, 100.0f);
	vec3 near = mat4_transform_point(p, v3(0, 0, -0.1f));
	vec3 far = mat4_transform_point(p, v3(0, 0, -100.0f));
	assert_float_equal(near.z, 1.0f, 1e-5);
	assert_float_equal(far.z, 0.0f, 1e-5);
	/* y up in view space is up on screen: Vulkan's NDC y points down */
	vec3 up = mat4_transform_point(p, v3(0, 1, -5));
	assert_true(up.y < 0.0f);
}

static void test_reversed_z_ortho(void **state)
{
	(void)state;
	mat4 p = mat4_ortho_reversed_z(4.0f, 2.0f, 1.0f, 11.0f);
	assert_float_equal(mat4_transform_point(p, v3(2, 1, -1)).x, 1.0f, 1e-6);
	assert_float_equal(mat4_transform_point(p, v3(2, 1, -1)).y, -1.0f, 1e-6);
	assert_float_equal(mat4_transform_point(p, v3(0, 0, -1)).z, 1.0f, 1e-6);
	assert_float_equal(mat4_transform_point(p, v3(0, 0, -11)).z, 0.0f, 1e-6);
}

static void test_invert(void **state)
{
	(void)state;
	mat4 m = mat4_mul(mat4_translate(v3(1, 2, 3)), mat4_mul(mat4_rotate(v3(1, 1, 0), 0.7f),
								mat4_scale(v3(2, 3, 4))));
	mat4 inv;
	assert_int_equal(mat4_invert(m, &inv), 0);
	mat4 id = mat4_mul(m, inv);
	for (int i = 0; i < 16; i++)
		assert_float_equal(id.m[i], (i % 5 == 0) ? 1.0f : 0.0f, 1e-5);
	mat4 zero = {{0}};
	assert_int_equal(mat4_invert(zero, &inv), -1);
}

/* The scene shader adds jitter after projection: clip.xy += j * clip.w. Two points at different depths
 * must move by the same NDC amount (seed 000 translated before projecting, which shifts near points
 * more than far ones). */
static void test_jitter_is_depth_independent(void **state)
{
	(void)state;
	mat4 p = mat4_perspective_reversed_z(1.0f, 1.0f, 0.1f, 100.0f);
	float j[2] = {0.25f / 320.0f * 2.0f, -0.125f / 180.0f * 2.0f};
	vec3 pts[2] = {v3(0.3f, 0.2f, -0.5f), v3(-4.0f, 7.0f, -80.0f)};
	for (int i = 0; i < 2; i++) {
		float in[4] = {pts[i].x, pts[i].y, pts[i].z, 1}, c[4];
		mat4_transform_vec4(p, in, c);
		float nx = c[0] / c[3], ny = c[1] / c[3];
		float jx = (c[0] + j[0] * c[3]) / c[3], jy = (c[1] + j[1] * c[3]) / c[3];
		assert_float_equal(jx - nx, j[0], 1e-6);
		assert_float_equal(jy - ny, j[1], 1e-6);
	}
}

static void test_halton(void **state)
{
	(void)state;
	assert_float_equal(aa_halton(1, 2), 0.5, 1e-12);
	assert_float_equal(aa_halton(2, 2), 0.25, 1e-12);
	assert_float_equal(aa_halton(3, 2), 0.75, 1e-12);
	assert_float_equal(aa_halton(1, 3), 1.0 / 3.0, 1e-12);
	assert_float_equal(aa_halton(5, 3), 7.0 / 9.0, 1e-12); /* 5 = 12 in base 3 -> 0.21 */
	/* points stay inside the pixel and cover all four quadrants */
	float off[64][2];
	aa_reference_offsets(64, off);
	int quadrant[4] = {0};
	for (int i = 0; i < 64; i++) {
		assert_true(off[i][0] >= -0.5f && off[i][0] < 0.5f);
		assert_true(off[i][1] >= -0.5f && off[i][1] < 0.5f);
		quadrant[(off[i][0] >= 0) + 2 * (off[i][1] >= 0)]++;
	}
	for (int q = 0; q < 4; q++)
		assert_in_range(quadrant[q], 12, 20);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_reversed_z_perspective),
		cmocka_unit_test(test_reversed_z_ortho),
		cmocka_unit_test(test_invert),
		cmocka_unit_test(test_jitter_is_depth_independent),
		cmocka_unit_test(test_halton),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
