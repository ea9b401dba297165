/* Validation helpers over jansson for scene files: every reader knows the JSON path it is at, so errors
 * read "scenes/foo.json: objects[2].mesh.radius: expected a positive number, got -1". Also declares the
 * loader's internal parts that live in other files (textures, meshes, camera paths). */
#ifndef AA_SCENE_JSON_H
#define AA_SCENE_JSON_H

#include <jansson.h>
#include <stdbool.h>
#include <stddef.h>
#include <string.h>

#include "scene/scene.h"

/* Validation context: the file name for messages and the JSON path of the value being read. */
struct sj {
	struct aa_error *err;
	char file[256];
	char path[256];
	size_t len;
};

/* A numeric range; open ends exclude the bound. Every number is also limited to |x| <= SJ_MAX_ABS. */
struct sj_range {
	double min, max;
	bool min_open, max_open;
};
/* Whether s ends with suffix (a scene file's ".json"). */
static inline bool sj_ends_with(const char *s, const char *suffix)
{
	size_t a = strlen(s), b = strlen(suffix);
	return a >= b && strcmp(s + a - b, suffix) == 0;
}

#define SJ_MAX_ABS 1e7
#define SJ_ANY ((struct sj_range){-SJ_MAX_ABS, SJ_MAX_ABS, false, false})
#define SJ_POSITIVE ((struct sj_range){0.0, SJ_MAX_ABS, true, false})
#define SJ_NONNEG ((struct sj_range){0.0, SJ_MAX_ABS, false, false})
#define SJ_CLOSED(a, b) ((struct sj_range){(a), (b), false, false})
#define SJ_OPEN(a, b) ((struct sj_range){(a), (b), true, true})

void sj_init(struct sj *s, const char *file, struct aa_error *err);
/* Extend the path by ".key" or "[i]"; both return a mark for sj_pop. */
size_t sj_push_key(struct sj *s, const char *key);
size_t sj_push_index(struct sj *s, size_t index);
void sj_pop(struct sj *s, size_t mark);
/* Sets the error at the current path ("file: path: message") and returns -1. */
int sj_fail(struct sj *s, enum aa_error_code code, const char *fmt, ...)
	__attribute__((format(printf, 3, 4)));
/* Same at path.key. */
int sj_fail_key(struct sj *s, const char *key, enum aa_error_code code, const char *fmt, ...)
	__attribute__((format(printf, 4, 5)));
/* A short description of a value for "got ..." in messages: -1, "abc", an object, null. */
const char *sj_describe(const json_t *v, char *buf, size_t size);
/* "a, b, c": the keys of an object (or "none"), for "(materials: floor, wire)". */
void sj_list_keys(const json_t *obj, char *buf, size_t size);

/* The value at the current path must be an object whose keys are all in `valid` (NULL-terminated).
 * "comment" is always allowed so files can carry notes. */
int sj_expect_object(struct sj *s, const json_t *v);
int sj_check_keys(struct sj *s, const json_t *obj, const char *const *valid);
int sj_require(struct sj *s, const json_t *obj, const char *key);

/* Field readers: when obj has no `key` the default is stored; a present value of the wrong type or out
 * of range is an error at path.key. */
int sj_number(struct sj *s, const json_t *obj, const char *key, struct sj_range r, double def, double *out);
int sj_float(struct sj *s, const json_t *obj, const char *key, struct sj_range r, float def, float *out);
int sj_int(struct sj *s, const json_t *obj, const char *key, int min, int max, int def, int *out);
int sj_bool(struct sj *s, const json_t *obj, const char *key, bool def, bool *out);
int sj_string(struct sj *s, const json_t *obj, const char *key, const char *def, char *out, size_t size);
/* Enum: the string must be one of names[] (NULL-terminated); *out is its index. */
int sj_enum(struct sj *s, const json_t *obj, const char *key, const char *const *names, int def, int *out);
int sj_vec3(struct sj *s, const json_t *obj, const char *key, struct sj_range r, vec3 def, vec3 *out);
/* The value at the current path (an array element, say) as [x, y, z]. */
int sj_dvec3(struct sj *s, const json_t *obj, const char *key, struct sj_range r, const double def[3], double out[3]);
int sj_vec3_value(struct sj *s, const json_t *v, struct sj_range r, vec3 *out);
/* A number (used for all components) or an array of n numbers. */
int sj_floats_or_scalar(struct sj *s, const json_t *obj, const char *key, int n, struct sj_range r,
			const float *def, float *out);
int sj_ints_or_scalar(struct sj *s, const json_t *obj, const char *key, int n, int min, int max,
		      const int *def, int *out);
/* Colours: "#RRGGBB" or "#RRGGBBAA" are sRGB (converted to linear; alpha is stored as is), arrays of 3
 * (or 4 when with_alpha) numbers in [0,1] are linear. out[3] is alpha (1 unless given). */
int sj_color(struct sj *s, const json_t *obj, const char *key, const float def[4], bool with_alpha,
	     float out[4]);

/* Joins a relative file name from a scene onto base_dir, refusing absolute paths, ".." components and
 * (after resolving symlinks) anything outside base_dir. The error is set at the current path. */
int sj_resolve_file(struct sj *s, const char *base_dir, const char *rel, char *out, size_t size);

/* ---- loader parts in other files ---- */

/* mesh_procedural.c: builds a mesh from a spec object ({"type": "sphere", ...} or {"type": "file", ...})
 * at the current path; refuses meshes over max_triangles. */
int aa_mesh_from_json(struct sj *s, const json_t *spec, const char *base_dir, uint64_t max_triangles,
		      struct aa_mesh *out);

/* texture.c: builds a texture from {"file": ...} or {"text": ...}; budget is the bytes still allowed. */
int aa_texture_from_json(struct sj *s, const json_t *spec, const char *base_dir, size_t budget,
			 struct aa_texture *out);

/* camera_path.c: the scene camera (all fields) and the paths array (absent: one static path). */
int aa_camera_from_json(struct sj *s, const json_t *obj, const struct aa_camera *base, bool need_position,
			struct aa_camera *out);
int aa_paths_from_json(struct sj *s, const json_t *paths, const struct aa_camera *camera,
		       struct aa_scene *scene);

/* An invalid JSON document: "display:line:column: invalid JSON: what" (AA_ERR_INVALID); returns -1. */
int sj_parse_error(struct aa_error *err, const char *display, const json_error_t *je);

#endif
