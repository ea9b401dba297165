/* Image files (image.h): PNG through libpng (png_io.c); every other format through OpenImageIO in
 * aalab-oiio.so (image_io.cc), loaded with dlopen the first time a file is not a PNG. */
#include "image/image.h"

#include <dlfcn.h>
#include <errno.h>
#include <limits.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "image/oiio_module.h"
#include "image/png_io.h"
#include "util/file_open.h"

static pthread_mutex_t module_lock = PTHREAD_MUTEX_INITIALIZER;
static const struct aa_oiio_module *module;
static char module_error[512];

/* The module: $AALAB_OIIO_MODULE, else beside the executable (a build tree), else the build tree this
 * was compiled in (tests in its subdirectories), else where it is installed (pkglibexecdir). */
static const struct aa_oiio_module *load_module(void)
{
	char here[PATH_MAX] = "", candidates[4][PATH_MAX + 32];
	int n = 0;
	const char *env = getenv("AALAB_OIIO_MODULE");
	if (env && *env)
		snprintf(candidates[n++], sizeof candidates[0], "%s", env);
	ssize_t len = readlink("/proc/self/exe", here, sizeof here - 1);
	if (len > 0) {
		here[len] = '\0';
		char *slash = strrchr(here, '/');
		if (slash) {
			*slash = '\0';
			snprintf(candidates[n++], sizeof candidates[0], "%s/%s", here, AA_OIIO_MODULE_FILE);
		}
	}
#ifdef AA_BUILD_DIR
	snprintf(candidates[n++], sizeof candidates[0], "%s/%s", AA_BUILD_DIR, AA_OIIO_MODULE_FILE);
#endif
#ifdef AA_MODULE_DIR
	snprintf(candidates[n++], sizeof candidates[0], "%s/%s", AA_MODULE_DIR, AA_OIIO_MODULE_FILE);
#endif
	snprintf(module_error, sizeof module_error, "%s was not found", AA_OIIO_MODULE_FILE);
	for (int i = 0; i < n; i++) {
		struct stat st;
		if (stat(candidates[i], &st) != 0)
			continue;
		void *handle = dlopen(candidates[i], RTLD_NOW | RTLD_LOCAL);
		if (!handle) {
			snprintf(module_error, sizeof module_error, "%s", dlerror());
			continue;
		}
		const struct aa_oiio_module *m = dlsym(handle, AA_OIIO_MODULE_SYMBOL);
		if (m && m->version == AA_OIIO_MODULE_VERSION)
			return m; /* kept loaded for the life of the process */
		snprintf(module_error, sizeof module_error, "%.300s is not a compatible %s", candidates[i],
			 AA_OIIO_MODULE_FILE);
		dlclose(handle);
	}
	return NULL;
}

static const struct aa_oiio_module *oiio(const char *path, struct aa_error *err)
{
	pthread_mutex_lock(&module_lock);
	if (!module)
		module = load_module();
	const struct aa_oiio_module *m = module;
	pthread_mutex_unlock(&module_lock);
	if (!m)
		aa_error_set(err, AA_ERR_IO, "", "image '%s' is not a PNG and needs OpenImageIO, which could not "
			     "be loaded (%s)", path, module_error);
	return m;
}

/* Subimage 0 as stored, from libpng for PNG content, else from OpenImageIO. */
static int read_pixels(const char *path, bool as_float, struct aa_file_pixels *px, struct aa_error *err)
{
	/* checked before any library opens it: a FIFO or a device would block the reader for good */
	int fd = aa_file_open_regular(path, "", err);
	if (fd < 0)
		return err && err->code == AA_ERR_NOT_FOUND ?
			aa_error_set(err, AA_ERR_NOT_FOUND, "", "image file '%s' does not exist", path) : -1;
	close(fd);
	if (aa_png_file_is_png(path))
		return aa_png_read(path, as_float, px, err);
	const struct aa_oiio_module *m = oiio(path, err);
	return m ? m->read(path, as_float, px, err) : -1;
}

/* Expands 1..4 stored channels to RGBA: grey fills R,G,B; a missing alpha becomes opaque. */
#define EXPAND_TO_RGBA(T, src, nchannels, pixels, opaque, dst)                                           \
	do {                                                                                              \
		const T *s_ = (src);                                                                      \
		T *d_ = (dst);                                                                            \
		for (size_t p_ = 0; p_ < (pixels); p_++, s_ += (nchannels), d_ += 4) {                    \
			bool grey_ = (nchannels) <= 2;                                                    \
			d_[0] = s_[0];                                                                    \
			d_[1] = grey_ ? s_[0] : s_[1];                                                    \
			d_[2] = grey_ ? s_[0] : s_[2];                                                    \
			d_[3] = (nchannels) == 2 ? s_[1] : (nchannels) == 4 ? s_[3] : (opaque);           \
		}                                                                                         \
	} while (0)

int aa_image_read_rgba8(const char *path, struct aa_image_rgba8 *out, struct aa_error *err)
{
	out->width = out->height = 0;
	out->pixels = NULL;
	struct aa_file_pixels px;
	if (read_pixels(path, false, &px, err))
		return -1;
	int rc = 0;
	if (aa_image_rgba8_alloc(out, px.width, px.height) != 0)
		rc = aa_error_set(err, AA_ERR_LIMIT, "", "out of memory for image '%s' (%dx%d)", path, px.width,
				  px.height);
	else
		EXPAND_TO_RGBA(uint8_t, px.data, px.channels, (size_t)px.width * px.height, 255, out->pixels);
	free(px.data);
	return rc;
}

int aa_image_decode_rgba8(const void *data, size_t size, const char *name, const char *hint,
			  struct aa_image_rgba8 *out, struct aa_error *err)
{
	out->width = out->height = 0;
	out->pixels = NULL;
	struct aa_file_pixels px;
	if (aa_png_memory_is_png(data, size)) {
		if (aa_png_read_memory(data, size, name, false, &px, err))
			return -1;
	} else {
		/* OpenImageIO reads files: a private temporary one, removed at once */
		char tmp[PATH_MAX], ext[16] = "";
		const char *dir = getenv("TMPDIR");
		for (size_t i = 0; hint && hint[i] && i < 8; i++) /* letters and digits only */
			if ((hint[i] >= 'a' && hint[i] <= 'z') || (hint[i] >= '0' && hint[i] <= '9'))
				snprintf(ext + strlen(ext), sizeof ext - strlen(ext), "%s%c", ext[0] ? "" : ".", hint[i]);
		snprintf(tmp, sizeof tmp, "%s/aalab-image-XXXXXX%s", dir && dir[0] ? dir : "/tmp", ext);
		int fd = mkstemps(tmp, (int)strlen(ext));
		if (fd < 0)
			return aa_error_set(err, AA_ERR_IO, "", "cannot decode image '%s': no temporary file (%s)", name,
					    strerror(errno));
		bool written = write(fd, data, size) == (ssize_t)size;
		close(fd);
		int rc = written ? read_pixels(tmp, false, &px, err) : -1;
		unlink(tmp);
		if (!written)
			return aa_error_set(err, AA_ERR_IO, "", "cannot decode image '%s': writing a temporary file failed",
					    name);
		if (rc) {
			/* the message names the temporary file: name the image instead */
			char msg[sizeof err->message];
			snprintf(msg, sizeof msg, "%s", err->message);
			return aa_error_set(err, err->code ? err->code : AA_ERR_IO, "", "cannot decode image '%s' (%s): %s",
					    name, hint && hint[0] ? hint : "unknown format", msg);
		}
	}
	int rc = 0;
	if (aa_image_rgba8_alloc(out, px.width, px.height) != 0)
		rc = aa_error_set(err, AA_ERR_LIMIT, "", "out of memory for image '%s' (%dx%d)", name, px.width,
				  px.height);
	else
		EXPAND_TO_RGBA(uint8_t, px.data, px.channels, (size_t)px.width * px.height, 255, out->pixels);
	free(px.data);
	return rc;
}

int aa_image_read_rgbaf(const char *path, struct aa_image_rgbaf *out, int *channels_in_file,
			struct aa_error *err)
{
	out->width = out->height = 0;
	out->pixels = NULL;
	struct aa_file_pixels px;
	if (read_pixels(path, true, &px, err))
		return -1;
	int rc = 0;
	if (aa_image_rgbaf_alloc(out, px.width, px.height) != 0)
		rc = aa_error_set(err, AA_ERR_LIMIT, "", "out of memory for image '%s' (%dx%d)", path, px.width,
				  px.height);
	else
		EXPAND_TO_RGBA(float, px.data, px.channels, (size_t)px.width * px.height, 1.0f, out->pixels);
	if (rc == 0 && channels_in_file)
		*channels_in_file = px.channels;
	free(px.data);
	return rc;
}

int aa_image_write_png(const char *path, const struct aa_image_rgba8 *img, struct aa_error *err)
{
	return aa_png_write(path, img, err);
}

int aa_image_encode_png(const struct aa_image_rgba8 *img, uint8_t **data, size_t *size, struct aa_error *err)
{
	return aa_png_encode(img, data, size, err);
}

int aa_image_write_rgbaf(const char *path, const struct aa_image_rgbaf *img, struct aa_error *err)
{
	const struct aa_oiio_module *m = oiio(path, err);
	return m ? m->write_rgbaf(path, img->width, img->height, img->pixels, err) : -1;
}
