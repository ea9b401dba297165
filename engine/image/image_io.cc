// aalab-oiio.so: image files through OpenImageIO, behind the C interface of oiio_module.h (the only C++ in
// aalab). Loaded by image_files.c only for files that are not PNG.
#include <OpenImageIO/imageio.h>

#include <cerrno>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <sys/stat.h>

extern "C" {
#include "image/oiio_module.h"
}

using OIIO::ImageInput;
using OIIO::ImageOutput;
using OIIO::ImageSpec;
using OIIO::TypeDesc;

namespace {

// The same bound as image.c, so a hostile header cannot ask for a huge allocation.
constexpr int max_side = 32768;

// aa_error_set (error.c) for the module, which links nothing of aalab.
__attribute__((format(printf, 3, 4))) int set_error(struct aa_error *err, enum aa_error_code code,
							 const char *fmt, ...)
{
	if (err) {
		err->code = code;
		err->path[0] = '\0';
		va_list ap;
		va_start(ap, fmt);
		vsnprintf(err->message, sizeof err->message, fmt, ap);
		va_end(ap);
	}
	return -1;
}

// OIIO keeps the last error per thread; fetch it (and clear it) so messages do not leak into later calls.
std::string oiio_message(const std::string &from_object)
{
	std::string msg = from_object.empty() ? OIIO::geterror() : from_object;
	while (!msg.empty() && (msg.back() == '\n' || msg.back() == ' '))
		msg.pop_back();
	return msg.empty() ? std::string("unknown OpenImageIO error") : msg;
}

int open_error(const char *path, struct aa_error *err)
{
	struct stat st;
	if (stat(path, &st) != 0 && errno == ENOENT)
		return set_error(err, AA_ERR_NOT_FOUND, "image file '%s' does not exist", path);
	std::string msg = oiio_message("");
	return set_error(err, AA_ERR_IO, "cannot read image '%s': %s", path, msg.c_str());
}

// OpenImageIO 2.4 (Debian 12) reads past its buffers on a BMP whose compression does not fit its bit
// depth (RLE8 at 24 bits per pixel crashed it: found by tests/fuzz/fuzz_image). Such files are refused
// before OpenImageIO sees them, whatever their name: it picks readers by content too.
int check_bmp_header(const char *path, struct aa_error *err)
{
	unsigned char h[34];
	FILE *f = fopen(path, "rb");
	size_t n = f ? fread(h, 1, sizeof h, f) : 0;
	if (f)
		fclose(f);
	if (n < 2 || h[0] != 'B' || h[1] != 'M')
		return 0; /* not a BMP */
	if (n < sizeof h)
		return set_error(err, AA_ERR_INVALID, "image '%s' is a BMP cut short (%zu bytes)", path, n);
	unsigned dib = h[14] | h[15] << 8 | h[16] << 16 | (unsigned)h[17] << 24;
	if (dib < 40)
		return 0; /* OS/2 headers have no compression field */
	unsigned bpp = h[28] | h[29] << 8;
	unsigned compression = h[30] | h[31] << 8 | h[32] << 16 | (unsigned)h[33] << 24;
	bool ok = (compression == 0 && (bpp == 1 || bpp == 4 || bpp == 8 || bpp == 16 || bpp == 24 || bpp == 32)) ||
		  (compression == 1 && bpp == 8) || (compression == 2 && bpp == 4) ||
		  (compression == 3 && (bpp == 16 || bpp == 32));
	if (!ok)
		return set_error(err, AA_ERR_INVALID, "image '%s' is a BMP with %u bits per pixel and compression %u, "
				 "a combination that is not valid BMP; refused", path, bpp, compression);
	return 0;
}

// Opens a file and checks that its first subimage is a flat 2D image with 1 to 4 channels.
int open_input(const char *path, std::unique_ptr<ImageInput> &in, struct aa_error *err)
{
	if (check_bmp_header(path, err))
		return -1;
	// PNG stores straight alpha; without this hint OIIO premultiplies colours by alpha while reading.
	ImageSpec config;
	config.attribute("oiio:UnassociatedAlpha", 1);
	in = ImageInput::open(path, &config);
	if (!in)
		return open_error(path, err);
	const ImageSpec &spec = in->spec();
	if (spec.nchannels < 1 || spec.nchannels > 4)
		return set_error(err, AA_ERR_INVALID,
				    "image '%s' has %d channels; only grey, grey+alpha, RGB and RGBA are supported",
				    path, spec.nchannels);
	if (spec.depth > 1 || spec.deep)
		return set_error(err, AA_ERR_INVALID, "image '%s' is a volume or deep image", path);
	if (spec.width < 1 || spec.height < 1 || spec.width > max_side || spec.height > max_side)
		return set_error(err, AA_ERR_INVALID,
				    "image '%s' is %dx%d; sides must be 1..%d pixels", path, spec.width,
				    spec.height, max_side);
	return 0;
}

bool valid_image(int width, int height, const void *pixels)
{
	return pixels && width > 0 && height > 0 && width <= max_side && height <= max_side;
}

// Reads subimage 0 with all its channels, as uint8 or float.
int module_read(const char *path, int as_float, struct aa_file_pixels *out, struct aa_error *err)
{
	*out = aa_file_pixels{};
	std::unique_ptr<ImageInput> in;
	if (open_input(path, in, err) != 0)
		return -1;
	const ImageSpec spec = in->spec();
	size_t values = (size_t)spec.width * spec.height * spec.nchannels;
	void *data = malloc(values * (as_float ? sizeof(float) : 1));
	if (!data)
		return set_error(err, AA_ERR_LIMIT, "out of memory for image '%s' (%dx%d)", path, spec.width,
				    spec.height);
	if (!in->read_image(0, 0, 0, spec.nchannels, as_float ? TypeDesc::FLOAT : TypeDesc::UINT8, data)) {
		free(data);
		std::string msg = oiio_message(in->geterror());
		return set_error(err, AA_ERR_IO, "cannot read pixels of '%s': %s", path, msg.c_str());
	}
	*out = aa_file_pixels{spec.width, spec.height, spec.nchannels, data};
	return 0;
}

int module_write_rgbaf(const char *path, int width, int height, const float *rgba, struct aa_error *err)
{
	if (!valid_image(width, height, rgba))
		return set_error(err, AA_ERR_INVALID, "cannot write '%s': empty image", path);
	auto out = ImageOutput::create(path);
	if (!out)
		return set_error(err, AA_ERR_IO, "cannot write '%s': %s", path, oiio_message("").c_str());
	// Formats without float pixels (PNG, JPEG) are converted by OIIO, clamped to [0,1].
	ImageSpec spec(width, height, 4, TypeDesc::FLOAT);
	spec.attribute("oiio:ColorSpace", "Linear");
	if (!out->open(path, spec))
		return set_error(err, AA_ERR_IO, "cannot write '%s': %s", path,
				    oiio_message(out->geterror()).c_str());
	bool ok = out->write_image(TypeDesc::FLOAT, rgba);
	std::string error = ok ? "" : oiio_message(out->geterror());
	if (!out->close() && ok) {
		error = oiio_message(out->geterror());
		ok = false;
	}
	if (!ok)
		return set_error(err, AA_ERR_IO, "cannot write '%s': %s", path, error.c_str());
	return 0;
}

} // namespace

extern "C" {
extern const struct aa_oiio_module aa_oiio_module;
const struct aa_oiio_module aa_oiio_module = {AA_OIIO_MODULE_VERSION, module_read, module_write_rgbaf};
}
