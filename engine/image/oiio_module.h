/* The C interface of aalab-oiio.so, the OpenImageIO module (image_io.cc). aalab loads it with dlopen only
 * when a file is not a PNG (image_files.c), so commands that never meet another format do not pay for
 * OpenImageIO's ~260 shared libraries at start-up. The module calls nothing in aalab: errors are written
 * into the caller's struct aa_error, pixels are malloc'ed for the caller to free. */
#ifndef AA_OIIO_MODULE_H
#define AA_OIIO_MODULE_H

#include "util/error.h"

#define AA_OIIO_MODULE_FILE "aalab-oiio.so"
#define AA_OIIO_MODULE_SYMBOL "aa_oiio_module"
#define AA_OIIO_MODULE_VERSION 1

/* Subimage 0 of a file as stored: width*height*channels values, uint8 or float, tightly packed. */
struct aa_file_pixels {
	int width, height, channels;
	void *data; /* malloc'ed */
};

struct aa_oiio_module {
	int version; /* AA_OIIO_MODULE_VERSION */
	/* 0, or -1 with err set; channels 1..4 only, sides 1..32768 */
	int (*read)(const char *path, int as_float, struct aa_file_pixels *out, struct aa_error *err);
	/* RGBA float pixels in the format the extension names (EXR keeps floats; 8-bit formats clamp). */
	int (*write_rgbaf)(const char *path, int width, int height, const float *rgba, struct aa_error *err);
};

#endif
