/* PNG through libpng (png_io.h). Errors from libpng arrive through a longjmp to the setjmp in each
 * function; everything those functions change after setjmp is volatile or freed by the cleanup there. */
#include "image/png_io.h"
#include "util/file_open.h"

#include <errno.h>
#include <png.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#define AA_PNG_MAX_SIDE 32768 /* as image.c: a hostile header cannot ask for a huge allocation */

struct png_context {
	char message[256]; /* libpng's error, for ours */
};

static void png_error_to_context(png_structp png, png_const_charp message)
{
	struct png_context *ctx = png_get_error_ptr(png);
	snprintf(ctx->message, sizeof ctx->message, "%s", message);
	png_longjmp(png, 1);
}

static void png_warning_ignored(png_structp png, png_const_charp message)
{
	(void)png;
	(void)message;
}

bool aa_png_file_is_png(const char *path)
{
	unsigned char signature[8];
	FILE *f = aa_file_fopen_regular(path, "", NULL); /* never blocks on a FIFO */
	if (!f)
		return false;
	bool png = fread(signature, 1, sizeof signature, f) == sizeof signature &&
		   png_sig_cmp(signature, 0, sizeof signature) == 0;
	fclose(f);
	return png;
}

static int png_read_stream(FILE *f, const char *path, bool as_float, struct aa_file_pixels *out,
			   struct aa_error *err);

int aa_png_read(const char *path, bool as_float, struct aa_file_pixels *out, struct aa_error *err)
{
	memset(out, 0, sizeof *out);
	FILE *f = aa_file_fopen_regular(path, "", err); /* never blocks on a FIFO */
	if (!f)
		return err && err->code == AA_ERR_NOT_FOUND ?
			aa_error_set(err, AA_ERR_NOT_FOUND, "", "image file '%s' does not exist", path) : -1;
	return png_read_stream(f, path, as_float, out, err);
}

bool aa_png_memory_is_png(const void *data, size_t size)
{
	return size >= 8 && png_sig_cmp((png_const_bytep)data, 0, 8) == 0;
}

int aa_png_read_memory(const void *data, size_t size, const char *name, bool as_float, struct aa_file_pixels *out,
		       struct aa_error *err)
{
	memset(out, 0, sizeof *out);
	/* libpng reads from a FILE: one over the bytes, so that files and memory share every step */
	FILE *f = size ? fmemopen((void *)data, size, "rb") : NULL;
	if (!f)
		return aa_error_set(err, AA_ERR_IO, "", "cannot read PNG '%s': %s", name,
				    size ? strerror(errno) : "no data");
	return png_read_stream(f, name, as_float, out, err);
}

/* Reads a PNG from f (closed here); path names it in messages. */
static int png_read_stream(FILE *f, const char *path, bool as_float, struct aa_file_pixels *out,
			   struct aa_error *err)
{
	memset(out, 0, sizeof *out);
	struct png_context ctx = {""};
	png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &ctx, png_error_to_context,
						 png_warning_ignored);
	png_infop info = png ? png_create_info_struct(png) : NULL;
	uint8_t *volatile rows_data = NULL;
	png_bytep *volatile rows = NULL;
	void *volatile data = NULL;
	if (!info) {
		png_destroy_read_struct(png ? &png : NULL, NULL, NULL);
		fclose(f);
		return aa_error_set(err, AA_ERR_LIMIT, "", "out of memory reading '%s'", path);
	}
	if (setjmp(png_jmpbuf(png))) {
		png_destroy_read_struct(&png, &info, NULL);
		fclose(f);
		free(rows_data);
		free(rows);
		free(data);
		return aa_error_set(err, AA_ERR_IO, "", "cannot read PNG '%s': %s", path, ctx.message);
	}
	png_init_io(png, f);
	png_set_user_limits(png, AA_PNG_MAX_SIDE, AA_PNG_MAX_SIDE);
	png_read_info(png, info);
	int color_type = png_get_color_type(png, info), depth = png_get_bit_depth(png, info);
	if (color_type == PNG_COLOR_TYPE_PALETTE)
		png_set_palette_to_rgb(png);
	if (color_type == PNG_COLOR_TYPE_GRAY && depth < 8)
		png_set_expand_gray_1_2_4_to_8(png);
	if (png_get_valid(png, info, PNG_INFO_tRNS))
		png_set_tRNS_to_alpha(png);
#if __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
	if (depth == 16)
		png_set_swap(png); /* PNG is big-endian; host order for the uint16 reads below */
#endif
	png_set_interlace_handling(png);
	png_read_update_info(png, info);
	int width = (int)png_get_image_width(png, info), height = (int)png_get_image_height(png, info);
	int channels = png_get_channels(png, info);
	int bytes_per_sample = png_get_bit_depth(png, info) == 16 ? 2 : 1;
	size_t row_bytes = png_get_rowbytes(png, info);
	if (channels < 1 || channels > 4 || row_bytes != (size_t)width * channels * bytes_per_sample)
		png_error(png, "unsupported pixel layout");
	rows_data = malloc(row_bytes * (size_t)height);
	rows = malloc(sizeof(png_bytep) * (size_t)height);
	size_t values = (size_t)width * height * channels;
	data = malloc(values * (as_float ? sizeof(float) : 1));
	if (!rows_data || !rows || !data)
		png_error(png, "out of memory");
	for (int y = 0; y < height; y++)
		rows[y] = rows_data + row_bytes * (size_t)y;
	png_read_image(png, rows);
	png_read_end(png, NULL);
	if (bytes_per_sample == 2) {
		const uint16_t *s = (const uint16_t *)rows_data;
		for (size_t i = 0; i < values; i++) {
			if (as_float)
				((float *)data)[i] = (float)s[i] * (1.0f / 65535.0f);
			else /* the nearest 8-bit value: v * 255 / 65535, rounded */
				((uint8_t *)data)[i] = (uint8_t)(((uint32_t)s[i] * 255u + 32767u) / 65535u);
		}
	} else if (as_float) {
		for (size_t i = 0; i < values; i++)
			((float *)data)[i] = (float)rows_data[i] * (1.0f / 255.0f);
	} else {
		memcpy(data, rows_data, values);
	}
	png_destroy_read_struct(&png, &info, NULL);
	fclose(f);
	free(rows_data);
	free(rows);
	*out = (struct aa_file_pixels){width, height, channels, data};
	return 0;
}

static bool opaque(const struct aa_image_rgba8 *img)
{
	size_t n = (size_t)img->width * img->height;
	for (size_t p = 0; p < n; p++)
		if (img->pixels[4 * p + 3] != 255)
			return false;
	return true;
}

struct png_memory {
	uint8_t *data;
	size_t size, capacity;
	bool failed;
};

static void png_write_to_memory(png_structp png, png_bytep bytes, png_size_t length)
{
	struct png_memory *m = png_get_io_ptr(png);
	if (m->failed)
		return;
	if (m->size + length > m->capacity) {
		size_t capacity = m->capacity ? m->capacity : 65536;
		while (capacity < m->size + length)
			capacity *= 2;
		uint8_t *grown = realloc(m->data, capacity);
		if (!grown) {
			m->failed = true;
			return;
		}
		m->data = grown;
		m->capacity = capacity;
	}
	memcpy(m->data + m->size, bytes, length);
	m->size += length;
}

static void png_flush_nothing(png_structp png)
{
	(void)png;
}

/* Writes img to a file (f) or to memory (m). RGB when opaque: smaller files. */
static int write_png(FILE *f, struct png_memory *m, const struct aa_image_rgba8 *img, char *message,
		     size_t message_size)
{
	struct png_context ctx = {""};
	png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &ctx, png_error_to_context,
						  png_warning_ignored);
	png_infop info = png ? png_create_info_struct(png) : NULL;
	png_bytep *volatile rows = NULL;
	if (!info) {
		png_destroy_write_struct(png ? &png : NULL, NULL);
		snprintf(message, message_size, "out of memory");
		return -1;
	}
	if (setjmp(png_jmpbuf(png))) {
		png_destroy_write_struct(&png, &info);
		free(rows);
		snprintf(message, message_size, "%s", ctx.message);
		return -1;
	}
	if (f)
		png_init_io(png, f);
	else
		png_set_write_fn(png, m, png_write_to_memory, png_flush_nothing);
	/* Frames, difference images and FLIP maps are written every frame of every job: one fixed filter
	 * rather than libpng's search over all five per row, and run-length matches only. Sub with Z_RLE
	 * encodes rendered frames, differences and maps about twice as fast as Paeth at zlib level 3, in
	 * files of about the same total size (docs/benchmarks.md). */
	png_set_compression_level(png, 1);
	png_set_compression_strategy(png, Z_RLE);
	png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
	bool rgb = opaque(img);
	png_set_IHDR(png, info, (png_uint_32)img->width, (png_uint_32)img->height, 8,
		     rgb ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_RGBA, PNG_INTERLACE_NONE,
		     PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
	png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
	png_write_info(png, info);
	if (rgb)
		png_set_filler(png, 0, PNG_FILLER_AFTER); /* drop the alpha byte of our 4-byte pixels */
	rows = malloc(sizeof(png_bytep) * (size_t)img->height);
	if (!rows)
		png_error(png, "out of memory");
	for (int y = 0; y < img->height; y++)
		rows[y] = img->pixels + (size_t)y * img->width * 4;
	png_write_image(png, rows);
	png_write_end(png, NULL);
	png_destroy_write_struct(&png, &info);
	free(rows);
	if (m && m->failed) {
		snprintf(message, message_size, "out of memory");
		return -1;
	}
	return 0;
}

static bool valid_image(const struct aa_image_rgba8 *img)
{
	return img->pixels && img->width > 0 && img->height > 0 && img->width <= AA_PNG_MAX_SIDE &&
	       img->height <= AA_PNG_MAX_SIDE;
}

int aa_png_write(const char *path, const struct aa_image_rgba8 *img, struct aa_error *err)
{
	if (!valid_image(img))
		return aa_error_set(err, AA_ERR_INVALID, "", "cannot write '%s': empty image", path);
	FILE *f = fopen(path, "wb");
	if (!f)
		return aa_error_set(err, AA_ERR_IO, "", "cannot write PNG '%s': %s", path, strerror(errno));
	char message[256];
	int rc = write_png(f, NULL, img, message, sizeof message);
	if (fclose(f) != 0 && rc == 0) {
		snprintf(message, sizeof message, "%s", strerror(errno));
		rc = -1;
	}
	if (rc) {
		remove(path);
		return aa_error_set(err, AA_ERR_IO, "", "cannot write PNG '%s': %s", path, message);
	}
	return 0;
}

int aa_png_encode(const struct aa_image_rgba8 *img, uint8_t **data, size_t *size, struct aa_error *err)
{
	*data = NULL;
	*size = 0;
	if (!valid_image(img))
		return aa_error_set(err, AA_ERR_INVALID, "", "cannot encode an empty image as PNG");
	struct png_memory m = {0};
	char message[256];
	if (write_png(NULL, &m, img, message, sizeof message)) {
		free(m.data);
		return aa_error_set(err, AA_ERR_IO, "", "cannot encode PNG: %s", message);
	}
	*data = m.data;
	*size = m.size;
	return 0;
}
