/* The in-memory scene: meshes, materials, textures, objects, lights and camera paths, as loaded from a
 * JSON scene file (docs/scene-format.md) or built in code (2D test patterns). The renderer reads this;
 * nothing here touches Vulkan. */
#ifndef AA_SCENE_H
#define AA_SCENE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "../error.h"
#include "../mat4.h"

#define AA_NAME_MAX 64

/* Limits on scene files (docs/scene-format.md): a bad or hostile file fails with AA_ERR_LIMIT instead of
 * exhausting memory or the CPU rasteriser. */
#define AA_SCENE_MAX_FILE_BYTES (4u << 20)      /* scene JSON text */
#define AA_SCENE_MAX_TRIANGLES 1000000u         /* drawn per scene (each object counts its mesh) */
#define AA_SCENE_MAX_OBJECTS 4096
#define AA_SCENE_MAX_MESHES 256
#define AA_SCENE_MAX_MATERIALS 256
#define AA_SCENE_MAX_TEXTURES 32
#define AA_SCENE_MAX_LIGHTS 8
#define AA_SCENE_MAX_PATHS 32
#define AA_SCENE_MAX_KEYS 256                   /* keys per camera path */
#define AA_TEXTURE_MAX_SIZE 4096                /* width or height, texels */
#define AA_SCENE_MAX_TEXTURE_BYTES (256u << 20) /* all textures with their mips */
#define AA_MESH_FILE_MAX_BYTES (64u << 20)

struct aa_vertex {
	float position[3];
	float normal[3];
	float uv[2];
};

struct aa_mesh {
	char name[AA_NAME_MAX];
	struct aa_vertex *vertices;
	uint32_t vertex_count;
	uint32_t *indices; /* triangle list */
	uint32_t index_count;
};

/* Decoded RGBA8 texture in sRGB encoding (as image files store colour), with a full mip chain so the
 * renderer can upload it as is. level 0 is width x height; level i is max(1, w>>i) x max(1, h>>i). */
struct aa_texture {
	char name[AA_NAME_MAX];
	char source[512]; /* file it came from, or "text:..." for generated text */
	int width, height;
	int mip_levels;
	uint8_t **mips; /* mip_levels pointers, each w_i*h_i*4 bytes */
};

enum aa_pattern {
	AA_PATTERN_NONE = 0, /* plain base colour */
	AA_PATTERN_CHECKER,  /* procedural in the shader: alternating base_color/color2, `scale` cells per uv unit */
	AA_PATTERN_STRIPES,  /* procedural: stripes along u, `scale` per uv unit, `stripe_width` fraction of color2 */
	AA_PATTERN_TEXTURE,  /* sampled: textures[texture_index] (image file or generated text) */
};

struct aa_material {
	char name[AA_NAME_MAX];
	float base_color[4];   /* linear RGB + alpha */
	enum aa_pattern pattern;
	float color2[3];       /* second colour of checker/stripes, linear */
	float scale[2];        /* pattern repeats per uv unit in u and v */
	float stripe_width;    /* share of each stripe period in color2, (0,1) */
	int texture_index;     /* index into scene->textures, -1 if none */
	float specular;        /* 0 = Lambert only; >0 adds Blinn-Phong specular of this strength */
	float roughness;       /* (0,1]: maps to the Blinn-Phong exponent */
	bool alpha_cutout;     /* fragments with alpha < alpha_cutoff are discarded (needs the alpha-test pass) */
	float alpha_cutoff;
	bool unlit;            /* colour is output as is, no lighting (2D patterns, emissive signs) */
};

enum aa_light_type { AA_LIGHT_DIRECTIONAL = 0, AA_LIGHT_POINT = 1 };

struct aa_light {
	enum aa_light_type type;
	float direction[3]; /* directional: direction the light travels (normalized) */
	float position[3];  /* point */
	float color[3];     /* linear */
	float intensity;
	float range;        /* point: distance at which it falls to zero (smooth window), 0 = inverse square only */
	bool casts_shadow;
};

/* Per-object motion over time t in seconds: model(t) = T(translate(t)) * R(spin(t)) * base. */
struct aa_animation {
	bool active;
	float velocity[3];      /* units per second, added to the translation */
	float oscillate_axis[3];/* sinusoidal offset: axis * amplitude * sin(2*pi*frequency*t) */
	float oscillate_amplitude;
	float oscillate_frequency;
	float spin_axis[3];
	float spin_degrees_per_second;
	float pivot[3];         /* spin pivot, world space */
};

struct aa_object {
	char name[AA_NAME_MAX];
	int mesh_index;
	int material_index;
	mat4 transform;         /* base model matrix at t = 0 */
	struct aa_animation animation;
	uint32_t model_id;      /* 1-based, unique per object: methods that read IDs use it */
};

enum aa_projection { AA_PROJECTION_PERSPECTIVE = 0, AA_PROJECTION_ORTHOGRAPHIC = 1 };

struct aa_camera {
	vec3 position, target, up;
	enum aa_projection projection;
	float fov_y_degrees;    /* perspective */
	float ortho_height;     /* orthographic: visible world height */
	float near_plane, far_plane;
};

struct aa_camera_key {
	double time;            /* seconds */
	struct aa_camera camera;
	bool cut;               /* a camera cut happens at this key: temporal history must reset */
};

enum aa_path_kind {
	AA_PATH_KEYFRAMES = 0,  /* Catmull-Rom through keys (position and target), other fields lerped */
	AA_PATH_STATIC,         /* first camera held */
	AA_PATH_ORBIT,          /* around `center` at the start camera's radius and height */
	AA_PATH_DOLLY,          /* straight toward the target by `distance` over `duration` */
	AA_PATH_PAN,            /* yaw by `degrees` over `duration`, position fixed */
};

struct aa_camera_path {
	char name[AA_NAME_MAX];
	enum aa_path_kind kind;
	double duration;        /* seconds; beyond it the path holds its end (keyframes) or wraps (orbit) */
	struct aa_camera_key *keys; /* keyframes; for named kinds, keys[0] is the start camera */
	int key_count;
	vec3 center;            /* orbit */
	float degrees;          /* orbit: degrees over `duration`; pan: yaw over `duration` */
	float distance;         /* dolly */
	float catmull_alpha;    /* keyframes: 0.5 centripetal (default), 0 uniform Catmull-Rom */
};

struct aa_scene {
	uint64_t uid;           /* unique per loaded scene in this process: the key of GPU caches */
	char name[AA_NAME_MAX];
	char file[1024];        /* "" for scenes built in code */
	char description[256];
	float background[3];    /* linear clear colour */
	float ambient[3];       /* linear ambient light */
	double fps;             /* frames per second of camera paths and animation, default 30 */

	struct aa_mesh *meshes; int mesh_count;
	struct aa_material *materials; int material_count;
	struct aa_texture *textures; int texture_count;
	struct aa_object *objects; int object_count;
	struct aa_light *lights; int light_count;
	struct aa_camera_path *paths; int path_count; /* paths[0] is the default path */
};

/* Finds a scene by name ("thin-wires") or path ("my/scene.json"). Names are looked up in, in order:
 * $AALAB_SCENE_DIR, the build tree's scenes/ (AA_SOURCE_SCENE_DIR), the installed pkgdatadir/scenes
 * (AA_INSTALLED_SCENE_DIR). Writes the resolved file path. Names with '/' or '..' are treated as paths
 * only when they end in ".json". */
int aa_scene_resolve(const char *name_or_path, char *out_path, size_t out_size, struct aa_error *err);

/* Lists the scene names available (caller frees each name and the array). */
int aa_scene_list(char ***names, int *count);

/* Loads and validates a scene file. Errors name the file, the JSON path ("objects[2].mesh.radius") and
 * what is wrong. Relative mesh/texture paths resolve against the scene file's directory and may not
 * leave it (no "..", no absolute paths). */
int aa_scene_load(const char *path, struct aa_scene **out, struct aa_error *err);
/* Same from an in-memory JSON text; base_dir is where relative files resolve (may be NULL: none). */
int aa_scene_load_string(const char *json_text, const char *display_name, const char *base_dir,
			 struct aa_scene **out, struct aa_error *err);
void aa_scene_free(struct aa_scene *scene);
/* A new process-wide scene identity (thread-safe; never 0). */
uint64_t aa_scene_new_uid(void);

/* Finds a camera path by name: "default" is paths[0]; "static" is paths[0]'s first camera held (the
 * caller passes hold_first = true to aa_camera_path_eval for "static"). NULL when there is no such path. */
const struct aa_camera_path *aa_scene_find_path(const struct aa_scene *scene, const char *name);

/* Evaluates a path at time t. *cut is set when a cut key lies in (t_prev, t] (t_prev < 0: no cut). */
void aa_camera_path_eval(const struct aa_camera_path *path, bool hold_first, double t_prev, double t,
			 struct aa_camera *out, bool *cut);

/* Model matrix of an object at time t (base transform with its animation applied). */
mat4 aa_object_model_matrix(const struct aa_object *object, double t);
bool aa_scene_has_animation(const struct aa_scene *scene);
bool aa_scene_has_cutout(const struct aa_scene *scene);
bool aa_scene_has_shadow_caster_light(const struct aa_scene *scene);
uint64_t aa_scene_triangle_count(const struct aa_scene *scene);
size_t aa_scene_bytes(const struct aa_scene *scene); /* CPU bytes held by meshes and textures */

/* 2D test patterns in pixel coordinates (x right, y down, pixel (i,j) covers [i,i+1]x[j,j+1]). */
struct aa_polygon2d {
	int count;          /* vertices, convex, counter-clockwise or clockwise */
	double xy[16][2];
};

/* Builds an unlit scene of constant-colour polygons over a background, seen by an orthographic camera
 * whose image maps exactly onto width x height pixels. */
int aa_scene_from_polygons(const struct aa_polygon2d *polys, int poly_count, int width, int height,
			   const float fg[3], const float bg[3], struct aa_scene **out, struct aa_error *err);

#endif
