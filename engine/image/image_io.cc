// Image files through OpenImageIO, behind the C interface declared in image.h (the only C++ in aalab).
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <sys/stat.h>

extern "C" {
#include "image.h"
}

using OIIO::ImageInput;
using OIIO::ImageOutput;
using OIIO::ImageSpec;
using OIIO::TypeDesc;

namespace {

// The same bound as image.c, so a hostile header cannot ask for a huge allocation.
constexpr int max_side = 32768;

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
		return aa_error_set(err, AA_ERR_NOT_FOUND, "", "image file '%s' does not exist", path);
	std::string msg = oiio_message("");
	return aa_error_set(err, AA_ERR_IO, "", "cannot read image '%s': %s", path, msg.c_str());
}

// Opens a file and checks that its first subimage is a flat 2D image with 1 to 4 channels.
int open_input(const char *path, std::unique_ptr<ImageInput> &in, struct aa_error *err)
{
	// PNG stores straight alpha; without this hint OIIO premultiplies colours by alpha while reading.
	ImageSpec config;
	config.attribute("oiio:UnassociatedAlpha", 1);
	in = ImageInput::open(path, &config);
	if (!in)
		return open_error(path, err);
	const ImageSpec &spec = in->spec();
	if (spec.nchannels < 1 || spec.nchannels > 4)
		return aa_error_set(err, AA_ERR_INVALID, "",
				    "image '%s' has %d channels; only grey, grey+alpha, RGB and RGBA are supported",
				    path, spec.nchannels);
	if (spec.depth > 1 || spec.deep)
		return aa_error_set(err, AA_ERR_INVALID, "", "image '%s' is a volume or deep image", path);
	if (spec.width < 1 || spec.height < 1 || spec.width > max_side || spec.height > max_side)
		return aa_error_set(err, AA_ERR_INVALID, "",
				    "image '%s' is %dx%d; sides must be 1..%d pixels", path, spec.width,
				    spec.height, max_side);
	return 0;
}

// Reads all channels of subimage 0 as `format` into a tightly packed buffer of nchannels per pixel.
template <typename T>
int read_channels(const char *path, ImageInput &in, TypeDesc format, std::vector<T> &data,
		  struct aa_error *err)
{
	const ImageSpec &spec = in.spec();
	data.resize((size_t)spec.width * spec.height * spec.nchannels);
	if (!in.read_image(0, 0, 0, spec.nchannels, format, data.data())) {
		std::string msg = oiio_message(in.geterror());
		return aa_error_set(err, AA_ERR_IO, "", "cannot read pixels of '%s': %s", path, msg.c_str());
	}
	return 0;
}

// Expands 1..4 stored channels to RGBA: grey fills R,G,B; a missing alpha becomes opaque.
template <typename T>
void expand_to_rgba(const T *src, int nchannels, size_t pixels, T opaque, T *dst)
{
	for (size_t p = 0; p < pixels; p++, src += nchannels, dst += 4) {
		bool grey = nchannels <= 2;
		dst[0] = src[0];
		dst[1] = grey ? src[0] : src[1];
		dst[2] = grey ? src[0] : src[2];
		if (nchannels == 2)
			dst[3] = src[1];
		else if (nchannels == 4)
			dst[3] = src[3];
		else
			dst[3] = opaque;
	}
}

bool has_transparency(const struct aa_image_rgba8 *img)
{
	size_t n = (size_t)img->width * img->height;
	for (size_t p = 0; p < n; p++)
		if (img->pixels[4 * p + 3] != 255)
			return true;
	return false;
}

// Writes img as PNG to an already created output; RGB when fully opaque, which makes files smaller.
bool write_png_pixels(ImageOutput &out, const char *name, const struct aa_image_rgba8 *img,
		      std::string &error)
{
	int channels = has_transparency(img) ? 4 : 3;
	ImageSpec spec(img->width, img->height, channels, TypeDesc::UINT8);
	spec.attribute("oiio:ColorSpace", "sRGB");
	// Our pixels hold straight alpha, as PNG does; otherwise OIIO would divide the colours by alpha.
	spec.attribute("oiio:UnassociatedAlpha", 1);
	if (!out.open(name, spec)) {
		error = oiio_message(out.geterror());
		return false;
	}
	// A 4-byte pixel stride lets OIIO drop the alpha byte without a copy.
	bool ok = out.write_image(TypeDesc::UINT8, img->pixels, 4, (OIIO::stride_t)img->width * 4);
	if (!ok)
		error = oiio_message(out.geterror());
	if (!out.close() && ok) {
		error = oiio_message(out.geterror());
		ok = false;
	}
	return ok;
}

bool valid_image(int width, int height, const void *pixels)
{
	return pixels && width > 0 && height > 0 && width <= max_side && height <= max_side;
}

} // namespace

extern "C" int aa_image_read_rgba8(const char *path, struct aa_image_rgba8 *out, struct aa_error *err)
{
	out->width = out->height = 0;
	out->pixels = nullptr;
	std::unique_ptr<ImageInput> in;
	if (open_input(path, in, err) != 0)
		return -1;
	const ImageSpec spec = in->spec();
	std::vector<uint8_t> data;
	if (read_channels(path, *in, TypeDesc::UINT8, data, err) != 0)
		return -1;
	if (aa_image_rgba8_alloc(out, spec.width, spec.height) != 0)
		return aa_error_set(err, AA_ERR_LIMIT, "", "out of memory for image '%s' (%dx%d)", path,
				    spec.width, spec.height);
	expand_to_rgba<uint8_t>(data.data(), spec.nchannels, (size_t)spec.width * spec.height, 255,
				out->pixels);
	return 0;
}

extern "C" int aa_image_read_rgbaf(const char *path, struct aa_image_rgbaf *out, int *channels_in_file,
				   struct aa_error *err)
{
	out->width = out->height = 0;
	out->pixels = nullptr;
	std::unique_ptr<ImageInput> in;
	if (open_input(path, in, err) != 0)
		return -1;
	const ImageSpec spec = in->spec();
	std::vector<float> data;
	if (read_channels(path, *in, TypeDesc::FLOAT, data, err) != 0)
		return -1;
	if (aa_image_rgbaf_alloc(out, spec.width, spec.height) != 0)
		return aa_error_set(err, AA_ERR_LIMIT, "", "out of memory for image '%s' (%dx%d)", path,
				    spec.width, spec.height);
	expand_to_rgba<float>(data.data(), spec.nchannels, (size_t)spec.width * spec.height, 1.0f,
			      out->pixels);
	if (channels_in_file)
		*channels_in_file = spec.nchannels;
	return 0;
}

extern "C" int aa_image_write_png(const char *path, const struct aa_image_rgba8 *img, struct aa_error *err)
{
	if (!valid_image(img->width, img->height, img->pixels))
		return aa_error_set(err, AA_ERR_INVALID, "", "cannot write '%s': empty image", path);
	auto out = ImageOutput::create("png");
	if (!out)
		return aa_error_set(err, AA_ERR_IO, "", "cannot write '%s': %s", path,
				    oiio_message("").c_str());
	std::string error;
	if (!write_png_pixels(*out, path, img, error))
		return aa_error_set(err, AA_ERR_IO, "", "cannot write PNG '%s': %s", path, error.c_str());
	return 0;
}

extern "C" int aa_image_encode_png(const struct aa_image_rgba8 *img, uint8_t **data, size_t *size,
				   struct aa_error *err)
{
	*data = nullptr;
	*size = 0;
	if (!valid_image(img->width, img->height, img->pixels))
		return aa_error_set(err, AA_ERR_INVALID, "", "cannot encode an empty image as PNG");
	std::vector<unsigned char> bytes;
	OIIO::Filesystem::IOVecOutput proxy(bytes);
	auto out = ImageOutput::create("png", &proxy);
	if (!out || !out->supports("ioproxy"))
		return aa_error_set(err, AA_ERR_INTERNAL, "",
				    "this OpenImageIO cannot encode PNG to memory: %s", oiio_message("").c_str());
	std::string error;
	if (!write_png_pixels(*out, "memory.png", img, error))
		return aa_error_set(err, AA_ERR_IO, "", "cannot encode PNG: %s", error.c_str());
	out.reset();
	*data = static_cast<uint8_t *>(malloc(bytes.size() ? bytes.size() : 1));
	if (!*data)
		return aa_error_set(err, AA_ERR_LIMIT, "", "out of memory for a %zu-byte PNG", bytes.size());
	if (!bytes.empty())
		memcpy(*data, bytes.data(), bytes.size());
	*size = bytes.size();
	return 0;
}

extern "C" int aa_image_write_rgbaf(const char *path, const struct aa_image_rgbaf *img, struct aa_error *err)
{
	if (!valid_image(img->width, img->height, img->pixels))
		return aa_error_set(err, AA_ERR_INVALID, "", "cannot write '%s': empty image", path);
	auto out = ImageOutput::create(path);
	if (!out)
		return aa_error_set(err, AA_ERR_IO, "", "cannot write '%s': %s", path,
				    oiio_message("").c_str());
	// Formats without float pixels (PNG, JPEG) are converted by OIIO, clamped to [0,1].
	ImageSpec spec(img->width, img->height, 4, TypeDesc::FLOAT);
	spec.attribute("oiio:ColorSpace", "Linear");
	if (!out->open(path, spec))
		return aa_error_set(err, AA_ERR_IO, "", "cannot write '%s': %s", path,
				    oiio_message(out->geterror()).c_str());
	bool ok = out->write_image(TypeDesc::FLOAT, img->pixels);
	std::string error = ok ? "" : oiio_message(out->geterror());
	if (!out->close() && ok) {
		error = oiio_message(out->geterror());
		ok = false;
	}
	if (!ok)
		return aa_error_set(err, AA_ERR_IO, "", "cannot write '%s': %s", path, error.c_str());
	return 0;
}
