/* Mesh files inside the scene loader: assimp's import (mesh_file.c), the checks and extension data read
 * from a glTF file's own JSON beside it (gltf_check.c), and rigs (scene_rig.c). */
#ifndef AA_MESH_FILE_H
#define AA_MESH_FILE_H

#include "scene/scene_json.h"

/* What an object asks of a file mesh when it is loaded. */
struct aa_mesh_file_options {
	bool materials;      /* load the file's materials and their textures (no object overrides them) */
	bool missing_warn;   /* a missing texture or .mtl file is a warning (the material goes without it),
			      * not an error */
};

/* Loads a mesh file into the scene being built: its parts (one mesh per material, appended to
 * scene->meshes; the first has part_count), the materials and textures they use (when options->materials)
 * and its rig, when a part is skinned or animated. Errors are set at the current path of s; `shown` is
 * the file name as the scene wrote it, base_dir the scene's directory (files the mesh file names must
 * stay inside it). Returns the index of the first part, or -1. */
int aa_mesh_file_load(struct sj *s, struct aa_scene *scene, const char *path, const char *shown,
		      const char *base_dir, const struct aa_mesh_file_options *options, uint64_t max_triangles);

/* ---- gltf_check.c ---- */

/* A texture reference of a glTF material: its texCoord and KHR_texture_transform (identity without). */
struct aa_gltf_map {
	bool present, transformed;
	int tex_coord;
	float offset[2], rotation, scale[2];
};

struct aa_gltf_material {
	float emissive_strength;          /* KHR_materials_emissive_strength, 1 without */
	struct aa_gltf_map maps[AA_MAP_COUNT];
};

struct aa_gltf_info {
	int material_count;
	struct aa_gltf_material *materials; /* by glTF material index (assimp keeps that order) */
};

/* Reads a .gltf or .glb file's container and JSON and refuses what aalab cannot draw as its author made
 * it, naming the file and the field: a truncated or malformed .glb, text that is not JSON, glTF 1.0,
 * required extensions aalab does not support, morph targets, accessors outside their buffers, indices
 * past the vertices. Adds warnings for what it drops or approximates (extensions used but not required,
 * texCoord other than 0, wrap modes, STEP and CUBICSPLINE keys). Fills info (free with
 * aa_gltf_info_free). */
int aa_gltf_check(struct sj *s, struct aa_scene *scene, const char *path, const char *shown, const char *base_dir,
		  struct aa_gltf_info *info);
void aa_gltf_info_free(struct aa_gltf_info *info);
/* True when the file is glTF by its name (.gltf, .glb) or its first bytes ("glTF" magic). */
bool aa_gltf_file_is_gltf(const char *path);

/* A file a mesh file names (a buffer, image or .mtl), relative to the mesh file: percent-escapes decoded,
 * absolute paths and '..' refused, and after resolving links it must lie inside base_dir. Writes the real
 * path; 0, or -1 with err set (AA_ERR_NOT_FOUND when it does not exist). */
int aa_resolve_beside(const char *model_path, const char *base_dir, const char *uri, char *out, size_t size,
		      struct aa_error *err);

/* ---- scene_rig.c ---- */
void aa_rig_free(struct aa_rig *rig);

#endif
