/* CPU images and file I/O. PNG goes through libpng (png_io.c); other formats through OpenImageIO in a
 * module loaded only when one is met (image_files.c, image_io.cc). */
#ifndef AA_IMAGE_H
#define AA_IMAGE_H

#include <stddef.h>
#include <stdint.h>

#include "util/error.h"

/* 8-bit RGBA, sRGB-encoded, straight (not premultiplied) alpha as PNG stores it, rows top to bottom,
 * tightly packed. */
struct aa_image_rgba8 {
	int width, height;
	uint8_t *pixels; /* width*height*4 */
};

/* Float RGBA, linear, rows top to bottom, tightly packed. */
struct aa_image_rgbaf {
	int width, height;
	float *pixels; /* width*height*4 */
};

int aa_image_rgba8_alloc(struct aa_image_rgba8 *img, int width, int height);
void aa_image_rgba8_free(struct aa_image_rgba8 *img);
int aa_image_rgbaf_alloc(struct aa_image_rgbaf *img, int width, int height);
void aa_image_rgbaf_free(struct aa_image_rgbaf *img);

/* sRGB transfer function (IEC 61966-2-1), on [0,1]. */
float aa_srgb_to_linear(float v);
float aa_linear_to_srgb(float v);
/* Linear float -> sRGB 8-bit with round-to-nearest; NaN maps to 0, values are clamped to [0,1]. */
void aa_image_encode_srgb8(const struct aa_image_rgbaf *in, struct aa_image_rgba8 *out);
/* One channel as aa_image_encode_srgb8 encodes it (a table), and by the definition (a pow): the same. */
uint8_t aa_srgb8_encode(float v);
uint8_t aa_srgb8_encode_exact(float v);

/* IEEE half floats (round to nearest even; overflow to infinity, NaN kept), for raw RGBA16F frames. */
uint16_t aa_float_to_half(float f);

/* Writes an 8-bit PNG (RGBA if any alpha < 255, else RGB). */
int aa_image_write_png(const char *path, const struct aa_image_rgba8 *img, struct aa_error *err);
/* Encodes a PNG into memory (for streaming); *data is malloc'ed. */
int aa_image_encode_png(const struct aa_image_rgba8 *img, uint8_t **data, size_t *size, struct aa_error *err);

/* Reads PNG, or any format OpenImageIO knows. 1 channel -> grey, 2 -> grey+alpha, 3 -> RGB, 4 -> RGBA;
 * other layouts are refused with AA_ERR_INVALID. read_rgba8 returns the file's stored values
 * (sRGB for PNG/JPEG); read_rgbaf returns float values as stored (linear for EXR/HDR; for 8-bit files
 * the stored value/255, not linearised). */
int aa_image_read_rgba8(const char *path, struct aa_image_rgba8 *out, struct aa_error *err);
int aa_image_read_rgbaf(const char *path, struct aa_image_rgbaf *out, int *channels_in_file,
			struct aa_error *err);
/* An image file held in memory (embedded in a glTF file), as aa_image_read_rgba8 reads files: PNG through
 * libpng from memory; other formats through OpenImageIO, from a temporary file named with the extension
 * `hint` ("jpg"). name is for messages. */
int aa_image_decode_rgba8(const void *data, size_t size, const char *name, const char *hint,
			  struct aa_image_rgba8 *out, struct aa_error *err);
/* Writes a float image (EXR when the path ends in .exr, otherwise as the extension says). */
int aa_image_write_rgbaf(const char *path, const struct aa_image_rgbaf *img, struct aa_error *err);

#endif
