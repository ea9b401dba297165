/* CPU image buffers and the sRGB transfer functions used to encode linear renders for display. */
#include "image/image.h"

#include <math.h>
#include <pthread.h>
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

/* The 8-bit sRGB code of a linear value, by definition. */
static uint8_t encode_channel_exact(float v)
{
	return quantize8(aa_linear_to_srgb((float)clamp01(v)));
}

/* The same codes without a pow per value: encode_channel_exact is non-decreasing in v, so code k starts
 * at threshold[k], the smallest float with that code (found by bisection over the float bit patterns of
 * [0, 1], which order like the floats). A bucket per 2^16 bit patterns gives the code at the bucket's
 * start, and a step or two up the thresholds finds v's. The same codes as the definition for every float
 * of [0, 1] (checked once, all 1.07e9 of them; tests/unit/test_metrics.c checks a sample and the code
 * boundaries). */
#define ONE_BITS 0x3f800000u
static float srgb8_threshold[257];
static uint8_t srgb8_bucket[(ONE_BITS >> 16) + 1];
static pthread_once_t srgb8_once = PTHREAD_ONCE_INIT;

static float float_of_bits(uint32_t bits)
{
	float f;
	memcpy(&f, &bits, sizeof f);
	return f;
}

static void srgb8_table_init(void)
{
	srgb8_threshold[0] = 0.0f;
	for (int k = 1; k <= 255; k++) {
		uint32_t lo = 0, hi = ONE_BITS; /* the first pattern whose code is >= k lies in (lo, hi] */
		while (hi - lo > 1) {
			uint32_t mid = lo + (hi - lo) / 2;
			if (encode_channel_exact(float_of_bits(mid)) >= k)
				hi = mid;
			else
				lo = mid;
		}
		srgb8_threshold[k] = float_of_bits(hi);
	}
	srgb8_threshold[256] = INFINITY;
	for (uint32_t b = 0; b <= (ONE_BITS >> 16); b++)
		srgb8_bucket[b] = encode_channel_exact(float_of_bits(b << 16));
}

static uint8_t encode_channel(float v)
{
	if (!(v > 0.0f))
		return 0; /* NaN, negatives and zero, as clamp01 */
	if (v >= 1.0f)
		return 255;
	uint32_t bits;
	memcpy(&bits, &v, sizeof bits);
	unsigned k = srgb8_bucket[bits >> 16];
	while (v >= srgb8_threshold[k + 1])
		k++;
	return (uint8_t)k;
}

uint8_t aa_srgb8_encode_exact(float v)
{
	return encode_channel_exact(v);
}

uint8_t aa_srgb8_encode(float v)
{
	pthread_once(&srgb8_once, srgb8_table_init);
	return encode_channel(v);
}

void aa_image_encode_srgb8(const struct aa_image_rgbaf *in, struct aa_image_rgba8 *out)
{
	pthread_once(&srgb8_once, srgb8_table_init);
	size_t n = (size_t)in->width * (size_t)in->height;
	for (size_t p = 0; p < n; p++) {
		const float *src = in->pixels + 4 * p;
		uint8_t *dst = out->pixels + 4 * p;
		for (int c = 0; c < 3; c++)
			dst[c] = encode_channel(src[c]);
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
