/* The in-memory scene: meshes, materials, textures, objects, lights and camera paths, as loaded from a
 * JSON scene file (docs/scene-format.md) or built in code (2D test patterns). The renderer reads this;
 * nothing here touches Vulkan. */
#ifndef AA_SCENE_H
#define AA_SCENE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <time.h>

#include "util/error.h"
#include "util/mat4.h"

#define AA_NAME_MAX 64

/* Limits on scene files (docs/scene-format.md): a bad or hostile file fails with AA_ERR_LIMIT instead of
 * exhausting memory or the CPU rasteriser. */
#define AA_SCENE_MAX_FILE_BYTES (4u << 20)      /* scene JSON text */
#define AA_SCENE_MAX_TRIANGLES 1000000u         /* drawn per scene (each object counts its mesh) */
#define AA_SCENE_MAX_OBJECTS 4096
#define AA_SCENE_MAX_MESHES 256               /* meshes a scene file defines or writes inline */
#define AA_SCENE_MAX_MATERIALS 256            /* materials a scene file defines (+1 implicit default) */
#define AA_SCENE_MAX_TEXTURES 32              /* textures a scene file defines */
/* What mesh files may add on top: each file material and each part (one per material) of a file mesh. */
#define AA_SCENE_MAX_ALL_MESHES 2048
#define AA_SCENE_MAX_ALL_MATERIALS 1024
#define AA_SCENE_MAX_ALL_TEXTURES 256
#define AA_SCENE_MAX_DRAWS 16384              /* objects after each is split into its parts */
#define AA_SCENE_MAX_WARNINGS 32
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
	float tangent[4];  /* xyz: the surface direction of +u, w: handedness (bitangent = w * normal x tangent,
			    * toward the top of the image); for normal maps */
	float color[4];    /* linear RGBA vertex colour: 1 where the mesh has none */
};

/* Up to four joints per vertex of a skinned mesh: indices into its rig's joints, weights summing to 1. */
struct aa_skin_weights {
	uint16_t joints[4];
	float weights[4];
};

struct aa_mesh {
	char name[AA_NAME_MAX];
	struct aa_vertex *vertices;
	uint32_t vertex_count;
	uint32_t *indices; /* triangle list */
	uint32_t index_count;
	float bounds_min[3], bounds_max[3]; /* of the positions, in the mesh's own space */
	/* Mesh files: a file mesh is split into parts, one per material; the first part of a file says how
	 * many follow (part_count, 1 for other meshes) and each part names its file material (-1: none, the
	 * scene's default). */
	int part_count;
	int file_material;
	/* Skinned or animated parts: per-vertex joints into the rig scene->rigs[rig]; NULL and -1 otherwise.
	 * Vertices are then in the rig's bind space, and posed on the CPU every frame (aa_rig_pose). */
	struct aa_skin_weights *skin;
	int rig;
};

/* Decoded RGBA8 texture in sRGB encoding (as image files store colour), with a full mip chain so the
 * renderer can upload it as is. level 0 is width x height; level i is max(1, w>>i) x max(1, h>>i). */
struct aa_texture {
	char name[AA_NAME_MAX];
	char source[512]; /* file it came from, or "text:..." for generated text */
	int width, height;
	int mip_levels;
	uint8_t **mips; /* mip_levels pointers, each w_i*h_i*4 bytes */
	bool linear;      /* data, not colour (normal, metallic-roughness and occlusion maps): stored and
			   * filtered as is, not sRGB-decoded */
	bool coverage;    /* alpha is coverage (the base colour of a cut-out or blended material): mips weight
			   * colour by alpha; otherwise alpha takes no part in the colour's mips (glTF OPAQUE) */
};

enum aa_pattern {
	AA_PATTERN_NONE = 0, /* plain base colour */
	AA_PATTERN_CHECKER,  /* procedural in the shader: alternating base_color/color2, `scale` cells per uv unit */
	AA_PATTERN_STRIPES,  /* procedural: stripes along u, `scale` per uv unit, `stripe_width` fraction of color2 */
	AA_PATTERN_TEXTURE,  /* sampled: textures[texture_index] (image file or generated text) */
};

/* The textures a material may sample besides its base colour (texture_index), for file materials. */
enum aa_material_map {
	AA_MAP_BASE = 0,       /* texture_index: sRGB base colour (alpha: coverage) */
	AA_MAP_EMISSIVE,       /* sRGB emitted colour, times `emissive` */
	AA_MAP_NORMAL,         /* tangent-space normal (linear) */
	AA_MAP_METAL_ROUGH,    /* linear: green = roughness, blue = metalness (glTF) */
	AA_MAP_OCCLUSION,      /* linear: red = ambient occlusion */
	AA_MAP_COUNT
};

enum aa_shading_model {
	AA_SHADING_BLINN_PHONG = 0, /* scene materials: Lambert + optional normalised Blinn-Phong */
	AA_SHADING_METAL_ROUGH,     /* glTF metallic-roughness: a GGX microfacet BRDF (docs/scene-format.md) */
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
	float roughness;       /* (0,1]: maps to the Blinn-Phong exponent; metal_rough: perceptual roughness */
	bool alpha_cutout;     /* fragments with alpha < alpha_cutoff are discarded (needs the alpha-test pass) */
	float alpha_cutoff;
	bool unlit;            /* colour is output as is, no lighting (2D patterns, emissive signs) */
	/* Materials from mesh files (all off in scene materials; aa_material_defaults) */
	enum aa_shading_model model;
	float metallic;        /* metal_rough: 0 dielectric .. 1 metal */
	float emissive[3];     /* linear emitted colour (glTF emissiveFactor x KHR_materials_emissive_strength) */
	float normal_scale;    /* glTF normalTexture.scale */
	float occlusion_strength;
	int maps[AA_MAP_COUNT];/* texture per map, -1 none; maps[AA_MAP_BASE] mirrors texture_index */
	/* KHR_texture_transform per map: uv' = (m[0] u + m[1] v + m[2], m[3] u + m[4] v + m[5]) */
	float uv_transform[AA_MAP_COUNT][6];
	bool uv_transformed;   /* some map's transform is not the identity */
	bool vertex_color;     /* base colour times the mesh's vertex colours (COLOR_0) */
	bool single_sided;     /* back faces are culled (glTF doubleSided false); scene materials are two-sided */
	bool blend;            /* alpha blended (glTF BLEND): drawn after opaque objects, back to front */
	char source[160];      /* where a file material came from: "assets/fox.glb: materials[0]" */
};

enum aa_light_type { AA_LIGHT_DIRECTIONAL = 0, AA_LIGHT_POINT = 1 };

struct aa_light {
	enum aa_light_type type;
	float direction[3]; /* directional: direction the light travels (normalized) */
	double position[3]; /* point, world (double, as aa_object.origin) */
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
	float pivot[3];         /* spin pivot, relative to the object's origin */
};

/* A rig: the node hierarchy of a mesh file, the joints its skinned parts use, and its animations. Posed
 * on the CPU (scene_rig.c): a joint's matrix is its node's world matrix times its inverse bind matrix,
 * as glTF defines skinning (the skinned mesh's own node transform is not used). */
enum aa_channel_path { AA_CHANNEL_TRANSLATION, AA_CHANNEL_ROTATION, AA_CHANNEL_SCALE };

struct aa_rig_channel {
	int node;
	enum aa_channel_path path;
	int key_count;
	float *times;           /* seconds, increasing */
	float *values;          /* 3 (translation, scale) or 4 (rotation quaternion x, y, z, w) per key */
};

struct aa_rig_clip {
	char name[AA_NAME_MAX];
	double duration;        /* seconds: the last key's time */
	int channel_count;
	struct aa_rig_channel *channels;
};

struct aa_rig_node {
	int parent;             /* index of the parent node, -1 for roots; parents come before children */
	float translation[3], rotation[4], scale[3]; /* the rest pose, as the file gives it */
};

struct aa_rig {
	char source[160];       /* the file, for messages */
	int node_count;
	struct aa_rig_node *nodes;
	int joint_count;
	int *joint_node;        /* per joint: its node (-1: the identity, for parts that do not move) */
	mat4 *inverse_bind;     /* per joint */
	int clip_count;
	struct aa_rig_clip *clips;
};

/* An object's pose: the rig's rest pose (clip -1) or its clip at time clip_time + clip_speed * t. */
struct aa_pose {
	int clip;
	double clip_time;       /* seconds into the clip at t = 0 */
	double clip_speed;      /* clip seconds per second (0: held) */
};

/* One draw: a scene object, or one part of an object whose file mesh has several materials. */
struct aa_object {
	char name[AA_NAME_MAX];
	int mesh_index;
	int material_index;
	/* World position, in double: in floats a position 600,000 units out is a multiple of 1/16 unit. The
	 * renderer subtracts the camera's position from it in double (camera-relative rendering). */
	double origin[3];
	mat4 transform;         /* base model matrix at t = 0, relative to origin (rotation and scale) */
	struct aa_animation animation;
	struct aa_pose pose;    /* skinned or animated mesh parts (mesh->rig >= 0) */
	uint32_t model_id;      /* 1-based, the scene file's object index + 1: all parts of an object share it */
};

enum aa_projection { AA_PROJECTION_PERSPECTIVE = 0, AA_PROJECTION_ORTHOGRAPHIC = 1 };

/* position and target are relative to origin (double), so that a camera far from the world's origin keeps
 * float precision: origin is the scene camera's position rounded to a multiple of 1024 units (0 for a
 * camera within 512 units of the origin) and every camera and path of the scene shares it. */
struct aa_camera {
	double origin[3];
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
	vec3 center;            /* orbit, relative to keys[0].camera.origin */
	float degrees;          /* orbit: degrees over `duration`; pan: yaw over `duration` */
	float distance;         /* dolly */
	float catmull_alpha;    /* keyframes: 0.5 centripetal (default), 0 uniform Catmull-Rom */
};

/* A file a scene's load read, as it was then (scene_sources.c). */
struct aa_scene_source {
	char *path;             /* resolved: no symbolic links */
	int64_t size;
	struct timespec mtime;
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
	struct aa_rig *rigs; int rig_count;
	int model_count;        /* objects in the scene file (the largest model_id) */
	/* What loading dropped or approximated, each message once (docs/scene-format.md, "Warnings") */
	int warning_count;      /* kept; more than AA_SCENE_MAX_WARNINGS are counted in warnings_dropped */
	int warnings_dropped;
	char warnings[AA_SCENE_MAX_WARNINGS][256];
	/* Every file the load read besides `file`, for caches of loaded scenes (scene_sources.c) */
	struct aa_scene_source *sources; int source_count;
	bool sources_unknown;   /* one could not be recorded: treat the scene as changed */
	/* SHA-256 of the scene text and of every source's bytes as loaded (aa_scene_sources_digest); false for
	 * scenes built in code and when a file changed while it was read: nothing can be keyed by it */
	bool content_known;
	uint8_t content_sha256[32];
};

/* scene_sources.c: while a load runs on this thread, collect into `scene` (NULL: stop) the files that the
 * resolvers report with aa_scene_source_read. aa_scene_sources_changed: whether any of them is gone or
 * has another size or modification time now. */
void aa_scene_sources_collect(struct aa_scene *scene);
void aa_scene_source_read(const char *path);
bool aa_scene_sources_changed(const struct aa_scene *scene);
void aa_scene_sources_free(struct aa_scene *scene);
/* After a load: scene->content_sha256 over the scene text (size bytes) and each source's bytes in the order
 * the load read them; content_known only when every source still has the size and time it was read with. */
void aa_scene_sources_digest(struct aa_scene *scene, const void *text, size_t size);

/* Finds a scene by name ("thin-wires") or path ("my/scene.json"). Names are looked up in, in order:
 * $AALAB_SCENE_DIR, the build tree's scenes/ (AA_SOURCE_SCENE_DIR), the installed pkgdatadir/scenes
 * (AA_INSTALLED_SCENE_DIR). Writes the resolved file path. Names with '/' or '..' are treated as paths
 * only when they end in ".json". */
int aa_scene_resolve(const char *name_or_path, char *out_path, size_t out_size, struct aa_error *err);

/* Lists the scene names available (caller frees each name and the array). */
int aa_scene_list(char ***names, int *count);

/* What `aalab scenes` shows of a scene file, read without building its meshes or textures. */
struct aa_scene_summary {
	char name[AA_NAME_MAX];
	char description[256];
	int path_count;
	char paths[AA_SCENE_MAX_PATHS][AA_NAME_MAX];
	int object_count;
};
int aa_scene_summarize(const char *path, struct aa_scene_summary *out, struct aa_error *err);

/* Loads and validates a scene file. Errors name the file, the JSON path ("objects[2].mesh.radius") and
 * what is wrong. Relative mesh/texture paths resolve against the scene file's directory and may not
 * leave it (no "..", no absolute paths). */
int aa_scene_load(const char *path, struct aa_scene **out, struct aa_error *err);
/* The same, naming the file `shown` in errors instead of path (aalabd: relative to the scene folder it was
 * found in, so that no error shows the server's folders). */
int aa_scene_load_as(const char *path, const char *shown, struct aa_scene **out, struct aa_error *err);
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
/* The same relative to eye (world, double): its translation is origin + motion - eye, taken in double
 * before it becomes a float, so that it keeps float precision near the camera wherever the world is. */
mat4 aa_object_model_relative(const struct aa_object *object, double t, const double eye[3]);
/* A camera's world position (origin + position) in double. */
void aa_camera_eye(const struct aa_camera *camera, double eye[3]);
bool aa_scene_has_animation(const struct aa_scene *scene); /* objects move or skinned parts are animated */
bool aa_object_is_animated(const struct aa_scene *scene, const struct aa_object *object);
bool aa_scene_has_cutout(const struct aa_scene *scene);   /* some object draws with a cut-out material */
bool aa_scene_has_shadow_caster_light(const struct aa_scene *scene);
/* Adds a warning (formatted once; a message already held is not repeated). */
void aa_scene_warn(struct aa_scene *scene, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* The defaults of a scene material (docs/scene-format.md): grey, Lambert, two-sided, no maps. */
void aa_material_defaults(struct aa_material *m);

/* Poses a rig at time t for an object: world matrices of every joint times its inverse bind matrix
 * (joint_count matrices), in the rig's space (the object's model matrix goes on top). */
void aa_rig_pose(const struct aa_rig *rig, const struct aa_pose *pose, double t, mat4 *joint_matrices);
/* Skins a mesh part with joint matrices: positions, normals and tangents into out (vertex_count). */
void aa_mesh_skin(const struct aa_mesh *mesh, const mat4 *joint_matrices, struct aa_vertex *out);
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
