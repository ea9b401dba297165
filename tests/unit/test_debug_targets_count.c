/* The count behind job option debug_targets (engine/render/debug_targets.c) on hand-made texels: every NaN and
 * Inf of half and float formats is found, the largest finite values and subnormals are not, a texel counts
 * once however many of its channels are bad, depth outside [0, 1] counts, and unchecked formats give 0. */
#include <float.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "render/debug_targets.h"

static void test_half_formats(void **state)
{
	(void)state;
	/* +Inf, -Inf, a quiet NaN, a signalling NaN; 65504 (largest finite), a subnormal, 1.0, -0.0 */
	const uint16_t bad[] = {0x7c00, 0xfc00, 0x7e00, 0x7c01};
	const uint16_t good[] = {0x7bff, 0x0001, 0x3c00, 0x8000};
	assert_int_equal(aa_debug_targets_count_invalid(bad, VK_FORMAT_R16_SFLOAT, 4, 1), 4);
	assert_int_equal(aa_debug_targets_count_invalid(good, VK_FORMAT_R16_SFLOAT, 2, 2), 0);
	/* RG16F: texel 0 (Inf, NaN) once, texel 1 clean, texel 2 (1.0, -Inf), texel 3 clean */
	const uint16_t rg[] = {0x7c00, 0x7e00, 0x3c00, 0x7bff, 0x3c00, 0xfc00, 0x0001, 0x8000};
	assert_int_equal(aa_debug_targets_count_invalid(rg, VK_FORMAT_R16G16_SFLOAT, 4, 1), 2);
	/* RGBA16F: a NaN in alpha only counts */
	const uint16_t rgba[] = {0x3c00, 0x3c00, 0x3c00, 0x7e00, 0x3c00, 0x3c00, 0x3c00, 0x3c00};
	assert_int_equal(aa_debug_targets_count_invalid(rgba, VK_FORMAT_R16G16B16A16_SFLOAT, 2, 1), 1);
}

static void test_float_formats(void **state)
{
	(void)state;
	const float values[] = {NAN, INFINITY, -INFINITY, FLT_MAX, -FLT_MAX, FLT_MIN / 4.0f, 2.0f, -3.0f};
	assert_int_equal(aa_debug_targets_count_invalid(values, VK_FORMAT_R32_SFLOAT, 8, 1), 3);
	assert_int_equal(aa_debug_targets_count_invalid(values, VK_FORMAT_R32G32_SFLOAT, 2, 2), 2);
	assert_int_equal(aa_debug_targets_count_invalid(values, VK_FORMAT_R32G32B32A32_SFLOAT, 2, 1), 1);
}

static void test_depth(void **state)
{
	(void)state;
	const float ok[] = {0.0f, 1.0f, 0.5f, -0.0f};
	const float bad[] = {nextafterf(1.0f, 2.0f), -1e-30f, NAN, 2.0f};
	assert_int_equal(aa_debug_targets_count_invalid(ok, VK_FORMAT_D32_SFLOAT, 4, 1), 0);
	assert_int_equal(aa_debug_targets_count_invalid(bad, VK_FORMAT_D32_SFLOAT, 4, 1), 4);
	/* the same values in a colour format: only the NaN */
	assert_int_equal(aa_debug_targets_count_invalid(bad, VK_FORMAT_R32_SFLOAT, 4, 1), 1);
}

static void test_unchecked_formats(void **state)
{
	(void)state;
	const uint32_t ones[4] = {0xffffffffu, 0xffffffffu, 0x7fc00000u, 0x7f800000u};
	assert_int_equal(aa_debug_targets_count_invalid(ones, VK_FORMAT_R8G8B8A8_UNORM, 4, 1), 0);
	assert_int_equal(aa_debug_targets_count_invalid(ones, VK_FORMAT_R32_UINT, 4, 1), 0);
	assert_false(aa_debug_targets_wants(VK_FORMAT_R32G32B32A32_UINT, VK_IMAGE_USAGE_SAMPLED_BIT, 1));
	assert_false(aa_debug_targets_wants(VK_FORMAT_R16G16B16A16_SFLOAT, VK_IMAGE_USAGE_SAMPLED_BIT, 4));
	assert_false(aa_debug_targets_wants(VK_FORMAT_D32_SFLOAT, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, 1));
	assert_true(aa_debug_targets_wants(VK_FORMAT_D32_SFLOAT, VK_IMAGE_USAGE_SAMPLED_BIT, 1));
	assert_true(aa_debug_targets_wants(VK_FORMAT_R16G16_SFLOAT, VK_IMAGE_USAGE_SAMPLED_BIT, 1));
	/* off: no usage bit added */
	assert_int_equal(aa_debug_targets_usage(NULL, VK_FORMAT_R16G16_SFLOAT, VK_IMAGE_USAGE_SAMPLED_BIT, 1),
			 VK_IMAGE_USAGE_SAMPLED_BIT);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_half_formats),
		cmocka_unit_test(test_float_formats),
		cmocka_unit_test(test_depth),
		cmocka_unit_test(test_unchecked_formats),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
