/* FLIP's SIMD kernels: the separable filters and the vectorisable parts of the per-pixel colour error.
 *
 * Every lane computes what scalar code computes for its pixel, operation for operation, so results are
 * bit for bit those of the scalar reference (tests/unit/test_flip.c checks it). Filter outputs are
 * 0 + w[0] s[0] + w[1] s[1] + ..., taps ascending, as the reference sums them, with the accumulators in
 * registers over all taps. On x86-64 an AVX2 clone is chosen at load time where the CPU has it; never
 * FMA, which would round differently. */
#include <string.h>

#include "metrics/flip_internal.h"

typedef float vfloat __attribute__((vector_size(32)));
#define VLEN 8

#if defined(__x86_64__) && defined(__has_attribute)
#if __has_attribute(target_clones)
#define VECTOR_CLONES __attribute__((target_clones("avx2", "default")))
#endif
#endif
#ifndef VECTOR_CLONES
#define VECTOR_CLONES
#endif

#define VLOAD(p) ({ vfloat v_; memcpy(&v_, (p), sizeof v_); v_; })
#define VSTORE(p, v) do { vfloat v_ = (v); memcpy((p), &v_, sizeof v_); } while (0)

/* Horizontal: out[e] = sum over k of w[k] * src[e + k], for len outputs (a multiple of 4 VLEN). */
VECTOR_CLONES void flip_filter_row(const float *src, const float *w, int taps, float *out, size_t len)
{
	for (size_t e = 0; e < len; e += 4 * VLEN) {
		vfloat a0 = { 0 }, a1 = { 0 }, a2 = { 0 }, a3 = { 0 };
		for (int k = 0; k < taps; k++) {
			const float *sp = src + e + k;
			const vfloat wk = (vfloat){ 0 } + w[k];
			a0 += wk * VLOAD(sp);
			a1 += wk * VLOAD(sp + VLEN);
			a2 += wk * VLOAD(sp + 2 * VLEN);
			a3 += wk * VLOAD(sp + 3 * VLEN);
		}
		VSTORE(out + e, a0);
		VSTORE(out + e + VLEN, a1);
		VSTORE(out + e + 2 * VLEN, a2);
		VSTORE(out + e + 3 * VLEN, a3);
	}
}

/* Three filters of one source (the feature filters), sharing its loads. */
VECTOR_CLONES void flip_filter_row3(const float *src, const float *w0, const float *w1, const float *w2, int taps,
				     float *o0, float *o1, float *o2, size_t len)
{
	for (size_t e = 0; e < len; e += 2 * VLEN) {
		vfloat a0 = { 0 }, a1 = { 0 }, b0 = { 0 }, b1 = { 0 }, c0 = { 0 }, c1 = { 0 };
		for (int k = 0; k < taps; k++) {
			const float *sp = src + e + k;
			const vfloat s0 = VLOAD(sp), s1 = VLOAD(sp + VLEN);
			const vfloat wa = (vfloat){ 0 } + w0[k], wb = (vfloat){ 0 } + w1[k], wc = (vfloat){ 0 } + w2[k];
			a0 += wa * s0;
			a1 += wa * s1;
			b0 += wb * s0;
			b1 += wb * s1;
			c0 += wc * s0;
			c1 += wc * s1;
		}
		VSTORE(o0 + e, a0);
		VSTORE(o0 + e + VLEN, a1);
		VSTORE(o1 + e, b0);
		VSTORE(o1 + e + VLEN, b1);
		VSTORE(o2 + e, c0);
		VSTORE(o2 + e + VLEN, c1);
	}
}

/* Vertical: out[e] = sum over k of w[k] * rows[k][offset + e], for BLOCK outputs. */
VECTOR_CLONES void flip_filter_column(const float *const *rows, size_t offset, const float *w, int taps,
				       float *out)
{
	for (int e = 0; e < BLOCK; e += 4 * VLEN) {
		vfloat a0 = { 0 }, a1 = { 0 }, a2 = { 0 }, a3 = { 0 };
		for (int k = 0; k < taps; k++) {
			const float *sp = rows[k] + offset + e;
			const vfloat wk = (vfloat){ 0 } + w[k];
			a0 += wk * VLOAD(sp);
			a1 += wk * VLOAD(sp + VLEN);
			a2 += wk * VLOAD(sp + 2 * VLEN);
			a3 += wk * VLOAD(sp + 3 * VLEN);
		}
		VSTORE(out + e, a0);
		VSTORE(out + e + VLEN, a1);
		VSTORE(out + e + 2 * VLEN, a2);
		VSTORE(out + e + 3 * VLEN, a3);
	}
}

/* Two filters of one column source (the vertical derivatives of the Gaussian-filtered luminance). */
VECTOR_CLONES void flip_filter_column2(const float *const *rows, size_t offset, const float *w0, const float *w1,
					int taps, float *o0, float *o1)
{
	for (int e = 0; e < BLOCK; e += 2 * VLEN) {
		vfloat a0 = { 0 }, a1 = { 0 }, b0 = { 0 }, b1 = { 0 };
		for (int k = 0; k < taps; k++) {
			const float *sp = rows[k] + offset + e;
			const vfloat s0 = VLOAD(sp), s1 = VLOAD(sp + VLEN);
			const vfloat wa = (vfloat){ 0 } + w0[k], wb = (vfloat){ 0 } + w1[k];
			a0 += wa * s0;
			a1 += wa * s1;
			b0 += wb * s0;
			b1 += wb * s1;
		}
		VSTORE(o0 + e, a0);
		VSTORE(o0 + e + VLEN, a1);
		VSTORE(o1 + e, b0);
		VSTORE(o1 + e + VLEN, b1);
	}
}

typedef int32_t vint __attribute__((vector_size(32)));
#define VSPLAT(x) ((vfloat){ 0 } + (x))

VECTOR_CLONES void flip_ycxcz_row(float *const rgb[3], int n, float *y, float *cx, float *cz, float *yn)
{
	const float(*to_xyz)[3] = flip_rgb_to_xyz;
	for (int e = 0; e < n; e += VLEN) {
		vfloat r = VLOAD(rgb[0] + e), g = VLOAD(rgb[1] + e), b = VLOAD(rgb[2] + e);
		/* linear RGB -> XYZ -> YCxCz (flip_linear_to_xyz, flip_xyz_to_ycxcz) */
		vfloat x = (to_xyz[0][0] * r + to_xyz[0][1] * g + to_xyz[0][2] * b) * white_d65_inv[0];
		vfloat yy = (to_xyz[1][0] * r + to_xyz[1][1] * g + to_xyz[1][2] * b) * white_d65_inv[1];
		vfloat z = (to_xyz[2][0] * r + to_xyz[2][1] * g + to_xyz[2][2] * b) * white_d65_inv[2];
		vfloat lum = 116.0f * yy - 16.0f;
		VSTORE(y + e, lum);
		VSTORE(cx + e, 500.0f * (x - yy));
		VSTORE(cz + e, 200.0f * (yy - z));
		/* the feature input: (Y + 16) / 116 in the reference's form */
		VSTORE(yn + e, lum * (1.0f / 116.0f) + (16.0f / 116.0f));
	}
}

VECTOR_CLONES void flip_colour_block(const float *const yc[2][4], float t[2][3][BLOCK], int32_t same[BLOCK])
{
	const float(*to_rgb)[3] = flip_xyz_to_rgb, (*to_xyz)[3] = flip_rgb_to_xyz;
	const vfloat zero = VSPLAT(0.0f), one = VSPLAT(1.0f);
	for (int e = 0; e < BLOCK; e += VLEN) {
		vfloat y[2], cx[2], cz[2];
		for (int i = 0; i < 2; i++) {
			y[i] = VLOAD(yc[i][0] + e);
			cx[i] = VLOAD(yc[i][1] + e);
			cz[i] = VLOAD(yc[i][2] + e) + VLOAD(yc[i][3] + e);
		}
		vint s = (y[0] == y[1]) & (cx[0] == cx[1]) & (cz[0] == cz[1]);
		memcpy(same + e, &s, sizeof s);
		for (int i = 0; i < 2; i++) {
			/* YCxCz -> XYZ (flip_ycxcz_to_xyz) */
			vfloat yn = (y[i] + 16.0f) / 116.0f, a = cx[i] / 500.0f, b = cz[i] / 200.0f;
			vfloat xyz[3] = { (yn + a) * white_d65[0], yn * white_d65[1], (yn - b) * white_d65[2] };
			/* -> linear RGB, clamped to [0,1] with NaN to 0 as the reference's clamp does */
			vfloat rgb[3];
			for (int c = 0; c < 3; c++) {
				vfloat v = to_rgb[c][0] * xyz[0] + to_rgb[c][1] * xyz[1] + to_rgb[c][2] * xyz[2];
				v = (vfloat)((vint)v & (v > zero));
				vint over = v > one;
				rgb[c] = (vfloat)(((vint)one & over) | ((vint)v & ~over));
			}
			/* -> XYZ, scaled by the inverse white point as flip_xyz_to_lab starts */
			for (int c = 0; c < 3; c++) {
				vfloat v = to_xyz[c][0] * rgb[0] + to_xyz[c][1] * rgb[1] + to_xyz[c][2] * rgb[2];
				VSTORE(&t[i][c][e], v * white_d65_inv[c]);
			}
		}
	}
}

VECTOR_CLONES void flip_lab_block(const float f[2][3][BLOCK], float dl[BLOCK], float dab2[BLOCK])
{
	const vint no_sign = (vint){ 0 } + 0x7fffffff;
	for (int e = 0; e < BLOCK; e += VLEN) {
		vfloat l[2], a[2], b[2];
		for (int i = 0; i < 2; i++) {
			vfloat fx = VLOAD(&f[i][0][e]), fy = VLOAD(&f[i][1][e]), fz = VLOAD(&f[i][2][e]);
			l[i] = 116.0f * fy - 16.0f;
			/* the Hunt adjustment scales the chroma by 0.01 L */
			a[i] = 0.01f * l[i] * (500.0f * (fx - fy));
			b[i] = 0.01f * l[i] * (200.0f * (fy - fz));
		}
		vfloat da = a[0] - a[1], db = b[0] - b[1];
		VSTORE(dl + e, (vfloat)((vint)(l[0] - l[1]) & no_sign));
		VSTORE(dab2 + e, da * da + db * db);
	}
}
