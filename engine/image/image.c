/* CPU image buffers and the sRGB transfer functions used to encode linear renders for display. */
#include "image.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Largest side we accept: keeps width*height*4 far from overflowing size_t and int arithmetic. */
#define AA_IMAGE_MAX_SIDE 32768

static size_t pixel_count(int width, int height)
{
	if (width <= 0 || height <= 0 || width > AA_IMAGE_MAX_SIDE || height > AA_IMAGE_MAX_SIDE)
		return 0;
	return (size_t)width * (size_t)height;
}

int aa_image_rgba8_alloc(struct aa_image_rgba8 *img, int width, int height)
{
	size_t n = pixel_count(width, height);
	img->width = img->height = 0;
	img->pixels = NULL;
	if (n == 0)
		return -1;
	img->pixels = calloc(n, 4);
	if (!img->pixels)
		return -1;
	img->width = width;
	img->height = height;
	return 0;
}

void aa_image_rgba8_free(struct aa_image_rgba8 *img)
{
	if (!img)
		return;
	free(img->pixels);
	img->pixels = NULL;
	img->width = img->height = 0;
}

int aa_image_rgbaf_alloc(struct aa_image_rgbaf *img, int width, int height)
{
	size_t n = pixel_count(width, height);
	img->width = img->height = 0;
	img->pixels = NULL;
	if (n == 0)
		return -1;
	img->pixels = calloc(n * 4, sizeof(float));
	if (!img->pixels)
		return -1;
	img->width = width;
	img->height = height;
	return 0;
}

void aa_image_rgbaf_free(struct aa_image_rgbaf *img)
{
	if (!img)
		return;
	free(img->pixels);
	img->pixels = NULL;
	img->width = img->height = 0;
}

/* Evaluated in double so that encode(decode(v)) returns v for every 8-bit value. */
float aa_srgb_to_linear(float v)
{
	double x = v;
	if (x <= 0.04045)
		return (float)(x / 12.92);
	return (float)pow((x + 0.055) / 1.055, 2.4);
}

float aa_linear_to_srgb(float v)
{
	double x = v;
	if (x <= 0.0031308)
		return (float)(x * 12.92);
	return (float)(1.055 * pow(x, 1.0 / 2.4) - 0.055);
}

/* NaN compares false everywhere, so test for "not >= 0" to send it to 0 together with negatives. */
static double clamp01(double x)
{
	if (!(x >= 0.0))
		return 0.0;
	return x > 1.0 ? 1.0 : x;
}

static uint8_t quantize8(double x)
{
	return (uint8_t)floor(clamp01(x) * 255.0 + 0.5);
}

void aa_image_encode_srgb8(const struct aa_image_rgbaf *in, struct aa_image_rgba8 *out)
{
	size_t n = (size_t)in->width * (size_t)in->height;
	for (size_t p = 0; p < n; p++) {
		const float *src = in->pixels + 4 * p;
		uint8_t *dst = out->pixels + 4 * p;
		for (int c = 0; c < 3; c++)
			dst[c] = quantize8(aa_linear_to_srgb((float)clamp01(src[c])));
		dst[3] = quantize8(src[3]); /* alpha is coverage, not a colour: no transfer function */
	}
}

uint16_t aa_float_to_half(float f)
{
	uint32_t x;
	memcpy(&x, &f, sizeof x);
	uint32_t sign = (x >> 16) & 0x8000u, exp = (x >> 23) & 0xffu, mant = x & 0x7fffffu;
	if (exp == 0xffu) /* Inf or NaN (keep a mantissa bit so NaN stays NaN) */
		return (uint16_t)(sign | 0x7c00u | (mant ? 0x200u : 0u));
	int e = (int)exp - 127 + 15;
	if (e >= 31)
		return (uint16_t)(sign | 0x7c00u);
	if (e <= 0) { /* subnormal half or zero */
		if (e < -10)
			return (uint16_t)sign;
		mant |= 0x800000u;
		uint32_t shift = (uint32_t)(14 - e);
		uint32_t half = mant >> shift, rest = mant & ((1u << shift) - 1), mid = 1u << (shift - 1);
		if (rest > mid || (rest == mid && (half & 1u)))
			half++;
		return (uint16_t)(sign | half);
	}
	uint32_t half = ((uint32_t)e << 10) | (mant >> 13), rest = mant & 0x1fffu;
	if (rest > 0x1000u || (rest == 0x1000u && (half & 1u)))
		half++; /* may carry into the exponent, which is right (up to infinity) */
	return (uint16_t)(sign | half);
}
