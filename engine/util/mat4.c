/* Matrix helpers: plain float math, column-major like GLSL. */
#include "util/mat4.h"

#include <math.h>

vec3 v3_add(vec3 a, vec3 b) { return v3(a.x + b.x, a.y + b.y, a.z + b.z); }
vec3 v3_sub(vec3 a, vec3 b) { return v3(a.x - b.x, a.y - b.y, a.z - b.z); }
vec3 v3_scale(vec3 a, float s) { return v3(a.x * s, a.y * s, a.z * s); }
vec3 v3_lerp(vec3 a, vec3 b, float t) { return v3_add(a, v3_scale(v3_sub(b, a), t)); }
float v3_dot(vec3 a, vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
vec3 v3_cross(vec3 a, vec3 b)
{
	return v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
float v3_length(vec3 a) { return sqrtf(v3_dot(a, a)); }
vec3 v3_normalize(vec3 a)
{
	float l = v3_length(a);
	return l > 1e-20f ? v3_scale(a, 1.0f / l) : a;
}

mat4 mat4_identity(void)
{
	mat4 r = {{0}};
	r.m[0] = r.m[5] = r.m[10] = r.m[15] = 1.0f;
	return r;
}

mat4 mat4_mul(mat4 a, mat4 b)
{
	mat4 r;
	for (int c = 0; c < 4; c++)
		for (int row = 0; row < 4; row++) {
			float s = 0.0f;
			for (int k = 0; k < 4; k++)
				s += a.m[k * 4 + row] * b.m[c * 4 + k];
			r.m[c * 4 + row] = s;
		}
	return r;
}

mat4 mat4_translate(vec3 t)
{
	mat4 r = mat4_identity();
	r.m[12] = t.x;
	r.m[13] = t.y;
	r.m[14] = t.z;
	return r;
}

mat4 mat4_scale(vec3 s)
{
	mat4 r = mat4_identity();
	r.m[0] = s.x;
	r.m[5] = s.y;
	r.m[10] = s.z;
	return r;
}

mat4 mat4_rotate(vec3 axis, float radians)
{
	vec3 a = v3_normalize(axis);
	float c = cosf(radians), s = sinf(radians), t = 1.0f - c;
	mat4 r = mat4_identity();
	r.m[0] = t * a.x * a.x + c;
	r.m[1] = t * a.x * a.y + s * a.z;
	r.m[2] = t * a.x * a.z - s * a.y;
	r.m[4] = t * a.x * a.y - s * a.z;
	r.m[5] = t * a.y * a.y + c;
	r.m[6] = t * a.y * a.z + s * a.x;
	r.m[8] = t * a.x * a.z + s * a.y;
	r.m[9] = t * a.y * a.z - s * a.x;
	r.m[10] = t * a.z * a.z + c;
	return r;
}

mat4 mat4_look_at(vec3 eye, vec3 target, vec3 up)
{
	vec3 f = v3_normalize(v3_sub(target, eye));
	vec3 s = v3_normalize(v3_cross(f, up));
	vec3 u = v3_cross(s, f);
	mat4 r = mat4_identity();
	r.m[0] = s.x; r.m[4] = s.y; r.m[8] = s.z;
	r.m[1] = u.x; r.m[5] = u.y; r.m[9] = u.z;
	r.m[2] = -f.x; r.m[6] = -f.y; r.m[10] = -f.z;
	r.m[12] = -v3_dot(s, eye);
	r.m[13] = -v3_dot(u, eye);
	r.m[14] = v3_dot(f, eye);
	return r;
}

mat4 mat4_perspective_reversed_z(float fov_y, float aspect, float near, float far)
{
	/* z_ndc = (near*far/(far-near)) / (-z_view) - near/(far-near)... written so that
	 * z_view = -near gives 1 and z_view = -far gives 0. */
	float f = 1.0f / tanf(fov_y * 0.5f);
	mat4 r = {{0}};
	r.m[0] = f / aspect;
	r.m[5] = -f; /* Vulkan NDC y points down */
	r.m[10] = near / (far - near);
	r.m[11] = -1.0f;
	r.m[14] = near * far / (far - near);
	return r;
}

mat4 mat4_ortho_reversed_z(float width, float height, float near, float far)
{
	mat4 r = mat4_identity();
	r.m[0] = 2.0f / width;
	r.m[5] = -2.0f / height;
	/* z_view = -near -> 1, z_view = -far -> 0 */
	r.m[10] = 1.0f / (far - near);
	r.m[14] = far / (far - near);
	return r;
}

mat4 mat4_transpose(mat4 a)
{
	mat4 r;
	for (int c = 0; c < 4; c++)
		for (int row = 0; row < 4; row++)
			r.m[c * 4 + row] = a.m[row * 4 + c];
	return r;
}

int mat4_invert(mat4 a, mat4 *out)
{
	/* Cofactor expansion in double precision. */
	double inv[16], det;
	const float *m = a.m;
	inv[0] = (double)m[5] * m[10] * m[15] - (double)m[5] * m[11] * m[14] - (double)m[9] * m[6] * m[15] +
		 (double)m[9] * m[7] * m[14] + (double)m[13] * m[6] * m[11] - (double)m[13] * m[7] * m[10];
	inv[4] = -(double)m[4] * m[10] * m[15] + (double)m[4] * m[11] * m[14] + (double)m[8] * m[6] * m[15] -
		 (double)m[8] * m[7] * m[14] - (double)m[12] * m[6] * m[11] + (double)m[12] * m[7] * m[10];
	inv[8] = (double)m[4] * m[9] * m[15] - (double)m[4] * m[11] * m[13] - (double)m[8] * m[5] * m[15] +
		 (double)m[8] * m[7] * m[13] + (double)m[12] * m[5] * m[11] - (double)m[12] * m[7] * m[9];
	inv[12] = -(double)m[4] * m[9] * m[14] + (double)m[4] * m[10] * m[13] + (double)m[8] * m[5] * m[14] -
		  (double)m[8] * m[6] * m[13] - (double)m[12] * m[5] * m[10] + (double)m[12] * m[6] * m[9];
	inv[1] = -(double)m[1] * m[10] * m[15] + (double)m[1] * m[11] * m[14] + (double)m[9] * m[2] * m[15] -
		 (double)m[9] * m[3] * m[14] - (double)m[13] * m[2] * m[11] + (double)m[13] * m[3] * m[10];
	inv[5] = (double)m[0] * m[10] * m[15] - (double)m[0] * m[11] * m[14] - (double)m[8] * m[2] * m[15] +
		 (double)m[8] * m[3] * m[14] + (double)m[12] * m[2] * m[11] - (double)m[12] * m[3] * m[10];
	inv[9] = -(double)m[0] * m[9] * m[15] + (double)m[0] * m[11] * m[13] + (double)m[8] * m[1] * m[15] -
		 (double)m[8] * m[3] * m[13] - (double)m[12] * m[1] * m[11] + (double)m[12] * m[3] * m[9];
	inv[13] = (double)m[0] * m[9] * m[14] - (double)m[0] * m[10] * m[13] - (double)m[8] * m[1] * m[14] +
		  (double)m[8] * m[2] * m[13] + (double)m[12] * m[1] * m[10] - (double)m[12] * m[2] * m[9];
	inv[2] = (double)m[1] * m[6] * m[15] - (double)m[1] * m[7] * m[14] - (double)m[5] * m[2] * m[15] +
		 (double)m[5] * m[3] * m[14] + (double)m[13] * m[2] * m[7] - (double)m[13] * m[3] * m[6];
	inv[6] = -(double)m[0] * m[6] * m[15] + (double)m[0] * m[7] * m[14] + (double)m[4] * m[2] * m[15] -
		 (double)m[4] * m[3] * m[14] - (double)m[12] * m[2] * m[7] + (double)m[12] * m[3] * m[6];
	inv[10] = (double)m[0] * m[5] * m[15] - (double)m[0] * m[7] * m[13] - (double)m[4] * m[1] * m[15] +
		  (double)m[4] * m[3] * m[13] + (double)m[12] * m[1] * m[7] - (double)m[12] * m[3] * m[5];
	inv[14] = -(double)m[0] * m[5] * m[14] + (double)m[0] * m[6] * m[13] + (double)m[4] * m[1] * m[14] -
		  (double)m[4] * m[2] * m[13] - (double)m[12] * m[1] * m[6] + (double)m[12] * m[2] * m[5];
	inv[3] = -(double)m[1] * m[6] * m[11] + (double)m[1] * m[7] * m[10] + (double)m[5] * m[2] * m[11] -
		 (double)m[5] * m[3] * m[10] - (double)m[9] * m[2] * m[7] + (double)m[9] * m[3] * m[6];
	inv[7] = (double)m[0] * m[6] * m[11] - (double)m[0] * m[7] * m[10] - (double)m[4] * m[2] * m[11] +
		 (double)m[4] * m[3] * m[10] + (double)m[8] * m[2] * m[7] - (double)m[8] * m[3] * m[6];
	inv[11] = -(double)m[0] * m[5] * m[11] + (double)m[0] * m[7] * m[9] + (double)m[4] * m[1] * m[11] -
		  (double)m[4] * m[3] * m[9] - (double)m[8] * m[1] * m[7] + (double)m[8] * m[3] * m[5];
	inv[15] = (double)m[0] * m[5] * m[10] - (double)m[0] * m[6] * m[9] - (double)m[4] * m[1] * m[10] +
		  (double)m[4] * m[2] * m[9] + (double)m[8] * m[1] * m[6] - (double)m[8] * m[2] * m[5];
	det = m[0] * inv[0] + m[1] * inv[4] + m[2] * inv[8] + m[3] * inv[12];
	if (fabs(det) < 1e-30)
		return -1;
	for (int i = 0; i < 16; i++)
		out->m[i] = (float)(inv[i] / det);
	return 0;
}

vec3 mat4_transform_point(mat4 a, vec3 p)
{
	float in[4] = {p.x, p.y, p.z, 1.0f}, o[4];
	mat4_transform_vec4(a, in, o);
	float w = fabsf(o[3]) > 1e-30f ? o[3] : 1.0f;
	return v3(o[0] / w, o[1] / w, o[2] / w);
}

vec3 mat4_transform_dir(mat4 a, vec3 d)
{
	return v3(a.m[0] * d.x + a.m[4] * d.y + a.m[8] * d.z, a.m[1] * d.x + a.m[5] * d.y + a.m[9] * d.z,
		  a.m[2] * d.x + a.m[6] * d.y + a.m[10] * d.z);
}

void mat4_transform_vec4(mat4 a, const float in[4], float out[4])
{
	for (int r = 0; r < 4; r++)
		out[r] = a.m[r] * in[0] + a.m[4 + r] * in[1] + a.m[8 + r] * in[2] + a.m[12 + r] * in[3];
}
