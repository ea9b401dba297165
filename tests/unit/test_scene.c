/* Scene tests: shipped scenes load, bad scenes fail with the right JSON path and a useful message,
 * camera paths, animation, procedural meshes, textures and the pixel-exact 2D pattern camera. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/scene.h"
#include "scene/texture.h"

#define CAM "\"camera\": {\"position\": [0, 1, 5], \"target\": [0, 0, 0]}"

static const char *scene_dir(void)
{
	const char *d = getenv("AALAB_SCENE_DIR");
#ifdef AA_SOURCE_SCENE_DIR
	if (!d || !d[0])
		d = AA_SOURCE_SCENE_DIR;
#endif
	return d;
}

static int setup(void **state)
{
	(void)state;
	/* Scene lookups by name use $AALAB_SCENE_DIR first; point it at the source tree when unset. */
	if (!getenv("AALAB_SCENE_DIR") && scene_dir())
		setenv("AALAB_SCENE_DIR", scene_dir(), 1);
	return scene_dir() ? 0 : -1;
}

/* Every triangle: valid indices, unit normals, non-degenerate, front face agreeing with the normals. */
static void check_mesh(const struct aa_mesh *m)
{
	assert_true(m->index_count > 0);
	assert_int_equal(m->index_count % 3, 0);
	for (uint32_t v = 0; v < m->vertex_count; v++) {
		const float *n = m->vertices[v].normal;
		float len = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
		if (fabsf(len - 1.0f) > 1e-3f)
			fail_msg("mesh %s vertex %u normal length %g", m->name, v, len);
	}
	for (uint32_t i = 0; i < m->index_count; i += 3) {
		vec3 p[3], nsum = v3(0, 0, 0);
		for (int k = 0; k < 3; k++) {
			uint32_t idx = m->indices[i + k];
			assert_true(idx < m->vertex_count);
			const float *q = m->vertices[idx].position, *n = m->vertices[idx].normal;
			p[k] = v3(q[0], q[1], q[2]);
			nsum = v3_add(nsum, v3(n[0], n[1], n[2]));
		}
		vec3 e1 = v3_sub(p[1], p[0]), e2 = v3_sub(p[2], p[0]), g = v3_cross(e1, e2);
		float scale = fmaxf(v3_dot(e1, e1), v3_dot(e2, e2));
		if (!(v3_length(g) > 1e-7f * scale))
			fail_msg("mesh %s triangle %u is degenerate", m->name, i / 3);
		if (v3_dot(g, nsum) <= 0.0f)
			fail_msg("mesh %s triangle %u winds against its normals", m->name, i / 3);
	}
}

static void test_shipped_scenes(void **state)
{
	(void)state;
	char **names;
	int count;
	bool shadow = false, plain = false, cutout = false, anim = false;
	assert_int_equal(aa_scene_list(&names, &count), 0);
	assert_true(count >= 4);
	const char *required[] = {"thin-wires", "hard-edges", "horizon", "moving-sphere"};
	for (size_t r = 0; r < 4; r++) {
		bool found = false;
		for (int i = 0; i < count; i++)
			found |= strcmp(names[i], required[r]) == 0;
		if (!found)
			fail_msg("scene %s is missing", required[r]);
	}
	for (int i = 0; i < count; i++) {
		char path[1024];
		struct aa_error err = {0};
		struct aa_scene *sc = NULL;
		if (aa_scene_resolve(names[i], path, sizeof path, &err) || aa_scene_load(path, &sc, &err))
			fail_msg("scene %s: %s", names[i], err.message);
		uint64_t tris = aa_scene_triangle_count(sc);
		print_message("  %-16s %6llu triangles, %zu bytes%s%s%s\n", names[i], (unsigned long long)tris,
			      aa_scene_bytes(sc), aa_scene_has_shadow_caster_light(sc) ? ", shadows" : "",
			      aa_scene_has_animation(sc) ? ", animated" : "", aa_scene_has_cutout(sc) ? ", cut-outs" : "");
		assert_true(tris > 0 && tris <= 20000); /* rendered 64+ times a frame on a CPU rasteriser */
		assert_string_equal(sc->name, names[i]);
		assert_true(sc->path_count >= 1 && sc->paths[0].duration >= 1.0);
		assert_true(sc->fps > 0);
		for (int m = 0; m < sc->mesh_count; m++)
			check_mesh(&sc->meshes[m]);
		/* 1-based in file order; the parts of one scene object drawing a mesh file share its id
		 * (hdr-fireflies' sparks.gltf has a part per emitter) */
		for (int o = 0; o < sc->object_count; o++)
			assert_true(sc->objects[o].model_id == (o ? sc->objects[o - 1].model_id : 0) + 1 ||
				    (o && sc->objects[o].model_id == sc->objects[o - 1].model_id));
		shadow |= aa_scene_has_shadow_caster_light(sc);
		plain |= !aa_scene_has_shadow_caster_light(sc) && !aa_scene_has_animation(sc);
		cutout |= aa_scene_has_cutout(sc);
		anim |= aa_scene_has_animation(sc);
		aa_scene_free(sc);
		free(names[i]);
	}
	free(names);
	/* The frame plan's tests need both kinds of scene. */
	assert_true(shadow && plain && cutout && anim);
}

struct bad_scene {
	const char *json;
	const char *path;    /* expected err->path */
	const char *message; /* expected substring of err->message */
	enum aa_error_code code;
};

static const struct bad_scene bad_scenes[] = {
	{"{\"objetcs\": [], " CAM "}", "objetcs", "unknown key 'objetcs' (did you mean 'objects'?", AA_ERR_INVALID},
	{"{\"materials\": {\"floor\": {\"colour\": \"#FF0000\"}}, \"objects\": [{\"mesh\": \"box\"}], " CAM "}",
	 "materials.floor.colour", "unknown key 'colour' (did you mean 'color'? valid keys: color, pattern",
	 AA_ERR_INVALID},
	{"{\"fps\": \"fast\", \"objects\": [{\"mesh\": \"box\"}], " CAM "}", "fps", "got \"fast\"", AA_ERR_INVALID},
	{"{\"objects\": [{\"mesh\": \"box\"}, {\"mesh\": {\"type\": \"sphere\", \"radius\": -1}}], " CAM "}",
	 "objects[1].mesh.radius", "expected a positive number in [0.0001, 100000], got -1", AA_ERR_INVALID},
	{"{\"materials\": {\"floor\": {}, \"wire\": {}}, \"objects\": [{\"mesh\": \"box\", \"material\": \"floor\"}, "
	 "{\"mesh\": \"box\"}, {\"mesh\": \"box\", \"material\": \"steel\"}], " CAM "}",
	 "objects[2].material", "unknown material 'steel' (materials: floor, wire)", AA_ERR_INVALID},
	{"{\"objects\": [{\"mesh\": {\"type\": \"file\", \"path\": \"../secret.obj\"}}], " CAM "}", "objects[0].mesh.path",
	 "'..' is not allowed", AA_ERR_INVALID},
	{"{\"objects\": [{\"mesh\": {\"type\": \"file\", \"path\": \"assets/../../x.obj\"}}], " CAM "}",
	 "objects[0].mesh.path", "'..' is not allowed", AA_ERR_INVALID},
	{"{\"objects\": [{\"mesh\": {\"type\": \"file\", \"path\": \"/etc/passwd\"}}], " CAM "}", "objects[0].mesh.path",
	 "absolute paths are not allowed", AA_ERR_INVALID},
	{"{\"textures\": {\"t\": {\"file\": \"../../etc/hostname\"}}, \"objects\": [{\"mesh\": \"box\"}], " CAM "}",
	 "textures.t.file", "'..' is not allowed", AA_ERR_INVALID},
	{"{\"objects\": [{\"mesh\": {\"type\": \"file\", \"path\": \"assets/missing.obj\"}}], " CAM "}",
	 "objects[0].mesh.path", "not found", AA_ERR_NOT_FOUND},
	{"{\"objects\": [{\"mesh\": \"box\"}], \"camera\": {\"position\": [0, 1, 5], \"target\": [0, 0, 0], "
	 "\"projection\": \"fisheye\"}}", "camera.projection", "unknown value 'fisheye' (expected one of: perspective, "
	 "orthographic)", AA_ERR_INVALID},
	{"{\"objects\": [], " CAM "}", "objects", "at least one object", AA_ERR_INVALID},
	{"{\"objects\": [{\"mesh\": \"box\"}]}", "camera", "missing required key 'camera'", AA_ERR_INVALID},
	{"{\"objects\": [{\"mesh\": \"box\"}], \"camera\": {\"position\": [0, 1, 5], \"target\": [0, 0, 0], \"fov\": 200}}",
	 "camera.fov", "in [1, 179], got 200", AA_ERR_INVALID},
	{"{\"objects\": [{\"mesh\": \"box\"}], \"camera\": {\"position\": [1, 1, 1], \"target\": [1, 1, 1]}}",
	 "camera.target", "target must differ from position", AA_ERR_INVALID},
	{"{\"objects\": [{\"mesh\": \"box\"}], \"camera\": {\"target\": [0, 0, 0]}}", "camera.position",
	 "missing required key 'position'", AA_ERR_INVALID},
	{"{\"objects\": [{\"mesh\": {\"type\": \"teapot\"}}], " CAM "}", "objects[0].mesh.type", "unknown value 'teapot'",
	 AA_ERR_INVALID},
	{"{\"objects\": [{\"mesh\": \"teapot\"}], " CAM "}", "objects[0].mesh", "unknown mesh 'teapot'", AA_ERR_INVALID},
	{"{\"objects\": [{\"mesh\": \"box\", \"scale\": -2}], " CAM "}", "objects[0].scale", "got -2", AA_ERR_INVALID},
	{"{\"objects\": [{\"mesh\": \"box\", \"position\": [1, 2]}], " CAM "}", "objects[0].position",
	 "expected an array of 3 numbers", AA_ERR_INVALID},
	{"{\"objects\": [{\"mesh\": \"box\", \"animation\": {\"oscillate\": {\"axis\": [0, 0, 0]}}}], " CAM "}",
	 "objects[0].animation.oscillate.axis", "axis must not be zero", AA_ERR_INVALID},
	{"{\"objects\": [{\"mesh\": \"box\"}], \"lights\": [{\"type\": \"directional\", \"direction\": [0, 0, 0]}], " CAM "}",
	 "lights[0].direction", "must not be zero", AA_ERR_INVALID},
	{"{\"objects\": [{\"mesh\": \"box\"}], \"lights\": [{\"type\": \"point\", \"position\": [0, 2, 0], "
	 "\"casts_shadow\": true}], " CAM "}", "lights[0].casts_shadow", "only directional lights", AA_ERR_INVALID},
	{"{\"objects\": [{\"mesh\": \"box\"}], \"lights\": [{\"type\": \"spot\"}], " CAM "}", "lights[0].type",
	 "unknown value 'spot'", AA_ERR_INVALID},
	{"{\"objects\": [{\"mesh\": \"box\"}], " CAM ", \"paths\": [{\"type\": \"keyframes\", \"keys\": [{\"time\": 0}, "
	 "{\"time\": 2}, {\"time\": 1}]}]}", "paths[0].keys[2].time", "key times must increase", AA_ERR_INVALID},
	{"{\"objects\": [{\"mesh\": \"box\"}], " CAM ", \"paths\": [{\"type\": \"keyframes\", \"keys\": [{\"time\": 0, "
	 "\"cut\": true}]}]}", "paths[0].keys[0].cut", "first key cannot be a cut", AA_ERR_INVALID},
	{"{\"objects\": [{\"mesh\": \"box\"}], " CAM ", \"paths\": [{\"name\": \"a\", \"type\": \"static\"}, "
	 "{\"name\": \"a\", \"type\": \"pan\"}]}", "paths[1].name", "duplicate path name 'a'", AA_ERR_INVALID},
	{"{\"objects\": [{\"mesh\": \"box\"}], " CAM ", \"paths\": [{\"name\": \"default\", \"type\": \"static\"}]}",
	 "paths[0].name", "reserved", AA_ERR_INVALID},
	{"{\"objects\": [{\"mesh\": \"box\"}], " CAM ", \"paths\": [{\"type\": \"orbit\", \"distance\": 3}]}",
	 "paths[0].distance", "unknown key 'distance'", AA_ERR_INVALID},
	{"{\"objects\": [{\"mesh\": \"box\"}], " CAM ", \"paths\": [{\"type\": \"dolly\"}]}", "paths[0].distance",
	 "missing required key 'distance'", AA_ERR_INVALID},
	{"{\"materials\": {\"m\": {\"texture\": \"nope\"}}, \"objects\": [{\"mesh\": \"box\"}], " CAM "}",
	 "materials.m.texture", "unknown texture 'nope' (textures: none)", AA_ERR_INVALID},
	{"{\"materials\": {\"m\": {\"pattern\": \"texture\"}}, \"objects\": [{\"mesh\": \"box\"}], " CAM "}",
	 "materials.m.pattern", "needs a 'texture'", AA_ERR_INVALID},
	{"{\"textures\": {\"t\": {\"text\": \"HI~\"}}, \"objects\": [{\"mesh\": \"box\"}], " CAM "}", "textures.t.text",
	 "not in the 5x7 font", AA_ERR_INVALID},
	{"{\"textures\": {\"t\": {\"text\": \"TOO WIDE FOR A TEXTURE\", \"scale\": 64}}, \"objects\": [{\"mesh\": "
	 "\"box\"}], " CAM "}", "textures.t.text", "over the limit of 4096", AA_ERR_LIMIT},
	{"{\"textures\": {\"t\": {}}, \"objects\": [{\"mesh\": \"box\"}], " CAM "}", "textures.t",
	 "needs exactly one of 'file'", AA_ERR_INVALID},
	{"{\"background\": \"#GG0000\", \"objects\": [{\"mesh\": \"box\"}], " CAM "}", "background", "expected a colour",
	 AA_ERR_INVALID},
	{"{\"background\": [0.5, 2, 0], \"objects\": [{\"mesh\": \"box\"}], " CAM "}", "background[1]", "got 2",
	 AA_ERR_INVALID},
	{"{\"objects\": [{\"mesh\": {\"type\": \"sphere\", \"stacks\": 512, \"slices\": 1024}}], " CAM "}",
	 "objects[0].mesh", "over the limit", AA_ERR_LIMIT},
	{"{\"objects\": [{\"mesh\": {\"type\": \"fence\", \"style\": \"grid\", \"length\": 10000, \"grid_spacing\": 0.01}}], "
	 CAM "}", "objects[0].mesh.grid_spacing", "too many", AA_ERR_LIMIT},
	{"{\"objects\": [{\"mesh\": {\"type\": \"wheel\", \"radius\": 1, \"hub_radius\": 2}}], " CAM "}",
	 "objects[0].mesh.hub_radius", "must be less than", AA_ERR_INVALID},
	{"{\"objects\": [{\"mesh\": {\"type\": \"plane\", \"subdivisions\": [2, 0]}}], " CAM "}",
	 "objects[0].mesh.subdivisions[1]", "integer in [1, 1024], got 0", AA_ERR_INVALID},
	{"{\"objects\": [{\"mesh\": \"box\"}], " CAM ", \"objects\": []}", "", "duplicate", AA_ERR_INVALID},
	{"{\"objects\": [{\"mesh\": \"box\"}],, " CAM "}", "", "bad.json:1:", AA_ERR_INVALID},
	{"[1, 2]", "", "expected an object, got an array", AA_ERR_INVALID},
};

static void test_bad_scenes(void **state)
{
	(void)state;
	for (size_t i = 0; i < sizeof bad_scenes / sizeof bad_scenes[0]; i++) {
		const struct bad_scene *b = &bad_scenes[i];
		struct aa_error err = {0};
		struct aa_scene *sc = (struct aa_scene *)1;
		int rc = aa_scene_load_string(b->json, "bad.json", scene_dir(), &sc, &err);
		if (rc == 0) {
			aa_scene_free(sc);
			fail_msg("bad scene %zu loaded: %s", i, b->json);
		}
		assert_null(sc);
		if (strcmp(err.path, b->path) != 0 || !strstr(err.message, b->message) || err.code != b->code)
			fail_msg("bad scene %zu: got path '%s' code %s message '%s'; wanted path '%s' code %s message with '%s'",
				 i, err.path, aa_error_code_name(err.code), err.message, b->path, aa_error_code_name(b->code),
				 b->message);
		/* Messages name the file and, when there is one, the path. */
		assert_non_null(strstr(err.message, "bad.json"));
		if (b->path[0])
			assert_non_null(strstr(err.message, b->path));
	}
}

static void test_no_base_dir(void **state)
{
	(void)state;
	struct aa_error err = {0};
	struct aa_scene *sc;
	assert_int_equal(aa_scene_load_string("{\"objects\": [{\"mesh\": {\"type\": \"file\", \"path\": \"a.obj\"}}], " CAM
					      "}", NULL, NULL, &sc, &err), -1);
	assert_string_equal(err.path, "objects[0].mesh.path");
	assert_non_null(strstr(err.message, "not loaded from a directory"));
}

static void test_resolve(void **state)
{
	(void)state;
	char path[1024];
	struct aa_error err = {0};
	assert_int_equal(aa_scene_resolve("thin-wires", path, sizeof path, &err), 0);
	assert_non_null(strstr(path, "thin-wires.json"));
	assert_int_equal(aa_scene_resolve(path, path, sizeof path, &err), 0);
	assert_int_equal(aa_scene_resolve("no-such-scene", path, sizeof path, &err), -1);
	assert_int_equal(err.code, AA_ERR_NOT_FOUND);
	assert_non_null(strstr(err.message, "thin-wires")); /* lists what exists */
	assert_int_equal(aa_scene_resolve("../etc/passwd", path, sizeof path, &err), -1);
	assert_int_equal(err.code, AA_ERR_INVALID);
	assert_int_equal(aa_scene_resolve("missing/dir/x.json", path, sizeof path, &err), -1);
	assert_int_equal(err.code, AA_ERR_NOT_FOUND);
	struct aa_scene *sc;
	assert_int_equal(aa_scene_load("/nonexistent/x.json", &sc, &err), -1);
	assert_int_equal(err.code, AA_ERR_NOT_FOUND);
}

static struct aa_scene *load_ok(const char *json)
{
	struct aa_error err = {0};
	struct aa_scene *sc = NULL;
	if (aa_scene_load_string(json, "test.json", scene_dir(), &sc, &err))
		fail_msg("%s", err.message);
	return sc;
}

static void assert_vec3_near(vec3 a, vec3 b, float eps)
{
	if (v3_length(v3_sub(a, b)) > eps)
		fail_msg("(%g, %g, %g) != (%g, %g, %g)", a.x, a.y, a.z, b.x, b.y, b.z);
}

static void test_camera_paths(void **state)
{
	(void)state;
	struct aa_scene *sc = load_ok(
		"{\"objects\": [{\"mesh\": \"box\"}], \"camera\": {\"position\": [0, 1, 10], \"target\": [0, 1, 0]}, "
		"\"paths\": [{\"name\": \"keys\", \"type\": \"keyframes\", \"keys\": [{\"time\": 0}, "
		"{\"time\": 1, \"position\": [4, 1, 8]}, {\"time\": 2.5, \"position\": [6, 3, 4], \"fov\": 30}, "
		"{\"time\": 3, \"position\": [-5, 2, 2], \"target\": [0, 0, -3], \"cut\": true}, "
		"{\"time\": 4, \"position\": [-4, 2, 1]}]}, "
		"{\"name\": \"uniform\", \"type\": \"keyframes\", \"interpolation\": \"uniform\", \"keys\": [{\"time\": 0}, "
		"{\"time\": 2, \"position\": [2, 1, 10]}]}, "
		"{\"name\": \"orbit\", \"type\": \"orbit\", \"center\": [0, 0, 0], \"degrees\": 90, \"duration\": 2}, "
		"{\"name\": \"dolly\", \"type\": \"dolly\", \"distance\": 4, \"duration\": 2}, "
		"{\"name\": \"pan\", \"type\": \"pan\", \"degrees\": 90, \"duration\": 1}, "
		"{\"name\": \"still\", \"type\": \"static\"}]}");
	struct aa_camera c;
	bool cut;
	const struct aa_camera_path *p = aa_scene_find_path(sc, "default");
	assert_ptr_equal(p, &sc->paths[0]);
	assert_ptr_equal(aa_scene_find_path(sc, "static"), &sc->paths[0]);
	assert_ptr_equal(aa_scene_find_path(sc, "orbit"), &sc->paths[2]);
	assert_null(aa_scene_find_path(sc, "nope"));
	assert_true(p->duration == 4.0);

	/* Keyframes pass through every key, hold before a cut and jump at it. */
	for (int k = 0; k < p->key_count; k++) {
		aa_camera_path_eval(p, false, -1, p->keys[k].time, &c, &cut);
		assert_vec3_near(c.position, p->keys[k].camera.position, 1e-4f);
		assert_vec3_near(c.target, p->keys[k].camera.target, 1e-4f);
		assert_false(cut);
	}
	aa_camera_path_eval(p, false, -1, 2.5, &c, NULL);
	assert_float_equal(c.fov_y_degrees, 30.0f, 1e-4f);
	aa_camera_path_eval(p, false, -1, 2.9, &c, NULL);
	assert_vec3_near(c.position, v3(6, 3, 4), 1e-5f);
	aa_camera_path_eval(p, false, 1.0 / 30, 2.0 / 30, &c, &cut);
	assert_false(cut);
	aa_camera_path_eval(p, false, 2.99, 3.01, &c, &cut);
	assert_true(cut);
	aa_camera_path_eval(p, false, 3.0, 3.1, &c, &cut); /* (t_prev, t]: the cut was in the previous step */
	assert_false(cut);
	aa_camera_path_eval(p, false, -1, 3.01, &c, &cut); /* no previous frame: no cut */
	assert_false(cut);
	aa_camera_path_eval(p, false, -1, 100, &c, NULL); /* holds the end */
	assert_vec3_near(c.position, v3(-4, 2, 1), 1e-5f);
	/* Between keys the centripetal curve stays near the chord (no overshoot loops). */
	aa_camera_path_eval(p, false, -1, 0.5, &c, NULL);
	assert_true(c.position.x > 0.5f && c.position.x < 3.5f && c.position.z > 8.0f && c.position.z < 10.5f);

	/* Two-key uniform path: straight line, so the midpoint is the middle. */
	aa_camera_path_eval(&sc->paths[1], false, -1, 1.0, &c, NULL);
	assert_vec3_near(c.position, v3(1, 1, 10), 1e-4f);

	/* Static / hold_first hold the first camera whatever t is. */
	aa_camera_path_eval(p, true, 0.5, 3.5, &c, &cut);
	assert_vec3_near(c.position, v3(0, 1, 10), 1e-6f);
	assert_false(cut);
	aa_camera_path_eval(&sc->paths[5], false, -1, 7, &c, NULL);
	assert_vec3_near(c.position, v3(0, 1, 10), 1e-6f);

	/* Orbit: a quarter turn about +y keeps radius and height, keeps turning after `duration`. */
	aa_camera_path_eval(&sc->paths[2], false, -1, 2.0, &c, NULL);
	assert_vec3_near(c.position, v3(10, 1, 0), 1e-3f);
	aa_camera_path_eval(&sc->paths[2], false, -1, 4.0, &c, NULL);
	assert_vec3_near(c.position, v3(0, 1, -10), 1e-3f);

	/* Dolly: moves along the view direction by distance * t / duration. */
	aa_camera_path_eval(&sc->paths[3], false, -1, 1.0, &c, NULL);
	assert_vec3_near(c.position, v3(0, 1, 8), 1e-5f);
	assert_vec3_near(c.target, v3(0, 1, -2), 1e-5f);

	/* Pan: position fixed, the view turns left by `degrees` (right-handed about up). */
	aa_camera_path_eval(&sc->paths[4], false, -1, 1.0, &c, NULL);
	assert_vec3_near(c.position, v3(0, 1, 10), 1e-6f);
	assert_vec3_near(c.target, v3(-10, 1, 10), 1e-3f);
	aa_scene_free(sc);

	/* No paths in the file: one static path at the camera. */
	sc = load_ok("{\"objects\": [{\"mesh\": \"box\"}], " CAM "}");
	assert_int_equal(sc->path_count, 1);
	assert_int_equal(sc->paths[0].kind, AA_PATH_STATIC);
	aa_scene_free(sc);
}

static void test_animation(void **state)
{
	(void)state;
	struct aa_scene *sc = load_ok(
		"{\"objects\": [{\"mesh\": \"box\"}, "
		"{\"mesh\": \"box\", \"position\": [1, 2, 3], \"animation\": {\"velocity\": [2, 0, 0]}}, "
		"{\"mesh\": \"box\", \"animation\": {\"oscillate\": {\"axis\": [0, 2, 0], \"amplitude\": 0.5, "
		"\"frequency\": 0.25}}}, "
		"{\"mesh\": \"box\", \"position\": [5, 0, 0], \"animation\": {\"spin\": {\"axis\": [0, 0, 1], "
		"\"degrees_per_second\": 90}}}, "
		"{\"mesh\": \"box\", \"position\": [5, 0, 0], \"animation\": {\"spin\": {\"axis\": [0, 0, 1], "
		"\"degrees_per_second\": 90, \"pivot\": [0, 0, 0]}}}], " CAM "}");
	assert_true(aa_scene_has_animation(sc));
	assert_false(sc->objects[0].animation.active);
	vec3 o = v3(0, 0, 0), x = v3(1, 0, 0);
	assert_vec3_near(mat4_transform_point(aa_object_model_matrix(&sc->objects[0], 5), o), o, 1e-6f);
	assert_vec3_near(mat4_transform_point(aa_object_model_matrix(&sc->objects[1], 1.5), o), v3(4, 2, 3), 1e-5f);
	/* sin(2*pi*0.25*1) = 1: a full amplitude up the (normalised) axis. */
	assert_vec3_near(mat4_transform_point(aa_object_model_matrix(&sc->objects[2], 1.0), o), v3(0, 0.5f, 0), 1e-5f);
	assert_vec3_near(mat4_transform_point(aa_object_model_matrix(&sc->objects[2], 2.0), o), o, 1e-5f);
	/* Spin about the object's own position by default, about a given pivot otherwise. */
	assert_vec3_near(mat4_transform_point(aa_object_model_matrix(&sc->objects[3], 1.0), o), v3(5, 0, 0), 1e-5f);
	assert_vec3_near(mat4_transform_point(aa_object_model_matrix(&sc->objects[3], 1.0), x), v3(5, 1, 0), 1e-5f);
	assert_vec3_near(mat4_transform_point(aa_object_model_matrix(&sc->objects[4], 1.0), o), v3(0, 5, 0), 1e-4f);
	assert_vec3_near(mat4_transform_point(aa_object_model_matrix(&sc->objects[4], 4.0), o), v3(5, 0, 0), 1e-4f);
	aa_scene_free(sc);
}

/* Every procedural type, defaults and with parameters: valid, unit normals, consistent winding. */
static void test_procedural_meshes(void **state)
{
	(void)state;
	static const char *specs[] = {
		"\"plane\"", "{\"type\": \"plane\", \"size\": [4, 2], \"subdivisions\": [3, 5], \"uv_repeat\": 2}",
		"\"box\"", "{\"type\": \"box\", \"size\": [3, 0.01, 0.5]}", "\"sphere\"",
		"{\"type\": \"sphere\", \"radius\": 2, \"stacks\": 3, \"slices\": 5}", "\"cylinder\"",
		"{\"type\": \"cylinder\", \"caps\": false, \"segments\": 3}", "\"wires\"",
		("{\"type\": \"wires\", \"points\": [[0, 5, 0], [0, 5, 10], [3, 6, 20]], \"count\": 4, \"radius\": 0.002, "
		 "\"sides\": 3}"), "{\"type\": \"wires\", \"points\": [[0, 0, 0], [0, 10, 0]], \"sag\": 0}", "\"fence\"",
		"{\"type\": \"fence\", \"style\": \"grid\", \"grid_spacing\": 0.2}", "\"blinds\"",
		"{\"type\": \"blinds\", \"tilt\": -80, \"cords\": false}", "\"stairs\"", "\"wheel\"",
		"{\"type\": \"wheel\", \"spokes\": 0}", "\"hairball\"", "{\"type\": \"hairball\", \"count\": 50, \"sides\": 5}",
	};
	for (size_t i = 0; i < sizeof specs / sizeof specs[0]; i++) {
		char json[600];
		snprintf(json, sizeof json, "{\"objects\": [{\"mesh\": %s}], " CAM "}", specs[i]);
		struct aa_scene *sc = load_ok(json);
		assert_int_equal(sc->mesh_count, 1);
		check_mesh(&sc->meshes[0]);
		aa_scene_free(sc);
	}
	/* Closed convex shapes: every normal points away from the centre. */
	struct aa_scene *sc = load_ok("{\"objects\": [{\"mesh\": \"box\"}, {\"mesh\": \"sphere\"}, "
				      "{\"mesh\": \"cylinder\"}], " CAM "}");
	for (int m = 0; m < sc->mesh_count; m++)
		for (uint32_t v = 0; v < sc->meshes[m].vertex_count; v++) {
			const struct aa_vertex *vx = &sc->meshes[m].vertices[v];
			float d = vx->position[0] * vx->normal[0] + vx->position[1] * vx->normal[1] +
				  vx->position[2] * vx->normal[2];
			assert_true(d > 0.0f);
		}
	assert_int_equal(sc->meshes[0].index_count / 3, 12);
	assert_int_equal(sc->meshes[1].index_count / 3, 2 * 16 * 32 - 2 * 32); /* poles are single triangles */
	aa_scene_free(sc);
	/* The plane faces +y with u along +x and v along +z. */
	sc = load_ok("{\"objects\": [{\"mesh\": {\"type\": \"plane\", \"size\": [2, 2]}}], " CAM "}");
	for (uint32_t v = 0; v < sc->meshes[0].vertex_count; v++) {
		const struct aa_vertex *vx = &sc->meshes[0].vertices[v];
		assert_float_equal(vx->normal[1], 1.0f, 1e-6f);
		assert_float_equal(vx->uv[0], (vx->position[0] + 1) / 2, 1e-6f);
		assert_float_equal(vx->uv[1], (vx->position[2] + 1) / 2, 1e-6f);
	}
	aa_scene_free(sc);
}

static void test_mesh_files(void **state)
{
	(void)state;
	struct aa_scene *sc = load_ok("{\"meshes\": {\"torus\": {\"type\": \"file\", \"path\": \"assets/torus.obj\"}, "
				      "\"gem\": {\"type\": \"file\", \"path\": \"assets/gem.gltf\"}}, "
				      "\"objects\": [{\"mesh\": \"torus\"}, {\"mesh\": \"gem\"}, {\"mesh\": \"torus\"}], " CAM "}");
	assert_int_equal(sc->mesh_count, 2);
	assert_int_equal(sc->meshes[0].index_count / 3, 24 * 12 * 2);
	assert_int_equal(sc->meshes[1].index_count / 3, 32);
	check_mesh(&sc->meshes[0]);
	check_mesh(&sc->meshes[1]);
	assert_int_equal(aa_scene_triangle_count(sc), 2 * 576 + 32); /* drawn: the torus twice */
	aa_scene_free(sc);
}

static void test_textures(void **state)
{
	(void)state;
	/* Every character the font claims has a glyph with some ink (except space). */
	for (const char *c = aa_font5x7_charset(); *c; c++) {
		uint8_t rows[7];
		assert_int_equal(aa_font5x7_glyph(*c, rows), 0);
		int ink = 0;
		for (int y = 0; y < 7; y++)
			ink |= rows[y];
		assert_true(*c == ' ' ? ink == 0 : ink != 0);
	}
	uint8_t rows[7];
	assert_int_equal(aa_font5x7_glyph('a', rows), 0); /* lower case draws as upper case */
	assert_int_equal(aa_font5x7_glyph('~', rows), -1);

	struct aa_texture t = {0};
	struct aa_error err = {0};
	const float white[4] = {1, 1, 1, 1}, black[4] = {0, 0, 0, 1};
	assert_int_equal(aa_texture_text(&t, "AB\nC", white, black, 2, 1, false, &err), 0);
	assert_int_equal(t.width, (2 * 1 + 2 * 6 - 1) * 2);
	assert_int_equal(t.height, (2 * 1 + 2 * 8 - 1) * 2);
	assert_int_equal(t.mip_levels, aa_texture_mip_count(t.width, t.height));
	/* 'A' top row is ".###.": texel (padding + 1 dot) * scale is ink, the padding is background. */
	assert_int_equal(t.mips[0][((2 * t.width) + 4) * 4], 255);
	assert_int_equal(t.mips[0][0], 0);
	int last = t.mip_levels - 1;
	assert_non_null(t.mips[last]);
	aa_texture_free(&t);

	/* Mips average in linear light: a 2x2 black/white checker becomes sRGB(0.5) = 188, not 128. */
	uint8_t px[16] = {0, 0, 0, 255, 255, 255, 255, 255, 255, 255, 255, 255, 0, 0, 0, 255};
	assert_int_equal(aa_texture_from_rgba8(&t, px, 2, 2, &err), 0);
	assert_int_equal(t.mip_levels, 2);
	assert_in_range(t.mips[1][0], 187, 189);
	assert_int_equal(t.mips[1][3], 255);
	aa_texture_free(&t);
	/* Where alpha is coverage, colour is weighted by it: a transparent texel's colour does not bleed into
	 * the mip. Where it is not (glTF OPAQUE), colour is averaged alone: red and green of alpha 0 give
	 * sRGB(0.5) of each, not black. Rebuilt either way from level 0. */
	uint8_t px2[8] = {255, 0, 0, 255, 0, 255, 0, 0};
	assert_int_equal(aa_texture_from_rgba8_as(&t, px2, 2, 1, AA_TEXELS_COVERAGE, &err), 0);
	assert_int_equal(t.mips[1][0], 255);
	assert_int_equal(t.mips[1][1], 0);
	assert_in_range(t.mips[1][3], 127, 128);
	assert_int_equal(aa_texture_rebuild(&t, false, &err), 0);
	assert_in_range(t.mips[1][0], 187, 189);
	assert_in_range(t.mips[1][1], 187, 189);
	assert_in_range(t.mips[1][3], 127, 128);
	aa_texture_free(&t);
	uint8_t px3[8] = {255, 0, 0, 0, 0, 255, 0, 0};
	assert_int_equal(aa_texture_from_rgba8(&t, px3, 2, 1, &err), 0);
	assert_false(t.coverage);
	assert_in_range(t.mips[1][0], 187, 189);
	assert_in_range(t.mips[1][1], 187, 189);
	assert_int_equal(t.mips[1][3], 0);
	aa_texture_free(&t);
	/* Odd sizes and the cap. */
	uint8_t *big = calloc(7 * 5 * 4, 1);
	assert_int_equal(aa_texture_from_rgba8(&t, big, 7, 5, &err), 0);
	assert_int_equal(t.mip_levels, 3);
	aa_texture_free(&t);
	assert_int_equal(aa_texture_from_rgba8(&t, big, 5000, 1, &err), -1);
	assert_int_equal(err.code, AA_ERR_LIMIT);
	free(big);

	/* An image texture through the scene file. */
	struct aa_scene *sc = load_ok("{\"textures\": {\"bricks\": {\"file\": \"assets/tiles.png\"}}, "
				      "\"materials\": {\"m\": {\"texture\": \"bricks\"}}, "
				      "\"objects\": [{\"mesh\": \"box\", \"material\": \"m\"}], " CAM "}");
	assert_int_equal(sc->texture_count, 1);
	assert_int_equal(sc->textures[0].width, 256);
	assert_int_equal(sc->textures[0].mip_levels, 9);
	assert_int_equal(sc->materials[0].pattern, AA_PATTERN_TEXTURE);
	assert_int_equal(sc->materials[0].texture_index, 0);
	assert_false(sc->textures[0].coverage);
	aa_scene_free(sc);

	/* A texture shared by a cut-out and a plain material: the cut-out one gets its own copy with
	 * alpha-weighted mips; a texture used only by cut-outs is rebuilt in place. */
	sc = load_ok("{\"textures\": {\"wire\": {\"file\": \"assets/chainlink.png\"}, "
		     "\"sign\": {\"text\": \"A\", \"background\": [0, 0, 0, 0]}}, "
		     "\"materials\": {\"plain\": {\"texture\": \"wire\"}, "
		     "\"cut\": {\"texture\": \"wire\", \"alpha_cutout\": true}, "
		     "\"letters\": {\"texture\": \"sign\", \"alpha_cutout\": true}}, "
		     "\"objects\": [{\"mesh\": \"box\", \"material\": \"plain\"}], " CAM "}");
	assert_int_equal(sc->texture_count, 3);
	int plain = -1, cut = -1, letters = -1;
	for (int i = 0; i < sc->material_count; i++) {
		if (strcmp(sc->materials[i].name, "plain") == 0)
			plain = sc->materials[i].texture_index;
		if (strcmp(sc->materials[i].name, "cut") == 0)
			cut = sc->materials[i].texture_index;
		if (strcmp(sc->materials[i].name, "letters") == 0)
			letters = sc->materials[i].texture_index;
	}
	assert_true(plain >= 0 && cut >= 0 && letters >= 0 && plain != cut);
	assert_false(sc->textures[plain].coverage);
	assert_true(sc->textures[cut].coverage);
	assert_true(sc->textures[letters].coverage);
	assert_int_equal(sc->textures[cut].width, sc->textures[plain].width);
	assert_memory_equal(sc->textures[cut].mips[0], sc->textures[plain].mips[0],
			    (size_t)sc->textures[plain].width * sc->textures[plain].height * 4);
	aa_scene_free(sc);
}

static void test_colors_and_defaults(void **state)
{
	(void)state;
	struct aa_scene *sc = load_ok("{\"background\": \"#FFFFFF\", \"ambient\": [0.25, 0.5, 0], "
				      "\"materials\": {\"a\": {\"color\": \"#808080\"}}, "
				      "\"objects\": [{\"mesh\": \"box\", \"material\": \"a\"}, {\"mesh\": \"box\"}], " CAM "}");
	assert_float_equal(sc->background[0], 1.0f, 1e-6f);
	assert_float_equal(sc->ambient[1], 0.5f, 1e-6f); /* arrays are linear, as is */
	assert_float_equal(sc->materials[0].base_color[0], 0.2158605f, 1e-4f); /* "#80" is sRGB */
	assert_float_equal(sc->fps, 30.0, 1e-9);
	assert_string_equal(sc->name, "test");
	/* An object without a material gets the implicit "default". */
	assert_string_equal(sc->materials[sc->objects[1].material_index].name, "default");
	assert_false(aa_scene_has_shadow_caster_light(sc));
	assert_false(aa_scene_has_cutout(sc));
	assert_false(aa_scene_has_animation(sc));
	aa_scene_free(sc);
}

/* A polygon vertex (x, y) in pixels lands on pixel position (x, y) through view + ortho projection. */
static void test_polygons_map_to_pixels(void **state)
{
	(void)state;
	const int w = 64, h = 48;
	struct aa_polygon2d polys[2] = {
		{.count = 3, .xy = {{3.25, 5.5}, {60, 10}, {20.75, 40}}},
		{.count = 4, .xy = {{0, 0}, {0, 48}, {64, 48}, {64, 0}}}, /* the other winding */
	};
	const float fg[3] = {1, 1, 1}, bg[3] = {0, 0, 0};
	struct aa_scene *sc;
	struct aa_error err = {0};
	assert_int_equal(aa_scene_from_polygons(polys, 2, w, h, fg, bg, &sc, &err), 0);
	assert_true(sc->materials[0].unlit);
	assert_int_equal(aa_scene_triangle_count(sc), 1 + 2);
	check_mesh(&sc->meshes[0]);
	struct aa_camera c;
	aa_camera_path_eval(aa_scene_find_path(sc, "default"), false, -1, 0, &c, NULL);
	assert_int_equal(c.projection, AA_PROJECTION_ORTHOGRAPHIC);
	mat4 view = mat4_look_at(c.position, c.target, c.up);
	mat4 proj = mat4_ortho_reversed_z(c.ortho_height * (float)w / (float)h, c.ortho_height, c.near_plane,
					  c.far_plane);
	mat4 mvp = mat4_mul(proj, mat4_mul(view, aa_object_model_matrix(&sc->objects[0], 0)));
	const struct aa_mesh *m = &sc->meshes[0];
	for (int p = 0, v = 0; p < 2; p++)
		for (int k = 0; k < polys[p].count; k++, v++) {
			const float *pos = m->vertices[v].position;
			vec3 ndc = mat4_transform_point(mvp, v3(pos[0], pos[1], pos[2]));
			double px = (ndc.x + 1.0) * 0.5 * w, py = (ndc.y + 1.0) * 0.5 * h;
			assert_float_equal(px, polys[p].xy[k][0], 1e-4);
			assert_float_equal(py, polys[p].xy[k][1], 1e-4);
			assert_true(ndc.z > 0.0f && ndc.z < 1.0f);
		}
	/* Every triangle faces the camera (+z). */
	for (uint32_t i = 0; i < m->index_count; i += 3) {
		const float *a = m->vertices[m->indices[i]].position, *b = m->vertices[m->indices[i + 1]].position,
			    *d = m->vertices[m->indices[i + 2]].position;
		float cz = (b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0]);
		assert_true(cz > 0.0f);
	}
	aa_scene_free(sc);
	polys[0].count = 2;
	assert_int_equal(aa_scene_from_polygons(polys, 1, w, h, fg, bg, &sc, &err), -1);
	assert_null(sc);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_shipped_scenes),
		cmocka_unit_test(test_bad_scenes),
		cmocka_unit_test(test_no_base_dir),
		cmocka_unit_test(test_resolve),
		cmocka_unit_test(test_camera_paths),
		cmocka_unit_test(test_animation),
		cmocka_unit_test(test_procedural_meshes),
		cmocka_unit_test(test_mesh_files),
		cmocka_unit_test(test_textures),
		cmocka_unit_test(test_colors_and_defaults),
		cmocka_unit_test(test_polygons_map_to_pixels),
	};
	return cmocka_run_group_tests(tests, setup, NULL);
}
