/* The shadow map's fit to the view (engine/render/shadow_fit.c) and the frame plan's reasons, without a GPU:
 * cascades cover their slice of the view, keep their size and texel grid when the camera moves by less than
 * a texel, hold the casters' depths and nothing beyond; the plan says what decided each pass. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "render/frame_plan.h"
#include "types/job.h"
#include "render/renderer.h"
#include "render/shadow_fit.h"
#include "run/job_spec.h"

static struct aa_camera camera_at(vec3 position, vec3 target)
{
	return (struct aa_camera){.position = position, .target = target, .up = v3(0, 1, 0),
				  .projection = AA_PROJECTION_PERSPECTIVE, .fov_y_degrees = 50, .near_plane = 0.1f,
				  .far_plane = 1000};
}

/* A long field (a floor 400 deep) with posts on it, like horizon: a wide range of view depths. */
static const struct aa_box field[] = {
	{{-100, -0.01f, -200}, {100, 0, 200}},
	{{-6.05f, 0, 150}, {-5.95f, 1.1f, 150.1f}},
	{{-6.05f, 0, 120}, {-5.95f, 1.1f, 120.1f}},
	{{5.95f, 0, 100}, {6.05f, 1.1f, 100.1f}},
};

static void fit(struct aa_camera cam, struct aa_shadow_fit *out, const struct aa_box *boxes, int n)
{
	struct aa_shadow_fit_input in = {.camera = cam, .aspect = 16.0f / 9.0f,
					 .light_direction = v3_normalize(v3(-0.3f, -1.0f, 0.2f)), .boxes = boxes,
					 .box_count = n, .tile_size = AA_SHADOW_TILE_SIZE};
	aa_shadow_fit(&in, out);
}

/* Sub-texel camera motion moves nothing in the map: every cascade keeps its size, and its centre moves
 * by whole texels (here: none), so every point of the world lands on the same texel position. */
static void test_stable_under_subtexel_motion(void **state)
{
	(void)state;
	struct aa_camera a = camera_at(v3(-1.5f, 1.1f, 190), v3(-0.5f, -5.5f, 150));
	struct aa_shadow_fit fa, fb;
	fit(a, &fa, field, 4);
	assert_int_equal(fa.cascade_count, AA_SHADOW_CASCADES);
	for (int step = 1; step <= 3; step++) {
		struct aa_camera b = a;
		float d = 0.3f * fa.cascades[0].texel * (float)step; /* less than a texel of the finest cascade */
		b.position = v3_add(a.position, v3(d, 0, -d));
		b.target = v3_add(a.target, v3(d, 0, -d));
		fit(b, &fb, field, 4);
		assert_int_equal(fb.cascade_count, fa.cascade_count);
		for (int i = 0; i < fa.cascade_count; i++) {
			const struct aa_shadow_cascade *ca = &fa.cascades[i], *cb = &fb.cascades[i];
			assert_true(ca->radius == cb->radius && ca->texel == cb->texel);
			for (int k = 0; k < 2; k++) {
				float shift = ((&cb->center.x)[k] - (&ca->center.x)[k]) / ca->texel;
				if (fabsf(shift - roundf(shift)) > 1e-3f)
					fail_msg("cascade %d moved by %g texels along %c", i, shift, "xy"[k]);
			}
		}
	}
	/* turning the camera a little keeps every cascade's size too (the slice's sphere does not turn) */
	struct aa_camera turned = a;
	turned.target = v3_add(a.target, v3(0.2f, 0, 0));
	fit(turned, &fb, field, 4);
	for (int i = 0; i < fa.cascade_count; i++)
		assert_true(fb.cascades[i].radius == fa.cascades[i].radius);
}

/* Camera-relative (docs/architecture.md): the same view fitted relative to the eye (camera at 0, boxes moved
 * by -eye, eye given) is the world fit moved by the eye's light-space position: the same sizes and splits,
 * and centres on the same world-fixed texel grid, so the map does not shimmer as the eye moves. */
static void test_camera_relative_fit(void **state)
{
	(void)state;
	vec3 eye = v3(-1.5f, 1.1f, 190);
	struct aa_camera world = camera_at(eye, v3(-0.5f, -5.5f, 150));
	struct aa_camera rel = camera_at(v3(0, 0, 0), v3_sub(world.target, eye));
	struct aa_box moved[4];
	for (int k = 0; k < 4; k++)
		moved[k] = (struct aa_box){v3_sub(field[k].min, eye), v3_sub(field[k].max, eye)};
	struct aa_shadow_fit fw, fr;
	fit(world, &fw, field, 4);
	struct aa_shadow_fit_input in = {.camera = rel, .eye = {eye.x, eye.y, eye.z}, .aspect = 16.0f / 9.0f,
					 .light_direction = v3_normalize(v3(-0.3f, -1.0f, 0.2f)), .boxes = moved,
					 .box_count = 4, .tile_size = AA_SHADOW_TILE_SIZE};
	aa_shadow_fit(&in, &fr);
	assert_int_equal(fr.cascade_count, fw.cascade_count);
	vec3 eye_light = mat4_transform_point(fw.light_view, eye);
	for (int i = 0; i < fw.cascade_count; i++) {
		const struct aa_shadow_cascade *cw = &fw.cascades[i], *cr = &fr.cascades[i];
		assert_true(cw->radius == cr->radius && cw->texel == cr->texel);
		for (int k = 0; k < 2; k++) {
			float apart = ((&cr->center.x)[k] + (&eye_light.x)[k] - (&cw->center.x)[k]) / cw->texel;
			if (fabsf(apart) > 1e-2f)
				fail_msg("cascade %d: the relative fit's centre is %g texels off the world fit's along %c", i,
					 apart, "xy"[k]);
		}
		/* sub-texel eye motion: the centre, in the world, moves by whole texels */
		double eye2[3] = {eye.x + 0.3 * cw->texel, eye.y, eye.z - 0.3 * cw->texel};
		struct aa_shadow_fit_input in2 = in;
		memcpy(in2.eye, eye2, sizeof eye2);
		struct aa_box moved2[4];
		vec3 d = v3((float)(eye2[0] - eye.x), 0, (float)(eye2[2] - eye.z));
		for (int b = 0; b < 4; b++)
			moved2[b] = (struct aa_box){v3_sub(moved[b].min, d), v3_sub(moved[b].max, d)};
		in2.boxes = moved2;
		struct aa_shadow_fit f2;
		aa_shadow_fit(&in2, &f2);
		vec3 eye2_light = mat4_transform_point(fw.light_view, v3((float)eye2[0], (float)eye2[1], (float)eye2[2]));
		for (int k = 0; k < 2; k++) {
			float shift = ((&f2.cascades[i].center.x)[k] + (&eye2_light.x)[k] - (&cr->center.x)[k] -
				       (&eye_light.x)[k]) / cw->texel;
			if (fabsf(shift - roundf(shift)) > 1e-2f)
				fail_msg("cascade %d moved by %g texels along %c when the eye moved", i, shift, "xy"[k]);
		}
	}
}

/* Each cascade's window holds its slice of the view frustum; the first is much finer than one map over
 * the whole field; the depth range holds the casters over the window and no more. */
static void test_cascades_cover_the_view(void **state)
{
	(void)state;
	struct aa_camera cam = camera_at(v3(-1.5f, 1.1f, 190), v3(-0.5f, -5.5f, 150));
	struct aa_shadow_fit f;
	fit(cam, &f, field, 4);
	vec3 forward = v3_normalize(v3_sub(cam.target, cam.position));
	vec3 right = v3_normalize(v3_cross(forward, cam.up)), up = v3_cross(right, forward);
	float ty = tanf(25.0f * 3.14159265f / 180.0f), tx = ty * 16.0f / 9.0f;
	for (int i = 0; i < f.cascade_count; i++) {
		const struct aa_shadow_cascade *c = &f.cascades[i];
		for (int corner = 0; corner < 8; corner++) {
			float d = corner & 4 ? f.splits[i + 1] : f.splits[i];
			vec3 p = v3_add(cam.position, v3_add(v3_scale(forward, d),
						       v3_add(v3_scale(right, (corner & 1 ? 1 : -1) * tx * d),
							      v3_scale(up, (corner & 2 ? 1 : -1) * ty * d))));
			vec3 l = mat4_transform_point(f.light_view, p);
			if (fabsf(l.x - c->center.x) > c->radius * 1.0001f || fabsf(l.y - c->center.y) > c->radius * 1.0001f)
				fail_msg("cascade %d does not hold its slice's corner %d", i, corner);
		}
		for (int k = 0; k < 4; k++) {
			float lo[3] = {field[k].min.x, field[k].min.y, field[k].min.z};
			float hi[3] = {field[k].max.x, field[k].max.y, field[k].max.z};
			struct aa_box l = aa_box_transform(f.light_view, lo, hi);
			if (aa_shadow_cascade_sees(&f, i, &field[k]))
				assert_true(l.max.z <= c->z_near && l.min.z >= c->z_far);
		}
		/* scale and offset map the window onto [-1, 1] and the depth range onto [0, 1], near the light 1 */
		assert_true(fabsf((c->center.x + c->radius) * c->scale[0] + c->offset[0] - 1.0f) < 1e-4f);
		assert_true(fabsf(c->z_near * c->scale[2] + c->offset[2] - 1.0f) < 1e-4f);
		assert_true(fabsf(c->z_far * c->scale[2] + c->offset[2]) < 1e-4f);
	}
	/* the view's depth range starts where something is in view (the floor ahead), not at the near plane */
	assert_true(f.splits[0] > 1.0f);
	/* the field is 400 deep: one 2048^2 map over it had texels of 400 / 2048; the nearest cascade's (of the
	 * renderer's tile size) are 10x finer */
	assert_true(f.cascades[0].texel < 0.1f * 400.0f / 2048.0f);
	/* a box behind the camera changes nothing */
	struct aa_box more[5];
	memcpy(more, field, sizeof field);
	more[4] = (struct aa_box){{-1, 0, 195}, {1, 50, 196}};
	struct aa_shadow_fit g;
	fit(cam, &g, more, 5);
	assert_true(g.splits[0] == f.splits[0] && g.splits[AA_SHADOW_CASCADES] == f.splits[AA_SHADOW_CASCADES]);
}

/* A scene smaller than the far slices: the cascade that holds all of it is the last one drawn. */
static void test_small_scene_uses_fewer_cascades(void **state)
{
	(void)state;
	static const struct aa_box small[] = {{{-1, 0, -1}, {1, 0.5f, 1}}};
	struct aa_shadow_fit f;
	fit(camera_at(v3(0, 1, 3), v3(0, 0, 0)), &f, small, 1);
	assert_true(f.cascade_count >= 1 && f.cascade_count < AA_SHADOW_CASCADES);
	assert_true(isinf(f.splits[f.cascade_count]));
}

/* ---------------------------------------------------------------- the frame plan's reasons */

static struct aa_scene *scene_of(const char *json)
{
	struct aa_scene *sc = NULL;
	struct aa_error err = {0};
	if (aa_scene_load_string(json, "plan.json", NULL, &sc, &err))
		fail_msg("%s", err.message);
	return sc;
}

static const struct aa_plan_entry *entry(const struct aa_frame_plan *p, const char *pass)
{
	for (int i = 0; i < p->entry_count; i++)
		if (strcmp(p->entries[i].pass, pass) == 0)
			return &p->entries[i];
	fail_msg("no %s in the plan", pass);
	return NULL;
}

static void plan_for(const struct aa_scene *sc, const char *path, struct aa_frame_plan *plan)
{
	struct aa_job_spec spec;
	struct aa_error err = {0};
	json_t *job = json_pack("{ss ss s[s]}", "scene", "x", "path", path, "methods", "none");
	assert_int_equal(aa_job_spec_from_json(job, &spec, &err), 0);
	json_decref(job);
	aa_frame_plan_build(sc, &spec, plan);
}

#define OBJECTS "\"objects\": [{\"mesh\": \"box\", \"material\": \"plain\"}]"
#define CAMERA "\"camera\": {\"position\": [0, 1, 5], \"target\": [0, 0, 0]}"

static void test_plan_reasons(void **state)
{
	(void)state;
	struct aa_frame_plan plan;
	/* a camera path that moves: velocity says so, even though no method reprojects */
	struct aa_scene *sc = scene_of("{\"materials\": {\"plain\": {}}, " OBJECTS ", " CAMERA ", \"paths\": "
				       "[{\"name\": \"pan\", \"type\": \"pan\", \"degrees\": 20}]}");
	plan_for(sc, "pan", &plan);
	assert_false(plan.velocity);
	assert_non_null(strstr(entry(&plan, "velocity")->reason, "the camera moves (path 'pan')"));
	plan_for(sc, "static", &plan);
	assert_non_null(strstr(entry(&plan, "velocity")->reason, "nothing moves"));
	assert_non_null(strstr(entry(&plan, "alpha-test")->reason, "no material is an alpha cut-out"));
	assert_false(entry(&plan, "alpha-blend")->ran);
	aa_scene_free(sc);

	/* a cut-out material no object draws with: not "no material is a cut-out" */
	sc = scene_of("{\"materials\": {\"plain\": {}, \"leaves\": {\"alpha_cutout\": true}}, " OBJECTS ", " CAMERA "}");
	plan_for(sc, "default", &plan);
	assert_false(plan.alpha_test);
	assert_non_null(strstr(entry(&plan, "alpha-test")->reason, "no object draws with a cut-out material (leaves)"));
	aa_scene_free(sc);
	sc = scene_of("{\"materials\": {\"plain\": {\"alpha_cutout\": true}}, " OBJECTS ", " CAMERA "}");
	plan_for(sc, "default", &plan);
	assert_true(plan.alpha_test);
	assert_non_null(strstr(entry(&plan, "alpha-test")->reason, "material 'plain' (object 'object0') is an alpha cut-out"));
	aa_scene_free(sc);

	/* a shadow-casting light of intensity 0 runs no shadow map, and says why */
	sc = scene_of("{\"materials\": {\"plain\": {}}, " OBJECTS ", " CAMERA ", \"lights\": [{\"type\": "
		      "\"directional\", \"direction\": [0, -1, 0], \"intensity\": 0, \"casts_shadow\": true}]}");
	plan_for(sc, "default", &plan);
	assert_false(plan.shadow_map);
	assert_non_null(strstr(entry(&plan, "shadow-map")->reason, "lights[0] casts shadows but gives no light"));
	aa_scene_free(sc);
	sc = scene_of("{\"materials\": {\"plain\": {}}, " OBJECTS ", " CAMERA ", \"lights\": [{\"type\": "
		      "\"directional\", \"direction\": [0, -1, 0], \"casts_shadow\": true}]}");
	plan_for(sc, "default", &plan);
	assert_true(plan.shadow_map);
	assert_non_null(strstr(entry(&plan, "shadow-map")->reason, "lights[0] (directional) casts shadows"));
	aa_scene_free(sc);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_stable_under_subtexel_motion),
		cmocka_unit_test(test_cascades_cover_the_view),
		cmocka_unit_test(test_camera_relative_fit),
		cmocka_unit_test(test_small_scene_uses_fewer_cascades),
		cmocka_unit_test(test_plan_reasons),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
