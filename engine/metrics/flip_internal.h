/* Inside FLIP: the colour transforms as inline functions (flip.c's loops use them; flip_color.c wraps them
 * as the public aa_flip_* functions) and the SIMD kernels of flip_simd.c. float32, in the reference
 * implementation's order of operations. */
#ifndef AA_FLIP_INTERNAL_H
#define AA_FLIP_INTERNAL_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#define BLOCK 128 /* floats per block of a row: the unit of the filters and of the error loop */
#define VECTOR_SLACK 8 /* floats that vector loops may read or write past the end of a row */

static const float white_d65[3] = { 0.950428545f, 1.000000000f, 1.088900371f };
static const float white_d65_inv[3] = { 1.052156925f, 1.000000000f, 0.918357670f };
/* Linear sRGB to XYZ: quotients of float literals, rounded as the reference rounds them. */
static const float flip_rgb_to_xyz[3][3] = {
	{ 10135552.0f / 24577794.0f, 8788810.0f / 24577794.0f, 4435075.0f / 24577794.0f },
	{ 2613072.0f / 12288897.0f, 8788810.0f / 12288897.0f, 887015.0f / 12288897.0f },
	{ 1425312.0f / 73733382.0f, 8788810.0f / 73733382.0f, 70074185.0f / 73733382.0f },
};
static const float flip_xyz_to_rgb[3][3] = {
	{ 3.241003275f, -1.537398934f, -0.498615861f },
	{ -0.969224334f, 1.875930071f, 0.041554224f },
	{ 0.055639423f, -0.204011202f, 1.057148933f },
};

static inline void flip_linear_to_xyz(const float c[3], float o[3])
{
	const float(*a)[3] = flip_rgb_to_xyz;
	float r = c[0], g = c[1], b = c[2];
	o[0] = a[0][0] * r + a[0][1] * g + a[0][2] * b;
	o[1] = a[1][0] * r + a[1][1] * g + a[1][2] * b;
	o[2] = a[2][0] * r + a[2][1] * g + a[2][2] * b;
}

static inline void flip_xyz_to_linear(const float c[3], float o[3])
{
	const float(*a)[3] = flip_xyz_to_rgb;
	float x = c[0], y = c[1], z = c[2];
	o[0] = a[0][0] * x + a[0][1] * y + a[0][2] * z;
	o[1] = a[1][0] * x + a[1][1] * y + a[1][2] * z;
	o[2] = a[2][0] * x + a[2][1] * y + a[2][2] * z;
}

static inline void flip_xyz_to_ycxcz(const float c[3], float o[3])
{
	float x = c[0] * white_d65_inv[0], y = c[1] * white_d65_inv[1], z = c[2] * white_d65_inv[2];
	o[0] = 116.0f * y - 16.0f;
	o[1] = 500.0f * (x - y);
	o[2] = 200.0f * (y - z);
}

static inline void flip_ycxcz_to_xyz(const float c[3], float o[3])
{
	float y = (c[0] + 16.0f) / 116.0f;
	float cx = c[1] / 500.0f, cz = c[2] / 200.0f;
	o[0] = (y + cx) * white_d65[0];
	o[1] = y * white_d65[1];
	o[2] = (y - cz) * white_d65[2];
}

static inline void flip_xyz_to_lab(const float c[3], float o[3])
{
	const float delta = 6.0f / 29.0f, delta_sq = delta * delta, delta_cube = delta * delta_sq;
	const float factor = 1.0f / (3.0f * delta_sq), term = 4.0f / 29.0f;
	float f[3];
	for (int i = 0; i < 3; i++) {
		float t = c[i] * white_d65_inv[i];
		f[i] = t > delta_cube ? powf(t, 1.0f / 3.0f) : factor * t + term;
	}
	o[0] = 116.0f * f[1] - 16.0f;
	o[1] = 500.0f * (f[0] - f[1]);
	o[2] = 200.0f * (f[1] - f[2]);
}

/* flip_simd.c: the filters (taps ascending, accumulated from 0 like the reference) and the vectorised
 * parts of the per-pixel colour error. Widths are whole blocks of BLOCK floats. */
void flip_filter_row(const float *src, const float *w, int taps, float *out, size_t len);
void flip_filter_row3(const float *src, const float *w0, const float *w1, const float *w2, int taps, float *o0,
		      float *o1, float *o2, size_t len);
void flip_filter_column(const float *const *rows, size_t offset, const float *w, int taps, float *out);
void flip_filter_column2(const float *const *rows, size_t offset, const float *w0, const float *w1, int taps,
			 float *o0, float *o1);
/* n pixels of linear R, G, B planes -> Y, Cx, Cz and the feature luminance Yn = (Y + 16) / 116. Reads
 * and writes up to VECTOR_SLACK - 1 values past n. */
void flip_ycxcz_row(float *const rgb[3], int n, float *y, float *cx, float *cz, float *yn);
/* Filtered Y, Cx and Cz (the sum of the two Cz rows) of reference (0) and test (1) -> linear RGB, clamped
 * -> XYZ scaled by the white point, into t[image][x|y|z]; same[e] is -1 where the three filtered values
 * agree exactly and 0 elsewhere. */
void flip_colour_block(const float *const yc[2][4], float t[2][3][BLOCK], int32_t same[BLOCK]);
/* From the cube-rooted t (CIELab f values) of both images: |dL| and da^2 + db^2 of the Hunt-adjusted
 * CIELab colours. */
void flip_lab_block(const float f[2][3][BLOCK], float dl[BLOCK], float dab2[BLOCK]);

#endif
