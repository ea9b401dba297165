/* Small column-major 4x4 matrix and vector helpers (the layout GLSL expects). */
#ifndef AA_MAT4_H
#define AA_MAT4_H

/* m[c*4 + r]: column c, row r. */
typedef struct { float m[16]; } mat4;
typedef struct { float x, y, z; } vec3;

static inline vec3 v3(float x, float y, float z) { vec3 v = {x, y, z}; return v; }
vec3 v3_add(vec3 a, vec3 b);
vec3 v3_sub(vec3 a, vec3 b);
vec3 v3_scale(vec3 a, float s);
vec3 v3_lerp(vec3 a, vec3 b, float t);
float v3_dot(vec3 a, vec3 b);
vec3 v3_cross(vec3 a, vec3 b);
float v3_length(vec3 a);
vec3 v3_normalize(vec3 a); /* returns a unchanged when its length is ~0 */

mat4 mat4_identity(void);
mat4 mat4_mul(mat4 a, mat4 b); /* a * b: b applied first */
mat4 mat4_translate(vec3 t);
mat4 mat4_scale(vec3 s);
mat4 mat4_rotate(vec3 axis, float radians);
mat4 mat4_look_at(vec3 eye, vec3 target, vec3 up); /* right-handed view, camera looks down -z */
/* Reversed-Z perspective for Vulkan clip space: near -> depth 1, far -> depth 0, y flipped to Vulkan's
 * downward NDC y. fov_y in radians. */
mat4 mat4_perspective_reversed_z(float fov_y, float aspect, float near, float far);
/* Reversed-Z orthographic: view-space x in [-w/2, w/2], y in [-h/2, h/2]. */
mat4 mat4_ortho_reversed_z(float width, float height, float near, float far);
int mat4_invert(mat4 a, mat4 *out); /* 0 on success, -1 if singular */
mat4 mat4_transpose(mat4 a);
vec3 mat4_transform_point(mat4 a, vec3 p); /* with perspective divide */
vec3 mat4_transform_dir(mat4 a, vec3 d);   /* upper 3x3 only */
void mat4_transform_vec4(mat4 a, const float in[4], float out[4]);

#endif
