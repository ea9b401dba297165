/* Meshes a scene file can ask for: procedural shapes (plane, box, sphere, cylinder, wires, fence, blinds,
 * stairs, wheel, hairball; parameters and defaults in docs/scene-format.md) and mesh files (glTF 2.0, OBJ).
 * All are right-handed, y up, with outward unit normals and counter-clockwise front faces. */
#ifndef AA_MESH_PROCEDURAL_H
#define AA_MESH_PROCEDURAL_H

#include "scene_json.h"

/* Mesh types for {"type": ...}, NULL-terminated ("file" included). */
extern const char *const aa_mesh_type_names[];

void aa_mesh_free(struct aa_mesh *mesh);

/* mesh_file.c: imports a glTF/OBJ file through assimp, all meshes merged into one with node transforms
 * applied. Errors are set at the current path of s; `shown` is the file name as the scene wrote it. */
int aa_mesh_load_file(struct sj *s, const char *path, const char *shown, uint64_t max_triangles,
		      struct aa_mesh *out);

#endif
