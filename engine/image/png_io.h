/* PNG files and memory through libpng: the format aalab writes and reads most, without OpenImageIO. */
#ifndef AA_PNG_IO_H
#define AA_PNG_IO_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "image/image.h"
#include "image/oiio_module.h"

/* True when the file starts with the PNG signature; false for any other content or a read error. */
bool aa_png_file_is_png(const char *path);
/* Reads a PNG as stored: grey, grey+alpha, RGB or RGBA (palettes expand to RGB, or RGBA with a tRNS
 * chunk; 1, 2 and 4-bit grey to 8 bits), as uint8 (16-bit samples rounded to 8 bits) or as float
 * (value x (1 / maximum), as OpenImageIO converts: the same floats). */
int aa_png_read(const char *path, bool as_float, struct aa_file_pixels *out, struct aa_error *err);
/* The same from bytes in memory (images embedded in glTF files); name is for messages. */
bool aa_png_memory_is_png(const void *data, size_t size);
int aa_png_read_memory(const void *data, size_t size, const char *name, bool as_float, struct aa_file_pixels *out,
		       struct aa_error *err);
/* 8-bit PNG of img: RGB when every alpha is 255, else RGBA. */
int aa_png_write(const char *path, const struct aa_image_rgba8 *img, struct aa_error *err);
int aa_png_encode(const struct aa_image_rgba8 *img, uint8_t **data, size_t *size, struct aa_error *err);

#endif
