/* Mesh files as their authors made them, without a GPU: the test assets that
 * scripts/make_scene_assets.py writes into tests/assets/ load with their materials, skins and animations,
 * each broken file is refused naming the file and the field or extension, and what is dropped or
 * approximated comes back as warnings. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "scene/scene.h"

#define CAM "\"camera\": {\"position\": [0, 0, 5], \"target\": [0, 0, 0]}"

static char assets[1024];

static int setup(void **state)
{
	(void)state;
	const char *top = getenv("top_srcdir");
#ifdef AA_SOURCE_SCENE_DIR
	if (!top || !top[0]) {
		snprintf(assets, sizeof assets, "%s/../tests/assets", AA_SOURCE_SCENE_DIR);
		return 0;
	}
#endif
	if (!top)
		return -1;
	snprintf(assets, sizeof assets, "%s/tests/assets", top);
	return 0;
}

/* A scene of one object drawing `file` (plus `extra` keys in the object). */
static int load_file(const char *file, const char *mesh_extra, const char *object_extra, struct aa_scene **sc,
		     struct aa_error *err)
{
	char json[1024];
	snprintf(json, sizeof json,
		 "{\"materials\": {\"paint\": {\"color\": [0.2, 0.3, 0.4]}}, \"objects\": [{\"name\": \"thing\", "
		 "\"mesh\": {\"type\": \"file\", \"path\": \"%s\"%s}%s}], " CAM "}", file, mesh_extra, object_extra);
	return aa_scene_load_string(json, "scene.json", assets, sc, err);
}

static struct aa_scene *load_ok(const char *file, const char *mesh_extra, const char *object_extra)
{
	struct aa_scene *sc = NULL;
	struct aa_error err = {0};
	if (load_file(file, mesh_extra, object_extra, &sc, &err))
		fail_msg("%s did not load: %s", file, err.message);
	return sc;
}

static const struct aa_material *material_of(const struct aa_scene *sc, const char *suffix)
{
	for (int i = 0; i < sc->material_count; i++) {
		size_t a = strlen(sc->materials[i].name), b = strlen(suffix);
		if (a >= b && strcmp(sc->materials[i].name + a - b, suffix) == 0)
			return &sc->materials[i];
	}
	fail_msg("no material named ...%s", suffix);
	return NULL;
}

static bool near(float a, float b, float tolerance)
{
	return fabsf(a - b) <= tolerance;
}

/* Every refusal rule: the file, the field or extension and what is wrong, at the object's mesh path. */
static void test_refusals(void **state)
{
	(void)state;
	static const struct {
		const char *file, *says;
		enum aa_error_code code;
	} refused[] = {
		{"broken-required-extension.gltf", "requires the extension EXT_unknown_foo (extensionsRequired[0])",
		 AA_ERR_INVALID},
		{"broken-index-range.gltf", "meshes[0].primitives[0].indices: index 60000", AA_ERR_INVALID},
		{"broken-nan-position.gltf", "not a finite number", AA_ERR_INVALID},
		{"broken-huge-position.gltf", "vertex 2 is at (1e+30, -0.5, 0): positions must be within 1e+07",
		 AA_ERR_INVALID},
		{"broken-nan-position.obj", "not a finite number", AA_ERR_INVALID},
		{"broken-huge-position.obj", "vertex 2 is at (1e+30, 1, 0): positions must be within 1e+07", AA_ERR_INVALID},
		{"broken-huge-position.ply", "vertex 2 is at (0, 3e+09, 0): positions must be within 1e+07", AA_ERR_INVALID},
		{"broken-index-range.obj", "a face names a vertex that does not exist", AA_ERR_INVALID},
		{"broken-truncated.glb", "truncated: its header says 1060 bytes, the file has 530", AA_ERR_INVALID},
		{"broken-not-json.gltf", "is not glTF", AA_ERR_INVALID},
		{"broken-gltf1.gltf", "is glTF 1.0 (asset.version), which aalab does not read: convert it to glTF 2.0",
		 AA_ERR_INVALID},
		{"broken-missing-texture.gltf", "texture 'missing-texture.png' not found", AA_ERR_NOT_FOUND},
		{"broken-missing-mtl.obj", "material library (mtllib) 'no-such-file.mtl' not found", AA_ERR_NOT_FOUND},
		{"broken-missing-map.obj", "texture 'no-such-image.png' not found", AA_ERR_NOT_FOUND},
		{"broken-morph-targets.gltf", "meshes[0].primitives[0] has morph targets", AA_ERR_INVALID},
	};
	for (size_t i = 0; i < sizeof refused / sizeof refused[0]; i++) {
		struct aa_scene *sc = NULL;
		struct aa_error err = {0};
		if (load_file(refused[i].file, "", "", &sc, &err) == 0) {
			aa_scene_free(sc);
			fail_msg("%s loaded", refused[i].file);
		}
		char file[160];
		snprintf(file, sizeof file, "mesh file '%s'", refused[i].file);
		if (!strstr(err.message, file) || !strstr(err.message, refused[i].says) || err.code != refused[i].code ||
		    strcmp(err.path, "objects[0].mesh.path") != 0)
			fail_msg("%s: got [%s] %s: %s; wanted [%s] and '%s'", refused[i].file, aa_error_code_name(err.code),
				 err.path, err.message, aa_error_code_name(refused[i].code), refused[i].says);
	}
}

/* "missing_files": "warn": the material goes without the texture, and the scene says so. */
static void test_missing_files_as_warnings(void **state)
{
	(void)state;
	struct aa_scene *sc = load_ok("broken-missing-texture.gltf", ", \"missing_files\": \"warn\"", "");
	assert_int_equal(sc->warning_count, 1);
	assert_non_null(strstr(sc->warnings[0], "texture 'missing-texture.png' not found: drawn without it"));
	assert_int_equal(material_of(sc, "/lost")->texture_index, -1);
	aa_scene_free(sc);
	sc = load_ok("broken-missing-mtl.obj", ", \"missing_files\": \"warn\"", "");
	assert_int_equal(sc->warning_count, 1);
	assert_non_null(strstr(sc->warnings[0], "material library 'no-such-file.mtl' not found"));
	aa_scene_free(sc);
}

/* base-color.gltf: a factor, a texture times a factor, KHR_materials_unlit; one object part each. */
static void test_base_color_materials(void **state)
{
	(void)state;
	struct aa_scene *sc = load_ok("base-color.gltf", "", "");
	assert_int_equal(sc->object_count, 3); /* one draw per material, one object id */
	for (int o = 0; o < 3; o++)
		assert_int_equal(sc->objects[o].model_id, 1);
	assert_int_equal(sc->model_count, 1);
	const struct aa_material *factor = material_of(sc, "/factor"), *textured = material_of(sc, "/texture"),
				 *unlit = material_of(sc, "/unlit");
	assert_int_equal(factor->model, AA_SHADING_METAL_ROUGH);
	assert_true(near(factor->base_color[0], 0.8f, 1e-6f) && near(factor->base_color[1], 0.1f, 1e-6f));
	assert_true(factor->metallic == 0.0f && factor->roughness == 1.0f && factor->single_sided);
	assert_int_equal(factor->texture_index, -1);
	assert_int_equal(textured->pattern, AA_PATTERN_TEXTURE);
	assert_true(textured->texture_index >= 0 && textured->maps[AA_MAP_BASE] == textured->texture_index);
	assert_false(sc->textures[textured->texture_index].linear); /* colour: sRGB */
	assert_true(textured->scale[0] == 1.0f && textured->scale[1] == 1.0f);
	assert_true(near(textured->base_color[2], 0.5f, 1e-6f));
	assert_true(unlit->unlit);
	/* every part of the object draws its own material, none the scene's default */
	for (int o = 0; o < 3; o++)
		assert_int_equal(sc->meshes[sc->objects[o].mesh_index].file_material, sc->objects[o].material_index);
	aa_scene_free(sc);
}

/* An object's "material" draws every part with it, and the file's materials are not loaded. */
static void test_scene_material_overrides(void **state)
{
	(void)state;
	struct aa_scene *sc = load_ok("base-color.gltf", "", ", \"material\": \"paint\"");
	assert_int_equal(sc->object_count, 3);
	assert_int_equal(sc->material_count, 1);
	assert_int_equal(sc->texture_count, 0);
	for (int o = 0; o < 3; o++)
		assert_string_equal(sc->materials[sc->objects[o].material_index].name, "paint");
	aa_scene_free(sc);
	/* a named mesh: its file materials load only when some object keeps them */
	struct aa_error err = {0};
	const char *overridden = "{\"materials\": {\"paint\": {}}, \"meshes\": {\"m\": {\"type\": \"file\", \"path\": "
				 "\"base-color.gltf\"}}, \"objects\": [{\"mesh\": \"m\", \"material\": \"paint\"}, "
				 "{\"mesh\": \"m\", \"material\": \"paint\"}], " CAM "}";
	assert_int_equal(aa_scene_load_string(overridden, "named.json", assets, &sc, &err), 0);
	assert_int_equal(sc->object_count, 6);
	assert_int_equal(sc->material_count, 1);
	assert_int_equal(sc->texture_count, 0);
	aa_scene_free(sc);
	const char *kept = "{\"materials\": {\"paint\": {}}, \"meshes\": {\"m\": {\"type\": \"file\", \"path\": "
			   "\"base-color.gltf\"}}, \"objects\": [{\"mesh\": \"m\", \"material\": \"paint\"}, "
			   "{\"mesh\": \"m\"}], " CAM "}";
	assert_int_equal(aa_scene_load_string(kept, "named.json", assets, &sc, &err), 0);
	assert_int_equal(sc->material_count, 4);
	assert_string_equal(sc->materials[sc->objects[0].material_index].name, "paint");
	assert_true(sc->materials[sc->objects[3].material_index].model == AA_SHADING_METAL_ROUGH);
	aa_scene_free(sc);
}

static void test_alpha_modes(void **state)
{
	(void)state;
	struct aa_scene *sc = load_ok("alpha-modes.gltf", "", "");
	const struct aa_material *mask = material_of(sc, "/mask"), *blend = material_of(sc, "/blend"),
				 *opaque = material_of(sc, "/opaque");
	assert_true(mask->alpha_cutout && mask->alpha_cutoff == 0.5f && !mask->blend);
	assert_true(blend->blend && !blend->alpha_cutout && blend->base_color[3] == 0.5f);
	assert_true(!opaque->blend && !opaque->alpha_cutout && opaque->base_color[3] == 1.0f); /* alpha ignored */
	assert_true(aa_scene_has_cutout(sc));
	aa_scene_free(sc);
}

static void test_emissive_and_maps(void **state)
{
	(void)state;
	struct aa_scene *sc = load_ok("emissive.gltf", "", "");
	const struct aa_material *strength = material_of(sc, "/strength"), *textured = material_of(sc, "/texture");
	/* emissiveFactor (0.4, 0.2, 0) x KHR_materials_emissive_strength 2 */
	assert_true(near(strength->emissive[0], 0.8f, 1e-6f) && near(strength->emissive[1], 0.4f, 1e-6f) &&
		    strength->emissive[2] == 0.0f);
	assert_int_equal(strength->maps[AA_MAP_EMISSIVE], -1);
	assert_true(textured->maps[AA_MAP_EMISSIVE] >= 0);
	assert_false(sc->textures[textured->maps[AA_MAP_EMISSIVE]].linear);
	aa_scene_free(sc);

	sc = load_ok("metallic-roughness.gltf", "", "");
	const struct aa_material *metal = material_of(sc, "/metal"), *mapped = material_of(sc, "/mapped");
	assert_true(metal->metallic == 1.0f && near(metal->roughness, 0.3f, 1e-6f));
	assert_true(mapped->maps[AA_MAP_METAL_ROUGH] >= 0 && mapped->maps[AA_MAP_OCCLUSION] >= 0);
	assert_true(sc->textures[mapped->maps[AA_MAP_METAL_ROUGH]].linear); /* data, not colour */
	/* one image used for both maps is loaded once */
	assert_int_equal(mapped->maps[AA_MAP_METAL_ROUGH], mapped->maps[AA_MAP_OCCLUSION]);
	aa_scene_free(sc);
}

/* Tangents: generated from the uvs where the file has none (+u is +x on this quad, the bitangent up the
 * image is +y: w = +1), the file's where it has them (-x). */
static void test_normal_map_tangents(void **state)
{
	(void)state;
	struct aa_scene *sc = load_ok("normal-map.gltf", "", "");
	const struct aa_mesh *m = &sc->meshes[sc->objects[0].mesh_index];
	assert_true(material_of(sc, "/bumpy")->maps[AA_MAP_NORMAL] >= 0);
	int generated = 0, given = 0;
	for (uint32_t v = 0; v < m->vertex_count; v++) {
		const float *t = m->vertices[v].tangent;
		if (m->vertices[v].position[0] < 0) { /* the left quad: no TANGENT in the file */
			assert_true(near(t[0], 1, 1e-5f) && near(t[1], 0, 1e-5f) && near(t[2], 0, 1e-5f) && t[3] == 1.0f);
			generated++;
		} else {
			assert_true(near(t[0], -1, 1e-5f) && near(t[1], 0, 1e-5f) && t[3] == 1.0f);
			given++;
		}
	}
	assert_int_equal(generated, 4);
	assert_int_equal(given, 4);
	aa_scene_free(sc);
}

/* KHR_texture_transform: offset (0.5, 0.5), rotation 90 degrees: uv' = (v + 0.5, -u + 0.5). */
static void test_texture_transform(void **state)
{
	(void)state;
	struct aa_scene *sc = load_ok("texture-transform.gltf", "", "");
	const struct aa_material *plain = material_of(sc, "/plain"), *moved = material_of(sc, "/moved");
	assert_false(plain->uv_transformed);
	assert_true(moved->uv_transformed);
	const float *m = moved->uv_transform[AA_MAP_BASE];
	static const float want[6] = {0, 1, 0.5f, -1, 0, 0.5f};
	for (int k = 0; k < 6; k++)
		if (!near(m[k], want[k], 1e-6f))
			fail_msg("uv transform [%g %g %g / %g %g %g]", m[0], m[1], m[2], m[3], m[4], m[5]);
	aa_scene_free(sc);
}

/* skin.gltf: the bar stands where its joints put it, not 100 units off where its own node says (the
 * node transform of a skinned mesh is ignored); "bend" turns its top 90 degrees about +z at y = 1. */
static void test_skin_and_animation(void **state)
{
	(void)state;
	struct aa_scene *sc = load_ok("skin.gltf", "", ", \"animation\": {\"clip\": \"bend\", \"time\": 0.25, \"speed\": 0.5}");
	const struct aa_object *o = &sc->objects[0];
	const struct aa_mesh *m = &sc->meshes[o->mesh_index];
	assert_int_equal(sc->rig_count, 1);
	assert_true(m->rig == 0 && m->skin != NULL);
	const struct aa_rig *rig = &sc->rigs[0];
	assert_int_equal(rig->joint_count, 2);
	assert_int_equal(rig->clip_count, 1);
	assert_string_equal(rig->clips[0].name, "bend");
	assert_true(near((float)rig->clips[0].duration, 1.0f, 1e-6f));
	assert_int_equal(o->pose.clip, 0);
	assert_true(o->pose.clip_time == 0.25 && o->pose.clip_speed == 0.5);
	assert_true(aa_object_is_animated(sc, o) && aa_scene_has_animation(sc));

	mat4 joints[2];
	struct aa_vertex posed[12];
	assert_int_equal(m->vertex_count, 12);
	/* the rest pose: the bar as the file has it, at the origin */
	struct aa_pose rest = {.clip = -1};
	aa_rig_pose(rig, &rest, 0.0, joints);
	aa_mesh_skin(m, joints, posed);
	for (uint32_t v = 0; v < 12; v++)
		for (int k = 0; k < 3; k++)
			if (!near(posed[v].position[k], m->vertices[v].position[k], 1e-5f))
				fail_msg("rest pose moved vertex %u", v);
	/* t = 1.5 s: clip time 0.25 + 0.5 x 1.5 = 1, the bend complete */
	aa_rig_pose(rig, &o->pose, 1.5, joints);
	aa_mesh_skin(m, joints, posed);
	for (uint32_t v = 0; v < 12; v++) {
		const float *p = m->vertices[v].position, *q = posed[v].position;
		if (p[1] < 0.5f) { /* the bottom ring follows joint 0, which stays */
			assert_true(near(q[0], p[0], 1e-5f) && near(q[1], p[1], 1e-5f));
		} else if (p[1] > 1.5f) { /* the top ring: turned about (0, 1) by 90 degrees: (x, y) -> (1 - y, 1 + x) */
			if (!near(q[0], 1.0f - p[1], 1e-4f) || !near(q[1], 1.0f + p[0], 1e-4f) || !near(q[2], p[2], 1e-4f))
				fail_msg("top vertex (%g, %g, %g) went to (%g, %g, %g)", p[0], p[1], p[2], q[0], q[1], q[2]);
			/* normals turn with it: the +x side now faces +y */
			const float *n0 = m->vertices[v].normal, *n1 = posed[v].normal;
			assert_true(near(n1[0], -n0[1], 1e-4f) && near(n1[1], n0[0], 1e-4f));
		}
	}
	/* halfway (clip time 0.5) the slerp is at 45 degrees */
	aa_rig_pose(rig, &o->pose, 0.5, joints);
	aa_mesh_skin(m, joints, posed);
	for (uint32_t v = 0; v < 12; v++)
		if (m->vertices[v].position[1] > 1.5f && m->vertices[v].position[0] == 0.1f) {
			float x = 0.1f, y = 1.0f, c = sqrtf(0.5f);
			assert_true(near(posed[v].position[0], c * x - c * y, 1e-4f));
			assert_true(near(posed[v].position[1], 1.0f + c * x + c * y, 1e-4f));
		}
	aa_scene_free(sc);

	/* held: speed 0 does not move, so nothing is animated */
	sc = load_ok("skin.gltf", "", ", \"animation\": {\"clip\": \"bend\", \"speed\": 0}");
	assert_false(aa_scene_has_animation(sc));
	aa_scene_free(sc);
}

/* Rotations interpolate the shorter way: keys q and -q' (the same turns as q and q') meet halfway at 45
 * degrees, not at -135. A rig built by hand: one node, one rotation channel of two keys. */
static void test_rotation_takes_the_short_way(void **state)
{
	(void)state;
	float times[2] = {0, 1}, s = sqrtf(0.5f);
	float values[8] = {0, 0, 0, 1, 0, 0, -s, -s};
	struct aa_rig_channel channel = {.node = 0, .path = AA_CHANNEL_ROTATION, .key_count = 2, .times = times,
					 .values = values};
	struct aa_rig_clip clip = {.name = "turn", .duration = 1, .channel_count = 1, .channels = &channel};
	struct aa_rig_node node = {.parent = -1, .rotation = {0, 0, 0, 1}, .scale = {1, 1, 1}};
	int joint_node = 0;
	mat4 ibm = mat4_identity(), joint;
	struct aa_rig rig = {.node_count = 1, .nodes = &node, .joint_count = 1, .joint_node = &joint_node,
			     .inverse_bind = &ibm, .clip_count = 1, .clips = &clip};
	struct aa_pose pose = {.clip = 0, .clip_time = 0.5, .clip_speed = 0};
	aa_rig_pose(&rig, &pose, 0, &joint);
	vec3 x = mat4_transform_dir(joint, v3(1, 0, 0));
	if (!near(x.x, s, 1e-5f) || !near(x.y, s, 1e-5f))
		fail_msg("+x went to (%g, %g, %g); 45 degrees about +z expected", x.x, x.y, x.z);
}

static void test_animation_errors(void **state)
{
	(void)state;
	struct aa_scene *sc = NULL;
	struct aa_error err = {0};
	assert_int_equal(load_file("skin.gltf", "", ", \"animation\": {\"clip\": \"jump\"}", &sc, &err), -1);
	assert_string_equal(err.path, "objects[0].animation.clip");
	assert_non_null(strstr(err.message, "unknown animation 'jump' (the mesh file has: bend)"));
	assert_int_equal(load_file("skin.gltf", "", ", \"animation\": {\"time\": 1}", &sc, &err), -1);
	assert_string_equal(err.path, "objects[0].animation.time");
	assert_int_equal(load_file("base-color.gltf", "", ", \"animation\": {\"clip\": \"bend\"}", &sc, &err), -1);
	assert_non_null(strstr(err.message, "has no animations"));
	assert_int_equal(load_file("skin.gltf", ", \"missing_files\": \"maybe\"", "", &sc, &err), -1);
	assert_string_equal(err.path, "objects[0].mesh.missing_files");
}

/* What the loader drops or approximates comes back once each, naming the file. */
static void test_warnings(void **state)
{
	(void)state;
	struct aa_scene *sc = load_ok("warnings.gltf", "", "");
	static const char *const expected[] = {
		"warnings.gltf: uses the extension KHR_materials_clearcoat, which aalab ignores",
		"warnings.gltf: materials[0] 'bar': baseColorTexture reads TEXCOORD_1; aalab draws it with TEXCOORD_0",
		"warnings.gltf: animations[0] 'bend' has CUBICSPLINE keys; aalab interpolates them linearly",
		"metallicFactor outside [0, 1] (or not a number): clamped",
	};
	for (size_t i = 0; i < sizeof expected / sizeof expected[0]; i++) {
		bool found = false;
		for (int w = 0; w < sc->warning_count; w++)
			found |= strstr(sc->warnings[w], expected[i]) != NULL;
		if (!found)
			fail_msg("no warning '%s' among %d", expected[i], sc->warning_count);
	}
	assert_int_equal(sc->warning_count, 4);
	assert_true(material_of(sc, "/bar")->metallic == 1.0f);
	aa_scene_free(sc);
	/* a file loaded twice in one scene warns once */
	char json[512];
	snprintf(json, sizeof json, "{\"objects\": [{\"mesh\": {\"type\": \"file\", \"path\": \"warnings.gltf\"}}, "
		 "{\"mesh\": {\"type\": \"file\", \"path\": \"warnings.gltf\"}}], " CAM "}");
	struct aa_error err = {0};
	assert_int_equal(aa_scene_load_string(json, "twice.json", assets, &sc, &err), 0);
	assert_int_equal(sc->warning_count, 4);
	aa_scene_free(sc);
}

/* An OBJ's .mtl: diffuse colour and map become the material (the scene's Blinn-Phong model). */
static void test_obj_material(void **state)
{
	(void)state;
	struct aa_scene *sc = load_ok("material.obj", "", "");
	const struct aa_material *m = material_of(sc, "/painted");
	assert_int_equal(m->model, AA_SHADING_BLINN_PHONG);
	assert_true(m->base_color[0] == 1.0f && m->base_color[2] == 0.5f && m->texture_index >= 0);
	assert_false(m->single_sided);
	aa_scene_free(sc);
}

static bool has_source(const struct aa_scene *sc, const char *name)
{
	for (int i = 0; i < sc->source_count; i++) {
		const char *slash = strrchr(sc->sources[i].path, '/');
		if (strcmp(slash ? slash + 1 : sc->sources[i].path, name) == 0)
			return true;
	}
	return false;
}

/* The files a load read, for the daemon's scene cache (scene_sources.c): the mesh, its .mtl and the map
 * the .mtl names, each once; unchanged right after the load, changed when one's time differs. */
static void test_sources(void **state)
{
	(void)state;
	struct aa_scene *sc = load_ok("material.obj", "", "");
	assert_true(has_source(sc, "material.obj"));
	assert_true(has_source(sc, "material.mtl"));
	assert_true(has_source(sc, "quadrants.png"));
	assert_int_equal(sc->source_count, 3);
	assert_false(sc->sources_unknown);
	assert_false(aa_scene_sources_changed(sc));
	sc->sources[2].mtime.tv_nsec ^= 1; /* as if that file had been written since */
	assert_true(aa_scene_sources_changed(sc));
	aa_scene_free(sc);
	/* outside a load nothing is collected */
	aa_scene_source_read("/etc/hostname");
	sc = load_ok("base-color.gltf", "", ""); /* its buffers and images are data: URIs */
	assert_int_equal(sc->source_count, 1);
	assert_true(has_source(sc, "base-color.gltf"));
	aa_scene_free(sc);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_refusals),
		cmocka_unit_test(test_missing_files_as_warnings),
		cmocka_unit_test(test_base_color_materials),
		cmocka_unit_test(test_scene_material_overrides),
		cmocka_unit_test(test_alpha_modes),
		cmocka_unit_test(test_emissive_and_maps),
		cmocka_unit_test(test_normal_map_tangents),
		cmocka_unit_test(test_texture_transform),
		cmocka_unit_test(test_skin_and_animation),
		cmocka_unit_test(test_rotation_takes_the_short_way),
		cmocka_unit_test(test_animation_errors),
		cmocka_unit_test(test_warnings),
		cmocka_unit_test(test_obj_material),
		cmocka_unit_test(test_sources),
	};
	return cmocka_run_group_tests(tests, setup, NULL);
}
