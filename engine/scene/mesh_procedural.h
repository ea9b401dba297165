/* Meshes a scene file can ask for: procedural shapes (plane, box, sphere, cylinder, wires, fence, blinds,
 * stairs, wheel, hairball; parameters and defaults in docs/scene-format.md) and mesh files (glTF 2.0, OBJ).
 * All are right-handed, y up, with outward unit normals and counter-clockwise front faces. */
#ifndef AA_MESH_PROCEDURAL_H
#define AA_MESH_PROCEDURAL_H

#include "scene/scene_json.h"

/* Mesh types for {"type": ...}, NULL-terminated ("file" included). */
extern const char *const aa_mesh_type_names[];

void aa_mesh_free(struct aa_mesh *mesh);

/* bounds_min/bounds_max from the vertices. */
void aa_mesh_compute_bounds(struct aa_mesh *mesh);

#endif
