/* libFuzzer target: the image reader of `aalab diff` (aa_image_read_rgba8 and aa_image_read_rgbaf, as
 * --hdr uses it). The first input byte picks the file name's extension, the rest is the file. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "image/image.h"

static char dir[256];

static const char *const extensions[] = {"png", "exr", "jpg", "tif", "hdr", "ppm", "bmp", "tga"};

/* Reads one small PPM before the first input: the OpenImageIO module (aalab-oiio.so, hundreds of
 * libraries) is loaded once per process, and charged to whichever input first needs it, that input took
 * over 1 s and, under sanitizers on a loaded machine, hit the smoke's 20 s timeout. */
int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerInitialize(int *argc, char ***argv)
{
	(void)argc;
	(void)argv;
	char path[] = "/tmp/aalab-fuzz-image-init.XXXXXX";
	int fd = mkstemp(path);
	if (fd < 0)
		return 0;
	static const char ppm[] = "P6\n1 1\n255\n\x10\x20\x30";
	if (write(fd, ppm, sizeof ppm - 1) == (ssize_t)(sizeof ppm - 1)) {
		char named[64];
		snprintf(named, sizeof named, "%s.ppm", path);
		if (rename(path, named) == 0) {
			struct aa_image_rgba8 img = {0};
			struct aa_error err = {0};
			if (aa_image_read_rgba8(named, &img, &err) == 0)
				aa_image_rgba8_free(&img);
			unlink(named);
		}
	}
	close(fd);
	unlink(path);
	return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	if (!dir[0]) {
		const char *base = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
		snprintf(dir, sizeof dir, "%s/aalab-fuzz-image.XXXXXX", base);
		if (!mkdtemp(dir))
			abort();
	}
	if (size < 1)
		return 0;
	const char *ext = extensions[data[0] % (sizeof extensions / sizeof extensions[0])];
	char path[320];
	snprintf(path, sizeof path, "%s/image.%s", dir, ext);
	FILE *f = fopen(path, "wb");
	if (!f)
		abort();
	fwrite(data + 1, 1, size - 1, f);
	fclose(f);
	struct aa_error err = {0};
	if (data[0] & 0x80) {
		struct aa_image_rgbaf img = {0};
		int channels = 0;
		if (aa_image_read_rgbaf(path, &img, &channels, &err) == 0)
			aa_image_rgbaf_free(&img);
	} else {
		struct aa_image_rgba8 img = {0};
		if (aa_image_read_rgba8(path, &img, &err) == 0)
			aa_image_rgba8_free(&img);
	}
	unlink(path);
	return 0;
}
