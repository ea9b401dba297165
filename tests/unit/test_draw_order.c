/* The opaque draw order (aa_draw_order_front_to_back in engine/render/renderer_frame.c), without a GPU: the object
 * whose box ends nearest to the eye is drawn first, so a floor or a wall that everything else stands on or
 * hangs in front of comes last, whatever its place in the scene file; equal keys keep the scene's order. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "render/renderer.h"

static void sort(const struct aa_box *boxes, int n, vec3 eye, int *order)
{
	for (int i = 0; i < n; i++)
		order[i] = i;
	assert_int_equal(aa_draw_order_front_to_back(boxes, n, eye, order), 0);
}

/* hard-edges' layout, seen from its camera: the floor first in the file, a wall behind the props, a sign on
 * the wall, a torus and a post near the camera. */
static void test_floor_and_wall_last(void **state)
{
	(void)state;
	const struct aa_box boxes[] = {
		{{-12, 0, -12}, {12, 0, 12}},              /* 0 floor: reaches 21.5 from the eye */
		{{-6, 0, -5.1f}, {6, 3.4f, -4.9f}},        /* 1 wall: 12.4 */
		{{-2.8f, 1.55f, -4.9f}, {3.6f, 3.05f, -4.88f}}, /* 2 sign: 11.0 */
		{{1.9f, 0.3f, 0.1f}, {2.9f, 1.3f, 1.1f}},  /* 3 torus: 6.1 */
		{{3.7f, 0, -2.1f}, {3.9f, 3, -1.9f}},      /* 4 post: 8.6 */
	};
	int order[5];
	sort(boxes, 5, v3(0.3f, 1.7f, 5.5f), order);
	const int want[5] = {3, 4, 2, 1, 0};
	for (int i = 0; i < 5; i++)
		assert_int_equal(order[i], want[i]);
}

/* The key is where a box ends, not where it begins: the eye stands on the floor (it begins at distance
 * 0), which still comes after a box that ends nearer. */
static void test_eye_above_the_floor(void **state)
{
	(void)state;
	const struct aa_box boxes[] = {
		{{-50, 0, -50}, {50, 0, 50}},  /* 0 floor around the eye */
		{{-1, 0, -8}, {1, 2, -6}},     /* 1 a crate ahead */
	};
	int order[2];
	sort(boxes, 2, v3(0, 1.7f, 0), order);
	assert_int_equal(order[0], 1);
	assert_int_equal(order[1], 0);
}

/* Equal keys keep ascending index, so the order (and which of two equal depths wins) is the same on
 * every run and platform: qsort alone is not stable. */
static void test_ties_keep_scene_order(void **state)
{
	(void)state;
	struct aa_box boxes[9];
	for (int i = 0; i < 9; i++) /* the same box nine times, mirrored around the eye: one key */
		boxes[i] = (struct aa_box){{i % 2 ? -3.0f : 2.0f, -1, -1}, {i % 2 ? -2.0f : 3.0f, 1, 1}};
	int order[9];
	sort(boxes, 9, v3(0, 0, 0), order);
	for (int i = 0; i < 9; i++)
		assert_int_equal(order[i], i);
}

/* Forty boxes at scrambled distances come out sorted, each index once. */
static void test_order_is_a_permutation(void **state)
{
	(void)state;
	struct aa_box boxes[40];
	for (int i = 0; i < 40; i++) {
		float d = (float)((i * 17) % 40); /* distances 0..39 in a scrambled order */
		boxes[i] = (struct aa_box){{d, 0, 0}, {d + 0.5f, 1, 1}};
	}
	int order[40];
	sort(boxes, 40, v3(-1, 0.5f, 0.5f), order);
	int seen[40] = {0};
	for (int i = 0; i < 40; i++) {
		assert_in_range(order[i], 0, 39);
		seen[order[i]]++;
		if (i > 0)
			assert_true(boxes[order[i - 1]].max.x < boxes[order[i]].max.x);
	}
	for (int i = 0; i < 40; i++)
		assert_int_equal(seen[i], 1);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_floor_and_wall_last),
		cmocka_unit_test(test_eye_above_the_floor),
		cmocka_unit_test(test_ties_keep_scene_order),
		cmocka_unit_test(test_order_is_a_permutation),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
