/* aalab's own strict reading of the OBJ (+ .mtl), OFF, PLY and STL files a scene names, before assimp
 * sees them (mesh_text_check.c). assimp 5.2's readers trust what these files say: counts in headers, indices,
 * numbers, and crash or loop when that is wrong (tests/fuzz). A file passes only in a form assimp reads the
 * same way aalab does; anything else is refused, naming the line (or element and byte) and what is wrong. */
#ifndef AA_MESH_TEXT_CHECK_H
#define AA_MESH_TEXT_CHECK_H

#include <stdbool.h>
#include <stddef.h>

struct sj;
struct aa_scene;

enum aa_mesh_format {
	AA_MESH_FORMAT_OTHER, /* not one aalab checks (glTF goes through gltf_check.c) */
	AA_MESH_FORMAT_OBJ,
	AA_MESH_FORMAT_MTL,
	AA_MESH_FORMAT_OFF,
	AA_MESH_FORMAT_PLY,
	AA_MESH_FORMAT_STL,
};

/* The format by the file name's extension, as assimp 5.2 picks its reader (case-insensitive). */
enum aa_mesh_format aa_mesh_format_of(const char *path);

/* Called for each library an OBJ file's mtllib line names (line: 1-based); returns 0 to go on, anything
 * else stops the check with that value. */
typedef int (*aa_mesh_library_fn)(void *ctx, const char *name, int line);

/* Checks `size` bytes of a file in `format`. 0 when it is good; -1 with `why` set ("line 7: ..."), or
 * what `library` returned. */
int aa_mesh_text_check(enum aa_mesh_format format, const char *data, size_t size, aa_mesh_library_fn library,
		       void *ctx, char *why, size_t why_size);

/* The file at `path` (OBJ, OFF, PLY or STL by its extension), and for OBJ every material library it names
 * (beside it, inside base_dir; a missing one is a warning when missing_warn). Errors at the current path
 * of s as "mesh file 'shown': ...". Returns 0 or -1. */
int aa_mesh_text_check_file(struct sj *s, struct aa_scene *scene, const char *path, const char *shown,
			    const char *base_dir, bool missing_warn);

#endif
