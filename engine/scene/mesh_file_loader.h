/* What mesh_file.c and mesh_file_materials.c share while one mesh file loads: the loader's state. Private
 * to those two files. */
#ifndef AA_MESH_FILE_LOADER_H
#define AA_MESH_FILE_LOADER_H

#include <assimp/scene.h>

#include "scene/mesh_file.h"

struct node_info {
	const struct aiNode *node;
	int parent;
	mat4 world;     /* rest pose */
	bool moves;     /* an animation channel targets it or an ancestor */
};

struct part {
	unsigned material;  /* assimp material index */
	uint32_t vertex_count, index_count;
	bool rigged;        /* some vertices are skinned or animated */
	bool colors;        /* some source mesh has COLOR_0 */
	int mesh;           /* its index in scene->meshes (which grows: no pointers into it) */
};

struct loader {
	struct sj *s;
	struct aa_scene *scene;
	const char *path, *shown, *base_dir;
	const struct aa_mesh_file_options *options;
	const struct aiScene *ai;
	bool gltf;
	struct aa_gltf_info gltf_info;
	struct node_info *nodes;
	int node_count;
	struct part *parts;
	int part_count;
	/* the rig being built: joints as (node, inverse bind) pairs, deduplicated */
	int joint_count, joint_cap;
	int *joint_node;
	mat4 *joint_ibm;
	size_t texture_bytes; /* the scene's textures so far */
};

#define FAIL(L, code, ...) aa_mesh_file_fail((L), (code), __VA_ARGS__)
/* Sets the error as "mesh file 'NAME': ..." at the object's path; returns -1. */
int aa_mesh_file_fail(struct loader *L, enum aa_error_code code, const char *fmt, ...)
	__attribute__((format(printf, 3, 4)));

/* ---- mesh_file_materials.c */
/* The file's material `index` as a scene material (with its textures), appended to the scene. */
int aa_mesh_file_add_material(struct loader *L, unsigned index, int *out);
/* Whether a file material is the importer's stand-in for "no material". */
bool aa_mesh_file_is_default_material(struct loader *L, unsigned index);

#endif
