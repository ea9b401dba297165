/* Loading a scene file: parses the JSON and validates every field (with the JSON path in each error),
 * builds meshes and textures, and frees it all again (finding it by name: scene_files.c). Format:
 * docs/scene-format.md. */
#include <dirent.h>
#include <errno.h>
#include <libgen.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "scene/mesh_file.h"
#include "scene/mesh_procedural.h"
#include "scene/scene_json.h"
#include "scene/texture.h"
#include "util/file_io.h"

/* ---------------------------------------------------------------- freeing */

void aa_scene_free(struct aa_scene *scene)
{
	if (!scene)
		return;
	for (int i = 0; i < scene->mesh_count; i++)
		aa_mesh_free(&scene->meshes[i]);
	for (int i = 0; i < scene->texture_count; i++)
		aa_texture_free(&scene->textures[i]);
	for (int i = 0; i < scene->path_count; i++)
		free(scene->paths[i].keys);
	for (int i = 0; i < scene->rig_count; i++)
		aa_rig_free(&scene->rigs[i]);
	free(scene->meshes);
	free(scene->textures);
	free(scene->materials);
	free(scene->objects);
	free(scene->lights);
	free(scene->paths);
	free(scene->rigs);
	aa_scene_sources_free(scene);
	free(scene);
}

/* ---------------------------------------------------------------- parts of a scene */

struct loader {
	struct sj s;
	const char *base_dir;
	struct aa_scene *sc;
	const json_t *materials, *meshes, *textures, *objects; /* the name maps, for lookups and "(materials: ...)" */
	int *named_mesh;                             /* per entry of "meshes": its first mesh (file parts follow) */
	int default_material;                        /* -1 until an object needs it */
	int object_cap;
	size_t texture_bytes;
	uint64_t triangles;                          /* drawn so far */
};

/* Index of `name` in a name map (objects keep insertion order, as the arrays were built), or -1. */
static int map_index(const json_t *map, const char *name)
{
	int i = 0;
	const char *key;
	json_t *v;
	json_object_foreach((json_t *)map, key, v) {
		(void)v;
		if (strcmp(key, name) == 0)
			return i;
		i++;
	}
	return -1;
}

/* Checks a name map (textures, materials, meshes) and returns its size. */
static int map_size(struct loader *L, const json_t *map, const char *what, int max)
{
	char got[64];
	if (!map)
		return 0;
	if (!json_is_object(map))
		return sj_fail_key(&L->s, what, AA_ERR_INVALID, "expected an object of named %s, got %s", what,
				   sj_describe(map, got, sizeof got));
	if (json_object_size(map) > (size_t)max)
		return sj_fail_key(&L->s, what, AA_ERR_LIMIT, "%zu %s is over the limit of %d", json_object_size(map), what,
				   max);
	const char *key;
	json_t *v;
	json_object_foreach((json_t *)map, key, v) {
		(void)v;
		if (!key[0] || strlen(key) >= AA_NAME_MAX)
			return sj_fail_key(&L->s, what, AA_ERR_INVALID, "%s names must have 1 to %d characters", what,
					   AA_NAME_MAX - 1);
	}
	return (int)json_object_size(map);
}

static int load_textures(struct loader *L)
{
	struct aa_scene *sc = L->sc;
	int n = map_size(L, L->textures, "textures", AA_SCENE_MAX_TEXTURES);
	if (n <= 0)
		return n;
	if (!(sc->textures = calloc((size_t)n, sizeof *sc->textures)))
		return sj_fail(&L->s, AA_ERR_INTERNAL, "out of memory");
	const char *key;
	json_t *v;
	size_t mark = sj_push_key(&L->s, "textures");
	json_object_foreach((json_t *)L->textures, key, v) {
		struct aa_texture *t = &sc->textures[sc->texture_count];
		size_t m2 = sj_push_key(&L->s, key);
		if (aa_texture_from_json(&L->s, v, L->base_dir, AA_SCENE_MAX_TEXTURE_BYTES - L->texture_bytes, t))
			return -1;
		sc->texture_count++;
		snprintf(t->name, sizeof t->name, "%s", key);
		L->texture_bytes += aa_texture_bytes(t->width, t->height);
		sj_pop(&L->s, m2);
	}
	sj_pop(&L->s, mark);
	return 0;
}

void aa_material_defaults(struct aa_material *m)
{
	*m = (struct aa_material){.name = "default", .base_color = {0.6f, 0.6f, 0.6f, 1}, .scale = {8, 8},
				  .stripe_width = 0.5f, .texture_index = -1, .roughness = 0.5f, .alpha_cutoff = 0.5f,
				  .normal_scale = 1.0f, .occlusion_strength = 1.0f};
	for (int k = 0; k < AA_MAP_COUNT; k++) {
		m->maps[k] = -1;
		m->uv_transform[k][0] = m->uv_transform[k][4] = 1.0f; /* identity */
	}
}

static int read_material(struct loader *L, const json_t *o, struct aa_material *m)
{
	static const char *const keys[] = {"color", "pattern", "color2", "scale", "stripe_width", "texture",
					   "specular", "roughness", "alpha_cutout", "alpha_cutoff", "unlit", NULL};
	static const char *const patterns[] = {"none", "checker", "stripes", "texture", NULL};
	static const float grey[4] = {0.6f, 0.6f, 0.6f, 1}, white[4] = {1, 1, 1, 1}, dark[4] = {0.05f, 0.05f, 0.05f, 1};
	static const float eight[2] = {8, 8}, one[2] = {1, 1};
	struct sj *s = &L->s;
	const json_t *tex = json_object_get(o, "texture");
	float c2[4];
	int pattern;
	aa_material_defaults(m);
	if (sj_check_keys(s, o, keys) ||
	    sj_enum(s, o, "pattern", patterns, tex ? AA_PATTERN_TEXTURE : AA_PATTERN_NONE, &pattern) ||
	    sj_color(s, o, "color", tex ? white : grey, true, m->base_color) ||
	    sj_color(s, o, "color2", dark, false, c2) ||
	    sj_floats_or_scalar(s, o, "scale", 2, SJ_CLOSED(1e-3, 1e4), tex ? one : eight, m->scale) ||
	    sj_float(s, o, "stripe_width", SJ_OPEN(0, 1), 0.5f, &m->stripe_width) ||
	    sj_float(s, o, "specular", SJ_CLOSED(0, 100), 0.0f, &m->specular) ||
	    sj_float(s, o, "roughness", SJ_CLOSED(0.01, 1), 0.5f, &m->roughness) ||
	    sj_bool(s, o, "alpha_cutout", false, &m->alpha_cutout) ||
	    sj_float(s, o, "alpha_cutoff", SJ_OPEN(0, 1), 0.5f, &m->alpha_cutoff) || sj_bool(s, o, "unlit", false, &m->unlit))
		return -1;
	memcpy(m->color2, c2, sizeof m->color2);
	m->pattern = (enum aa_pattern)pattern;
	m->texture_index = -1;
	if (tex) {
		char name[AA_NAME_MAX], list[300];
		if (sj_string(s, o, "texture", "", name, sizeof name))
			return -1;
		if (pattern != AA_PATTERN_TEXTURE)
			return sj_fail_key(s, "texture", AA_ERR_INVALID, "a texture needs pattern 'texture' (this one is '%s')",
					   patterns[pattern]);
		if ((m->texture_index = map_index(L->textures, name)) < 0) {
			sj_list_keys(L->textures, list, sizeof list);
			return sj_fail_key(s, "texture", AA_ERR_INVALID, "unknown texture '%s' (textures: %s)", name, list);
		}
		m->maps[AA_MAP_BASE] = m->texture_index;
	} else if (pattern == AA_PATTERN_TEXTURE) {
		return sj_fail_key(s, "pattern", AA_ERR_INVALID, "pattern 'texture' needs a 'texture' name");
	}
	/* the base texture's transform is its scale, which shadow cut-outs read like file materials' */
	m->uv_transform[AA_MAP_BASE][0] = m->scale[0];
	m->uv_transform[AA_MAP_BASE][4] = m->scale[1];
	return 0;
}

static int load_materials(struct loader *L)
{
	struct aa_scene *sc = L->sc;
	int n = map_size(L, L->materials, "materials", AA_SCENE_MAX_MATERIALS - 1);
	if (n < 0)
		return -1;
	/* One spare slot for the implicit "default" material of objects that name none. */
	if (!(sc->materials = calloc((size_t)n + 1, sizeof *sc->materials)))
		return sj_fail(&L->s, AA_ERR_INTERNAL, "out of memory");
	const char *key;
	json_t *v;
	size_t mark = sj_push_key(&L->s, "materials");
	json_object_foreach((json_t *)L->materials, key, v) {
		struct aa_material *m = &sc->materials[sc->material_count];
		size_t m2 = sj_push_key(&L->s, key);
		if (read_material(L, v, m))
			return -1;
		snprintf(m->name, sizeof m->name, "%s", key);
		sc->material_count++;
		sj_pop(&L->s, m2);
	}
	sj_pop(&L->s, mark);
	return 0;
}

/* A mesh slot at the end of sc->meshes (procedural meshes take one, files one per part). */
static int mesh_slot(struct loader *L)
{
	struct aa_scene *sc = L->sc;
	if (sc->mesh_count >= AA_SCENE_MAX_ALL_MESHES)
		return sj_fail(&L->s, AA_ERR_LIMIT, "more than %d meshes (file meshes count one per material)",
			       AA_SCENE_MAX_ALL_MESHES);
	struct aa_mesh *grown = realloc(sc->meshes, (size_t)(sc->mesh_count + 1) * sizeof *grown);
	if (!grown)
		return sj_fail(&L->s, AA_ERR_INTERNAL, "out of memory");
	sc->meshes = grown;
	memset(&sc->meshes[sc->mesh_count], 0, sizeof *sc->meshes);
	return sc->mesh_count;
}

/* Whether any object draws the named mesh `name` with the file's own materials (no "material"). */
static bool named_mesh_keeps_materials(struct loader *L, const char *name)
{
	size_t i;
	const json_t *o;
	json_array_foreach(L->objects, i, o) {
		const json_t *mesh = json_object_get(o, "mesh");
		if (json_is_string(mesh) && strcmp(json_string_value(mesh), name) == 0 && !json_object_get(o, "material"))
			return true;
	}
	return false;
}

/* {"type": "file", "path": ..., "missing_files": "error" | "warn"}: the file's parts (and materials,
 * when an object keeps them) appended to the scene; *first is the first part. */
static int load_file_mesh(struct loader *L, const json_t *spec, bool keep_materials, uint64_t max_triangles,
			  int *first)
{
	static const char *const keys[] = {"type", "path", "missing_files", NULL};
	static const char *const missing_modes[] = {"error", "warn", NULL};
	struct sj *s = &L->s;
	char rel[512], full[4096];
	int missing;
	if (sj_check_keys(s, spec, keys) || sj_require(s, spec, "path") || sj_string(s, spec, "path", "", rel, sizeof rel) ||
	    sj_enum(s, spec, "missing_files", missing_modes, 0, &missing))
		return -1;
	struct aa_mesh_file_options options = {.materials = keep_materials, .missing_warn = missing == 1};
	size_t mark = sj_push_key(s, "path");
	if (sj_resolve_file(s, L->base_dir, rel, full, sizeof full))
		return -1;
	*first = aa_mesh_file_load(s, L->sc, full, rel, L->base_dir, &options, max_triangles);
	if (*first < 0)
		return -1;
	sj_pop(s, mark);
	return 0;
}

static bool is_file_spec(const json_t *spec)
{
	const json_t *type = json_object_get(spec, "type");
	return json_is_object(spec) && json_is_string(type) && strcmp(json_string_value(type), "file") == 0;
}

/* A procedural mesh spec into a new slot. */
static int load_procedural_mesh(struct loader *L, const json_t *spec, uint64_t max_triangles, int *index)
{
	int slot = mesh_slot(L);
	if (slot < 0 || aa_mesh_from_json(&L->s, spec, L->base_dir, max_triangles, &L->sc->meshes[slot]))
		return -1;
	*index = L->sc->mesh_count++;
	return 0;
}

static int load_named_meshes(struct loader *L)
{
	const char *key;
	json_t *v;
	int n = 0;
	if (!(L->named_mesh = calloc(json_object_size(L->meshes) + 1, sizeof *L->named_mesh)))
		return sj_fail(&L->s, AA_ERR_INTERNAL, "out of memory");
	size_t mark = sj_push_key(&L->s, "meshes");
	json_object_foreach((json_t *)L->meshes, key, v) {
		size_t m2 = sj_push_key(&L->s, key);
		int first;
		if (is_file_spec(v) ? load_file_mesh(L, v, named_mesh_keeps_materials(L, key), AA_SCENE_MAX_TRIANGLES, &first)
				    : load_procedural_mesh(L, v, AA_SCENE_MAX_TRIANGLES, &first))
			return -1;
		L->named_mesh[n++] = first;
		if (!is_file_spec(v))
			snprintf(L->sc->meshes[first].name, sizeof L->sc->meshes[first].name, "%s", key);
		sj_pop(&L->s, m2);
	}
	sj_pop(&L->s, mark);
	return 0;
}

/* "mesh": a name from "meshes", a bare type name ("sphere": defaults) or an inline spec object. *index is
 * its first mesh; file meshes have more parts after it (meshes[*index].part_count). */
static int object_mesh(struct loader *L, const json_t *o, int *index)
{
	struct sj *s = &L->s;
	const json_t *spec = json_object_get(o, "mesh");
	json_t *tmp = NULL;
	char list[300], got[64];
	if (json_is_string(spec)) {
		const char *name = json_string_value(spec);
		int named = map_index(L->meshes, name);
		if (named >= 0) {
			*index = L->named_mesh[named];
			return 0;
		}
		bool is_type = false;
		for (int i = 0; aa_mesh_type_names[i]; i++)
			is_type |= strcmp(name, aa_mesh_type_names[i]) == 0 && strcmp(name, "file") != 0;
		if (!is_type) {
			sj_list_keys(L->meshes, list, sizeof list);
			return sj_fail_key(s, "mesh", AA_ERR_INVALID,
					   "unknown mesh '%.60s' (meshes: %s; or a type: plane, box, sphere, cylinder, wires, "
					   "fence, blinds, stairs, wheel, hairball)", name, list);
		}
		spec = tmp = json_pack("{ss}", "type", name);
	} else if (!json_is_object(spec)) {
		return sj_fail_key(s, "mesh", AA_ERR_INVALID, "expected a mesh name or a mesh object, got %s",
				   sj_describe(spec, got, sizeof got));
	}
	if (L->sc->mesh_count >= AA_SCENE_MAX_MESHES + (int)json_object_size(L->meshes) && !is_file_spec(spec)) {
		json_decref(tmp);
		return sj_fail_key(s, "mesh", AA_ERR_LIMIT, "more than %d meshes: share meshes through \"meshes\"",
				   AA_SCENE_MAX_MESHES);
	}
	size_t mark = sj_push_key(s, "mesh");
	uint64_t left = AA_SCENE_MAX_TRIANGLES - L->triangles;
	int rc = is_file_spec(spec) ? load_file_mesh(L, spec, !json_object_get(o, "material"), left, index)
				    : load_procedural_mesh(L, spec, left, index);
	json_decref(tmp);
	if (rc)
		return -1;
	sj_pop(s, mark);
	return 0;
}

/* The scene's material named "default", or a plain grey one made for objects that name none. */
static int default_material(struct loader *L)
{
	struct aa_scene *sc = L->sc;
	int named = map_index(L->materials, "default");
	if (named >= 0)
		return named;
	if (L->default_material < 0) {
		struct aa_material *grown = realloc(sc->materials, (size_t)(sc->material_count + 1) * sizeof *grown);
		if (!grown)
			return sj_fail(&L->s, AA_ERR_INTERNAL, "out of memory");
		sc->materials = grown;
		aa_material_defaults(&sc->materials[sc->material_count]);
		L->default_material = sc->material_count++;
	}
	return L->default_material;
}

/* The scene material an object names for all its parts, or -1 when it names none. */
static int object_material(struct loader *L, const json_t *o, int *index)
{
	char name[AA_NAME_MAX], list[300];
	*index = -1;
	if (!json_object_get(o, "material"))
		return 0;
	if (sj_string(&L->s, o, "material", "", name, sizeof name))
		return -1;
	if ((*index = map_index(L->materials, name)) < 0) {
		sj_list_keys(L->materials, list, sizeof list);
		return sj_fail_key(&L->s, "material", AA_ERR_INVALID, "unknown material '%s' (materials: %s)", name, list);
	}
	return 0;
}

static void set3(float out[3], vec3 v)
{
	out[0] = v.x, out[1] = v.y, out[2] = v.z;
}

/* "clip", "time", "speed": a mesh file's animation (its rig) at time + speed * t. */
static int object_clip(struct loader *L, const json_t *a, int mesh, struct aa_pose *pose)
{
	struct sj *s = &L->s;
	struct aa_scene *sc = L->sc;
	char name[AA_NAME_MAX], list[400] = "";
	double time, speed;
	pose->clip = -1;
	if (sj_number(s, a, "time", SJ_CLOSED(-1e6, 1e6), 0.0, &time) ||
	    sj_number(s, a, "speed", SJ_CLOSED(-1e3, 1e3), 1.0, &speed))
		return -1;
	pose->clip_time = time;
	pose->clip_speed = speed;
	if (!json_object_get(a, "clip")) {
		if (json_object_get(a, "time") || json_object_get(a, "speed"))
			return sj_fail_key(s, json_object_get(a, "time") ? "time" : "speed", AA_ERR_INVALID,
					   "needs 'clip', the name of an animation of the mesh file");
		return 0;
	}
	if (sj_string(s, a, "clip", "", name, sizeof name))
		return -1;
	int rig = -1;
	for (int k = 0; k < sc->meshes[mesh].part_count && rig < 0; k++)
		rig = sc->meshes[mesh + k].rig;
	if (rig < 0 || sc->rigs[rig].clip_count == 0)
		return sj_fail_key(s, "clip", AA_ERR_INVALID, "this object's mesh has no animations (only mesh files with "
				   "skins or animated nodes have)");
	const struct aa_rig *r = &sc->rigs[rig];
	for (int c = 0; c < r->clip_count; c++) {
		if (strcmp(r->clips[c].name, name) == 0) {
			pose->clip = c;
			return 0;
		}
		snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", c ? ", " : "", r->clips[c].name);
	}
	return sj_fail_key(s, "clip", AA_ERR_INVALID, "unknown animation '%s' (the mesh file has: %s)", name, list);
}

static int object_animation(struct loader *L, const json_t *a, const double position[3], int mesh, struct aa_animation *an,
			    struct aa_pose *pose)
{
	static const char *const keys[] = {"velocity", "oscillate", "spin", "clip", "time", "speed", NULL};
	static const char *const osc_keys[] = {"axis", "amplitude", "frequency", NULL};
	static const char *const spin_keys[] = {"axis", "degrees_per_second", "pivot", NULL};
	struct sj *s = &L->s;
	vec3 zero = v3(0, 0, 0), axis, velocity;
	double pivot[3] = {position[0], position[1], position[2]};
	if (sj_check_keys(s, a, keys) || sj_vec3(s, a, "velocity", SJ_CLOSED(-1e4, 1e4), zero, &velocity) ||
	    object_clip(L, a, mesh, pose))
		return -1;
	set3(an->velocity, velocity);
	const json_t *osc = json_object_get(a, "oscillate"), *spin = json_object_get(a, "spin");
	set3(an->spin_axis, v3(0, 1, 0));
	if (osc) {
		size_t mark = sj_push_key(s, "oscillate");
		if (sj_check_keys(s, osc, osc_keys) || sj_require(s, osc, "axis") ||
		    sj_vec3(s, osc, "axis", SJ_CLOSED(-1e3, 1e3), zero, &axis) ||
		    sj_float(s, osc, "amplitude", SJ_CLOSED(0, 1e4), 1.0f, &an->oscillate_amplitude) ||
		    sj_float(s, osc, "frequency", SJ_CLOSED(0, 1e3), 0.5f, &an->oscillate_frequency))
			return -1;
		if (v3_length(axis) < 1e-6f)
			return sj_fail_key(s, "axis", AA_ERR_INVALID, "axis must not be zero");
		set3(an->oscillate_axis, v3_normalize(axis));
		sj_pop(s, mark);
	}
	if (spin) {
		size_t mark = sj_push_key(s, "spin");
		if (sj_check_keys(s, spin, spin_keys) || sj_vec3(s, spin, "axis", SJ_CLOSED(-1e3, 1e3), v3(0, 1, 0), &axis) ||
		    sj_require(s, spin, "degrees_per_second") ||
		    sj_float(s, spin, "degrees_per_second", SJ_CLOSED(-1e6, 1e6), 0, &an->spin_degrees_per_second) ||
		    sj_dvec3(s, spin, "pivot", SJ_ANY, position, pivot))
			return -1;
		if (v3_length(axis) < 1e-6f)
			return sj_fail_key(s, "axis", AA_ERR_INVALID, "axis must not be zero");
		set3(an->spin_axis, v3_normalize(axis));
		sj_pop(s, mark);
	}
	/* The spin pivot defaults to the object's position, so objects spin in place; it is kept relative to
	 * that position (the object's origin), which is small in floats wherever the object is. */
	set3(an->pivot, v3((float)(pivot[0] - position[0]), (float)(pivot[1] - position[1]), (float)(pivot[2] - position[2])));
	an->active = v3_length(velocity) > 0 || (an->oscillate_amplitude > 0 && an->oscillate_frequency > 0) ||
		     an->spin_degrees_per_second != 0;
	return 0;
}

/* One draw per part of the object's mesh (one for procedural meshes). */
static int add_draws(struct loader *L, const struct aa_object *proto, int first_mesh, int override)
{
	struct aa_scene *sc = L->sc;
	int parts = sc->meshes[first_mesh].part_count > 0 ? sc->meshes[first_mesh].part_count : 1;
	if (sc->object_count + parts > AA_SCENE_MAX_DRAWS)
		return sj_fail(&L->s, AA_ERR_LIMIT, "the scene draws more than %d objects and mesh parts",
			       AA_SCENE_MAX_DRAWS);
	if (sc->object_count + parts > L->object_cap) {
		int cap = 2 * (sc->object_count + parts);
		struct aa_object *grown = realloc(sc->objects, (size_t)cap * sizeof *grown);
		if (!grown)
			return sj_fail(&L->s, AA_ERR_INTERNAL, "out of memory");
		sc->objects = grown;
		L->object_cap = cap;
	}
	for (int k = 0; k < parts; k++) {
		const struct aa_mesh *m = &sc->meshes[first_mesh + k];
		struct aa_object *o = &sc->objects[sc->object_count];
		*o = *proto;
		o->mesh_index = first_mesh + k;
		o->material_index = override >= 0 ? override : m->file_material >= 0 ? m->file_material : default_material(L);
		if (o->material_index < 0)
			return -1;
		sc->object_count++;
		L->triangles += m->index_count / 3;
	}
	if (L->triangles > AA_SCENE_MAX_TRIANGLES)
		return sj_fail(&L->s, AA_ERR_LIMIT, "the scene draws more than %u triangles, the limit",
			       (unsigned)AA_SCENE_MAX_TRIANGLES);
	return 0;
}

static int read_object(struct loader *L, const json_t *o, int index)
{
	static const char *const keys[] = {"name", "mesh", "material", "position", "rotation", "scale", "animation", NULL};
	static const float one[3] = {1, 1, 1};
	struct sj *s = &L->s;
	struct aa_object obj = {.pose = {.clip = -1}};
	char def_name[32];
	vec3 rot;
	double pos[3];
	float scale[3];
	int mesh, override;
	snprintf(def_name, sizeof def_name, "object%d", index);
	if (sj_check_keys(s, o, keys) || sj_string(s, o, "name", def_name, obj.name, sizeof obj.name) ||
	    sj_require(s, o, "mesh") || object_material(L, o, &override) || object_mesh(L, o, &mesh) ||
	    sj_dvec3(s, o, "position", SJ_ANY, (const double[3]){0, 0, 0}, pos) ||
	    sj_vec3(s, o, "rotation", SJ_CLOSED(-3600, 3600), v3(0, 0, 0), &rot) ||
	    sj_floats_or_scalar(s, o, "scale", 3, SJ_CLOSED(1e-4, 1e5), one, scale))
		return -1;
	/* Rotation in degrees about x, then y, then z (R = Rz Ry Rx), applied after scale. */
	const float d2r = 3.14159265358979f / 180.0f;
	mat4 r = mat4_mul(mat4_rotate(v3(0, 0, 1), rot.z * d2r),
			  mat4_mul(mat4_rotate(v3(0, 1, 0), rot.y * d2r), mat4_rotate(v3(1, 0, 0), rot.x * d2r)));
	/* The position stays in double (obj.origin); the float matrix holds what is relative to it. */
	obj.origin[0] = pos[0], obj.origin[1] = pos[1], obj.origin[2] = pos[2];
	obj.transform = mat4_mul(r, mat4_scale(v3(scale[0], scale[1], scale[2])));
	obj.model_id = (uint32_t)index + 1;
	const json_t *anim = json_object_get(o, "animation");
	if (anim) {
		size_t mark = sj_push_key(s, "animation");
		if (object_animation(L, anim, pos, mesh, &obj.animation, &obj.pose))
			return -1;
		sj_pop(s, mark);
	}
	return add_draws(L, &obj, mesh, override);
}

static int load_objects(struct loader *L, const json_t *objects)
{
	struct aa_scene *sc = L->sc;
	struct sj *s = &L->s;
	char got[64];
	if (!objects)
		return sj_fail_key(s, "objects", AA_ERR_INVALID, "missing required key 'objects' (a scene needs objects)");
	if (!json_is_array(objects))
		return sj_fail_key(s, "objects", AA_ERR_INVALID, "expected an array of objects, got %s",
				   sj_describe(objects, got, sizeof got));
	size_t n = json_array_size(objects);
	if (n == 0)
		return sj_fail_key(s, "objects", AA_ERR_INVALID, "a scene needs at least one object");
	if (n > AA_SCENE_MAX_OBJECTS)
		return sj_fail_key(s, "objects", AA_ERR_LIMIT, "%zu objects is over the limit of %d", n,
				   AA_SCENE_MAX_OBJECTS);
	L->objects = objects;
	if (map_size(L, L->meshes, "meshes", AA_SCENE_MAX_MESHES) < 0)
		return -1;
	L->object_cap = (int)n;
	if (!(sc->objects = calloc(n, sizeof *sc->objects)))
		return sj_fail(s, AA_ERR_INTERNAL, "out of memory");
	if (load_named_meshes(L))
		return -1;
	size_t mark = sj_push_key(s, "objects");
	for (size_t i = 0; i < n; i++) {
		size_t m2 = sj_push_index(s, i);
		if (read_object(L, json_array_get(objects, i), (int)i))
			return -1;
		sj_pop(s, m2);
	}
	sj_pop(s, mark);
	sc->model_count = (int)n;
	return 0;
}

static int read_light(struct sj *s, const json_t *o, struct aa_light *l, int *shadow_casters)
{
	static const char *const types[] = {"directional", "point", NULL};
	static const char *const dir_keys[] = {"type", "direction", "color", "intensity", "casts_shadow", NULL};
	static const char *const point_keys[] = {"type", "position", "color", "intensity", "range", "casts_shadow", NULL};
	static const float white[4] = {1, 1, 1, 1};
	float color[4];
	int type;
	if (sj_expect_object(s, o) || sj_require(s, o, "type") || sj_enum(s, o, "type", types, 0, &type) ||
	    sj_check_keys(s, o, type == AA_LIGHT_DIRECTIONAL ? dir_keys : point_keys) ||
	    sj_color(s, o, "color", white, false, color) ||
	    sj_float(s, o, "intensity", SJ_CLOSED(0, 1e4), 1.0f, &l->intensity) ||
	    sj_float(s, o, "range", SJ_NONNEG, 0.0f, &l->range) || sj_bool(s, o, "casts_shadow", false, &l->casts_shadow))
		return -1;
	l->type = (enum aa_light_type)type;
	memcpy(l->color, color, sizeof l->color);
	vec3 v;
	if (l->type == AA_LIGHT_DIRECTIONAL) {
		if (sj_require(s, o, "direction") || sj_vec3(s, o, "direction", SJ_CLOSED(-1e3, 1e3), v3(0, -1, 0), &v))
			return -1;
		if (v3_length(v) < 1e-6f)
			return sj_fail_key(s, "direction", AA_ERR_INVALID, "direction must not be zero");
		v = v3_normalize(v);
		l->direction[0] = v.x, l->direction[1] = v.y, l->direction[2] = v.z;
	} else {
		if (sj_require(s, o, "position") || sj_dvec3(s, o, "position", SJ_ANY, (const double[3]){0, 0, 0}, l->position))
			return -1;
		/* Shadow maps are rendered for directional lights only. */
		if (l->casts_shadow)
			return sj_fail_key(s, "casts_shadow", AA_ERR_INVALID, "only directional lights can cast shadows");
	}
	if (l->casts_shadow && ++*shadow_casters > 1)
		return sj_fail_key(s, "casts_shadow", AA_ERR_INVALID, "only one light may cast shadows");
	return 0;
}

static int load_lights(struct loader *L, const json_t *lights)
{
	struct sj *s = &L->s;
	int casters = 0;
	if (!lights)
		return 0;
	size_t mark = sj_push_key(s, "lights");
	if (!json_is_array(lights) || json_array_size(lights) > AA_SCENE_MAX_LIGHTS)
		return sj_fail(s, AA_ERR_INVALID, "expected an array of at most %d lights", AA_SCENE_MAX_LIGHTS);
	size_t n = json_array_size(lights);
	if (n && !(L->sc->lights = calloc(n, sizeof *L->sc->lights)))
		return sj_fail(s, AA_ERR_INTERNAL, "out of memory");
	for (size_t i = 0; i < n; i++) {
		size_t m2 = sj_push_index(s, i);
		if (read_light(s, json_array_get(lights, i), &L->sc->lights[i], &casters))
			return -1;
		L->sc->light_count++;
		sj_pop(s, m2);
	}
	sj_pop(s, mark);
	return 0;
}

/* ---------------------------------------------------------------- whole scene */

static int load_root(struct loader *L, const json_t *root, const char *default_name)
{
	static const char *const keys[] = {"name", "description", "fps", "background", "ambient", "textures",
					   "materials", "meshes", "objects", "lights", "camera", "paths", NULL};
	static const float bg[4] = {0.02f, 0.02f, 0.025f, 1}, amb[4] = {0.05f, 0.05f, 0.05f, 1};
	struct aa_scene *sc = L->sc;
	struct sj *s = &L->s;
	float c[4];
	if (sj_check_keys(s, root, keys) || sj_string(s, root, "name", default_name, sc->name, sizeof sc->name) ||
	    sj_string(s, root, "description", "", sc->description, sizeof sc->description) ||
	    sj_number(s, root, "fps", SJ_CLOSED(1, 1000), 30.0, &sc->fps) || sj_color(s, root, "background", bg, false, c))
		return -1;
	memcpy(sc->background, c, sizeof sc->background);
	if (sj_color(s, root, "ambient", amb, false, c))
		return -1;
	memcpy(sc->ambient, c, sizeof sc->ambient);
	L->textures = json_object_get(root, "textures");
	L->materials = json_object_get(root, "materials");
	L->meshes = json_object_get(root, "meshes");
	if (load_textures(L) || load_materials(L) || load_objects(L, json_object_get(root, "objects")) ||
	    load_lights(L, json_object_get(root, "lights")))
		return -1;
	struct aa_error e = {0};
	if (aa_scene_fit_texture_alpha(sc, &e))
		return sj_fail_key(s, "textures", e.code, "%s", e.message);
	struct aa_camera cam;
	const json_t *camera = json_object_get(root, "camera");
	if (!camera)
		return sj_fail_key(s, "camera", AA_ERR_INVALID, "missing required key 'camera' (position and target)");
	size_t mark = sj_push_key(s, "camera");
	if (aa_camera_from_json(s, camera, NULL, true, &cam))
		return -1;
	sj_pop(s, mark);
	return aa_paths_from_json(s, json_object_get(root, "paths"), &cam, sc);
}

static int load_json(json_t *root, const char *display, const char *base_dir, const char *file,
		     struct aa_scene **out, struct aa_error *err)
{
	struct loader L = {.base_dir = base_dir, .default_material = -1};
	char stem[AA_NAME_MAX] = "scene";
	sj_init(&L.s, display, err);
	*out = NULL;
	if (display && display[0]) {
		const char *b = strrchr(display, '/');
		snprintf(stem, sizeof stem, "%s", b ? b + 1 : display);
		if (sj_ends_with(stem, ".json"))
			stem[strlen(stem) - 5] = '\0';
	}
	if (!(L.sc = calloc(1, sizeof *L.sc))) {
		json_decref(root);
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	}
	snprintf(L.sc->file, sizeof L.sc->file, "%s", file ? file : "");
	aa_scene_sources_collect(L.sc);
	int rc = load_root(&L, root, stem);
	aa_scene_sources_collect(NULL);
	json_decref(root);
	free(L.named_mesh);
	if (rc) {
		aa_scene_free(L.sc);
		return -1;
	}
	L.sc->uid = aa_scene_new_uid();
	*out = L.sc;
	return 0;
}

int aa_scene_load_string(const char *json_text, const char *display_name, const char *base_dir,
			 struct aa_scene **out, struct aa_error *err)
{
	const char *display = display_name && display_name[0] ? display_name : "<string>";
	json_error_t je;
	*out = NULL;
	if (strlen(json_text) > AA_SCENE_MAX_FILE_BYTES)
		return aa_error_set(err, AA_ERR_LIMIT, "", "%s: scene text is over the limit of %u bytes", display,
				    (unsigned)AA_SCENE_MAX_FILE_BYTES);
	json_t *root = json_loads(json_text, JSON_REJECT_DUPLICATES, &je);
	if (!root)
		return sj_parse_error(err, display, &je);
	if (load_json(root, display, base_dir, NULL, out, err))
		return -1;
	aa_scene_sources_digest(*out, json_text, strlen(json_text));
	return 0;
}

int aa_scene_load(const char *path, struct aa_scene **out, struct aa_error *err)
{
	return aa_scene_load_as(path, path, out, err);
}

int aa_scene_load_as(const char *path, const char *shown, struct aa_scene **out, struct aa_error *err)
{
	struct stat st;
	json_error_t je;
	*out = NULL;
	if (stat(path, &st) != 0)
		return aa_error_set(err, errno == ENOENT ? AA_ERR_NOT_FOUND : AA_ERR_IO, "",
				    "scene file '%s' %s", shown, errno == ENOENT ? "not found" : strerror(errno));
	if (!S_ISREG(st.st_mode))
		return aa_error_set(err, AA_ERR_IO, "", "scene file '%s' is not a regular file", shown);
	if ((uint64_t)st.st_size > AA_SCENE_MAX_FILE_BYTES)
		return aa_error_set(err, AA_ERR_LIMIT, "", "%s: scene file is %lld bytes, over the limit of %u", shown,
				    (long long)st.st_size, (unsigned)AA_SCENE_MAX_FILE_BYTES);
	/* parsed from the bytes that are hashed: the content digest is of what was loaded */
	uint8_t *text;
	size_t size;
	struct aa_error rerr = {0};
	if (aa_file_read(path, AA_SCENE_MAX_FILE_BYTES, &text, &size, &rerr))
		return aa_error_set(err, rerr.code, "", "scene file '%s' %s", shown, rerr.code == AA_ERR_INVALID ?
				    "is not a regular file" : "cannot be read");
	json_t *root = json_loadb((const char *)text, size, JSON_REJECT_DUPLICATES, &je);
	char dir[PATH_MAX];
	snprintf(dir, sizeof dir, "%s", path);
	int rc = root ? load_json(root, shown, dirname(dir), path, out, err) : sj_parse_error(err, shown, &je);
	if (rc == 0)
		aa_scene_sources_digest(*out, text, size);
	free(text);
	return rc;
}
