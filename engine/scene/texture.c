/* Scene textures: image files (through engine/image) and 5x7-font text, with mips filtered in linear
 * light because the stored bytes are sRGB and averaging sRGB values darkens edges; colour weighted by
 * alpha only where the material makes alpha coverage (aa_scene_fit_texture_alpha). */
#include "scene/texture.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "image/image.h"
#include "scene/scene_json.h"
#include "util/file_open.h"

#define TEXTURE_FILE_MAX_BYTES (64u << 20)
#define TEXT_MAX_CHARS 256

void aa_texture_free(struct aa_texture *tex)
{
	if (!tex)
		return;
	if (tex->mips)
		for (int i = 0; i < tex->mip_levels; i++)
			free(tex->mips[i]);
	free(tex->mips);
	tex->mips = NULL;
	tex->mip_levels = 0;
}

int aa_texture_mip_count(int width, int height)
{
	int n = 1, m = width > height ? width : height;
	while (m > 1) {
		m >>= 1;
		n++;
	}
	return n;
}

static int level_dim(int d, int level)
{
	int v = d >> level;
	return v > 0 ? v : 1;
}

size_t aa_texture_bytes(int width, int height)
{
	size_t total = 0;
	int levels = aa_texture_mip_count(width, height);
	for (int i = 0; i < levels; i++)
		total += (size_t)level_dim(width, i) * (size_t)level_dim(height, i) * 4;
	return total;
}

/* Box-filter taps for shrinking n texels to m: destination j covers source [j*n/m, (j+1)*n/m), so odd
 * sizes get fractional weights instead of dropping a row or column. At most 4 taps since n/m <= 3. */
struct taps {
	int first, count;
	float w[4];
};

static void make_taps(int n, int m, struct taps *t)
{
	double ratio = (double)n / m;
	for (int j = 0; j < m; j++) {
		double a = j * ratio, b = (j + 1) * ratio;
		int first = (int)floor(a);
		t[j].first = first;
		t[j].count = 0;
		for (int i = first; i < n && i < b && t[j].count < 4; i++) {
			double lo = fmax(a, i), hi = fmin(b, i + 1.0);
			t[j].w[t[j].count++] = (float)((hi - lo) / ratio);
		}
	}
}

/* src: sw x sh premultiplied linear RGBA; dst: dw x dh. Separable: rows first into tmp (dw x sh). */
static void downsample(const float *src, int sw, int sh, float *dst, int dw, int dh, float *tmp,
		       struct taps *tx, struct taps *ty)
{
	make_taps(sw, dw, tx);
	make_taps(sh, dh, ty);
	for (int y = 0; y < sh; y++)
		for (int x = 0; x < dw; x++) {
			float acc[4] = {0};
			for (int k = 0; k < tx[x].count; k++) {
				const float *p = &src[((size_t)y * sw + (size_t)(tx[x].first + k)) * 4];
				for (int c = 0; c < 4; c++)
					acc[c] += tx[x].w[k] * p[c];
			}
			memcpy(&tmp[((size_t)y * dw + (size_t)x) * 4], acc, sizeof acc);
		}
	for (int y = 0; y < dh; y++)
		for (int x = 0; x < dw; x++) {
			float acc[4] = {0};
			for (int k = 0; k < ty[y].count; k++) {
				const float *p = &tmp[((size_t)(ty[y].first + k) * dw + (size_t)x) * 4];
				for (int c = 0; c < 4; c++)
					acc[c] += ty[y].w[k] * p[c];
			}
			memcpy(&dst[((size_t)y * dw + (size_t)x) * 4], acc, sizeof acc);
		}
}

static uint8_t encode_srgb(float linear)
{
	float v = aa_linear_to_srgb(linear < 0.0f ? 0.0f : linear > 1.0f ? 1.0f : linear);
	return (uint8_t)lrintf(v * 255.0f);
}

static uint8_t encode_unorm(float v)
{
	return (uint8_t)lrintf((v < 0.0f ? 0.0f : v > 1.0f ? 1.0f : v) * 255.0f);
}

int aa_texture_from_rgba8(struct aa_texture *out, const uint8_t *pixels, int width, int height,
			  struct aa_error *err)
{
	return aa_texture_from_rgba8_as(out, pixels, width, height, AA_TEXELS_COLOR, err);
}

int aa_texture_from_rgba8_data(struct aa_texture *out, const uint8_t *pixels, int width, int height, bool linear,
			       struct aa_error *err)
{
	return aa_texture_from_rgba8_as(out, pixels, width, height, linear ? AA_TEXELS_DATA : AA_TEXELS_COLOR, err);
}

/* Levels 1.. from level 0 (out->mips[0], width, height, linear and coverage set). Colour is averaged in
 * linear light; weighted by alpha only where alpha is coverage, since weighting colour by an alpha that
 * means nothing (glTF OPAQUE) turns texels of alpha 0 black, and with them the coarser mips. */
static int build_mips(struct aa_texture *out, struct aa_error *err)
{
	int width = out->width, height = out->height;
	const uint8_t *pixels = out->mips[0];
	size_t n0 = (size_t)width * height;
	float *cur = malloc(n0 * 4 * sizeof(float));
	float *next = malloc(n0 * 4 * sizeof(float));
	float *tmp = malloc(n0 * 4 * sizeof(float)); /* a 1-texel-wide image keeps its height in pass one */
	int big = width > height ? width : height;
	struct taps *tx = malloc((size_t)big * sizeof *tx), *ty = malloc((size_t)big * sizeof *ty);
	int rc = 0;
	bool linear = out->linear, weighted = out->coverage;
	if (!cur || !next || !tmp || !tx || !ty) {
		rc = aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory for a %dx%d texture", width, height);
		goto done;
	}
	float lut[256];
	for (int i = 0; i < 256; i++) /* data maps (normals, roughness) are averaged as stored */
		lut[i] = linear ? (float)i / 255.0f : aa_srgb_to_linear((float)i / 255.0f);
	for (size_t i = 0; i < n0; i++) {
		float a = (float)pixels[i * 4 + 3] / 255.0f, w = weighted ? a : 1.0f;
		for (int c = 0; c < 3; c++)
			cur[i * 4 + c] = lut[pixels[i * 4 + c]] * w;
		cur[i * 4 + 3] = a;
	}
	int w = width, h = height;
	for (int level = 1; level < out->mip_levels; level++) {
		int nw = level_dim(width, level), nh = level_dim(height, level);
		downsample(cur, w, h, next, nw, nh, tmp, tx, ty);
		free(out->mips[level]);
		uint8_t *dst = out->mips[level] = malloc((size_t)nw * nh * 4);
		if (!dst) {
			rc = aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory for texture mips");
			goto done;
		}
		for (size_t i = 0; i < (size_t)nw * nh; i++) {
			float a = next[i * 4 + 3], wsum = weighted ? a : 1.0f;
			for (int c = 0; c < 3; c++) {
				float v = wsum > 1e-6f ? next[i * 4 + c] / wsum : 0.0f;
				dst[i * 4 + c] = linear ? encode_unorm(v) : encode_srgb(v);
			}
			dst[i * 4 + 3] = encode_unorm(a);
		}
		float *t = cur;
		cur = next;
		next = t;
		w = nw, h = nh;
	}
done:
	free(cur);
	free(next);
	free(tmp);
	free(tx);
	free(ty);
	return rc;
}

int aa_texture_from_rgba8_as(struct aa_texture *out, const uint8_t *pixels, int width, int height,
			     enum aa_texels kind, struct aa_error *err)
{
	if (width < 1 || height < 1 || width > AA_TEXTURE_MAX_SIZE || height > AA_TEXTURE_MAX_SIZE)
		return aa_error_set(err, AA_ERR_LIMIT, "", "texture is %dx%d; each side must be 1 to %d texels", width,
				    height, AA_TEXTURE_MAX_SIZE);
	out->width = width;
	out->height = height;
	out->linear = kind == AA_TEXELS_DATA;
	out->coverage = kind == AA_TEXELS_COVERAGE;
	out->mip_levels = aa_texture_mip_count(width, height);
	out->mips = calloc((size_t)out->mip_levels, sizeof *out->mips);
	size_t n0 = (size_t)width * height;
	int rc = 0;
	if (!out->mips || !(out->mips[0] = malloc(n0 * 4)))
		rc = aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory for a %dx%d texture", width, height);
	else {
		memcpy(out->mips[0], pixels, n0 * 4);
		rc = build_mips(out, err);
	}
	if (rc)
		aa_texture_free(out);
	return rc;
}

int aa_texture_rebuild(struct aa_texture *tex, bool coverage, struct aa_error *err)
{
	if (tex->coverage == coverage)
		return 0;
	tex->coverage = coverage;
	return build_mips(tex, err);
}

int aa_texture_copy(struct aa_texture *dst, const struct aa_texture *src, struct aa_error *err)
{
	*dst = *src;
	dst->mips = calloc((size_t)src->mip_levels, sizeof *dst->mips);
	for (int i = 0; dst->mips && i < src->mip_levels; i++) {
		size_t bytes = (size_t)level_dim(src->width, i) * (size_t)level_dim(src->height, i) * 4;
		if (!(dst->mips[i] = malloc(bytes))) {
			aa_texture_free(dst);
			return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory for a copy of a texture");
		}
		memcpy(dst->mips[i], src->mips[i], bytes);
	}
	if (!dst->mips) {
		dst->mip_levels = 0;
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory for a copy of a texture");
	}
	return 0;
}

/* glTF: alpha is coverage in the base colour of MASK and BLEND materials only; OPAQUE ignores it, and
 * emissive maps have none. A texture used both ways gets a second copy for the cut-out or blended side. */
int aa_scene_fit_texture_alpha(struct aa_scene *sc, struct aa_error *err)
{
	int n = sc->texture_count;
	if (n == 0)
		return 0;
	bool *as_coverage = calloc((size_t)n, sizeof *as_coverage), *as_color = calloc((size_t)n, sizeof *as_color);
	int *copy = malloc((size_t)n * sizeof *copy);
	int rc = 0;
	if (!as_coverage || !as_color || !copy) {
		rc = aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
		goto done;
	}
	for (int i = 0; i < sc->material_count; i++) {
		const struct aa_material *m = &sc->materials[i];
		bool cut = m->alpha_cutout || m->blend;
		int base = m->texture_index;
		if (base >= 0 && base < n && m->pattern == AA_PATTERN_TEXTURE)
			(cut ? as_coverage : as_color)[base] = true;
		int emissive = m->maps[AA_MAP_EMISSIVE];
		if (emissive >= 0 && emissive < n)
			as_color[emissive] = true;
	}
	size_t bytes = 0;
	for (int t = 0; t < n; t++)
		bytes += aa_texture_bytes(sc->textures[t].width, sc->textures[t].height);
	for (int t = 0; t < n; t++) {
		copy[t] = t;
		struct aa_texture *tex = &sc->textures[t];
		if (tex->linear || !as_coverage[t])
			continue;
		if (!as_color[t]) {
			if ((rc = aa_texture_rebuild(tex, true, err)))
				goto done;
			continue;
		}
		size_t more = aa_texture_bytes(tex->width, tex->height);
		if (sc->texture_count >= AA_SCENE_MAX_ALL_TEXTURES || bytes + more > AA_SCENE_MAX_TEXTURE_BYTES) {
			rc = aa_error_set(err, AA_ERR_LIMIT, "", "texture '%s' is used with alpha as coverage (a cut-out or "
					  "blended base colour) and without (opaque, emissive): its second copy would exceed "
					  "the scene's limits of %d textures and %u bytes", tex->source,
					  AA_SCENE_MAX_ALL_TEXTURES, (unsigned)AA_SCENE_MAX_TEXTURE_BYTES);
			goto done;
		}
		struct aa_texture *grown = realloc(sc->textures, (size_t)(sc->texture_count + 1) * sizeof *grown);
		if (!grown) {
			rc = aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
			goto done;
		}
		sc->textures = grown;
		struct aa_texture *dup = &sc->textures[sc->texture_count];
		if ((rc = aa_texture_copy(dup, &sc->textures[t], err)) || (rc = aa_texture_rebuild(dup, true, err)))
			goto done;
		snprintf(dup->name, sizeof dup->name, "%.50s/cut", sc->textures[t].name);
		copy[t] = sc->texture_count++;
		bytes += more;
	}
	for (int i = 0; i < sc->material_count; i++) {
		struct aa_material *m = &sc->materials[i];
		int base = m->texture_index;
		if ((m->alpha_cutout || m->blend) && base >= 0 && base < n) {
			m->texture_index = copy[base];
			if (m->maps[AA_MAP_BASE] == base)
				m->maps[AA_MAP_BASE] = copy[base];
		}
	}
done:
	free(as_coverage);
	free(as_color);
	free(copy);
	return rc;
}

int aa_texture_text(struct aa_texture *out, const char *text, const float fg[4], const float bg[4], int scale,
		    int padding, bool center, struct aa_error *err)
{
	size_t len = strlen(text);
	if (len == 0 || len > TEXT_MAX_CHARS)
		return aa_error_set(err, AA_ERR_INVALID, "", "text must have 1 to %d characters", TEXT_MAX_CHARS);
	int lines = 1, cols = 0, col = 0;
	for (size_t i = 0; i < len; i++) {
		uint8_t rows[7];
		if (text[i] == '\n') {
			lines++;
			col = 0;
			continue;
		}
		if (aa_font5x7_glyph((unsigned char)text[i], rows))
			return aa_error_set(err, AA_ERR_INVALID, "",
					    "character '%c' (code %d) is not in the 5x7 font; it has: %s",
					    (text[i] > 32 && text[i] < 127) ? text[i] : '?', (unsigned char)text[i],
					    aa_font5x7_charset());
		if (++col > cols)
			cols = col;
	}
	if (cols == 0)
		return aa_error_set(err, AA_ERR_INVALID, "", "text has no characters to draw");
	/* Cells are 6x8 dots (5x7 glyph plus one dot of spacing); the last spacing is trimmed. */
	long dots_w = 2L * padding + cols * 6L - 1, dots_h = 2L * padding + lines * 8L - 1;
	long w = dots_w * scale, h = dots_h * scale;
	if (w > AA_TEXTURE_MAX_SIZE || h > AA_TEXTURE_MAX_SIZE)
		return aa_error_set(err, AA_ERR_LIMIT, "", "text texture would be %ldx%ld, over the limit of %d: "
				    "use a smaller scale or padding, or shorter lines", w, h, AA_TEXTURE_MAX_SIZE);
	uint8_t fgc[4], bgc[4];
	for (int c = 0; c < 3; c++) {
		fgc[c] = encode_srgb(fg[c]);
		bgc[c] = encode_srgb(bg[c]);
	}
	fgc[3] = encode_unorm(fg[3]);
	bgc[3] = encode_unorm(bg[3]);
	uint8_t *px = malloc((size_t)w * (size_t)h * 4);
	if (!px)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory for a text texture");
	for (long i = 0; i < w * h; i++)
		memcpy(&px[i * 4], bgc, 4);
	const char *line = text;
	for (int ln = 0; ln < lines; ln++) {
		int n = (int)strcspn(line, "\n");
		int x0 = padding + (center ? (cols - n) * 3 : 0); /* half a cell per missing character */
		int y0 = padding + ln * 8;
		for (int k = 0; k < n; k++) {
			uint8_t rows[7];
			aa_font5x7_glyph((unsigned char)line[k], rows);
			for (int gy = 0; gy < 7; gy++)
				for (int gx = 0; gx < 5; gx++) {
					if (!(rows[gy] & (0x10 >> gx)))
						continue;
					long tx = (long)(x0 + k * 6 + gx) * scale, ty = (long)(y0 + gy) * scale;
					for (int sy = 0; sy < scale; sy++)
						for (int sx = 0; sx < scale; sx++)
							memcpy(&px[((ty + sy) * w + tx + sx) * 4], fgc, 4);
				}
		}
		line += n + (line[n] == '\n');
	}
	int rc = aa_texture_from_rgba8(out, px, (int)w, (int)h, err);
	free(px);
	if (!rc)
		snprintf(out->source, sizeof out->source, "text:%s", text);
	return rc;
}

/* {"file": "assets/tiles.png"} or {"text": "AALAB", "foreground": ..., "background": ..., ...}. */
int aa_texture_from_json(struct sj *s, const json_t *spec, const char *base_dir, size_t budget,
			 struct aa_texture *out)
{
	static const char *const keys[] = {"file", "text", "foreground", "background", "scale", "padding", "align",
					   NULL};
	static const char *const aligns[] = {"center", "left", NULL};
	static const float white[4] = {1, 1, 1, 1}, black[4] = {0, 0, 0, 1};
	struct aa_error e = {0};
	if (sj_check_keys(s, spec, keys))
		return -1;
	const json_t *file = json_object_get(spec, "file"), *text = json_object_get(spec, "text");
	if ((file != NULL) == (text != NULL))
		return sj_fail(s, AA_ERR_INVALID, "a texture needs exactly one of 'file' (an image) or 'text'");
	if (text) {
		char str[TEXT_MAX_CHARS + 1];
		float fg[4], bg[4];
		int scale, padding, align;
		if (sj_string(s, spec, "text", "", str, sizeof str) || sj_color(s, spec, "foreground", white, true, fg) ||
		    sj_color(s, spec, "background", black, true, bg) || sj_int(s, spec, "scale", 1, 64, 4, &scale) ||
		    sj_int(s, spec, "padding", 0, 256, 2, &padding) || sj_enum(s, spec, "align", aligns, 0, &align))
			return -1;
		if (aa_texture_text(out, str, fg, bg, scale, padding, align == 0, &e))
			return sj_fail_key(s, "text", e.code, "%s", e.message);
	} else {
		char rel[512], full[4096];
		struct stat st;
		if (sj_string(s, spec, "file", "", rel, sizeof rel))
			return -1;
		size_t mark = sj_push_key(s, "file");
		if (sj_resolve_file(s, base_dir, rel, full, sizeof full))
			return -1;
		int fd = aa_file_open_regular(full, "", &e); /* never blocks on a FIFO */
		if (fd < 0 && e.code == AA_ERR_INVALID)
			return sj_fail(s, AA_ERR_INVALID, "image '%s' is not a regular file (a FIFO, socket or device)", rel);
		if (fd >= 0)
			close(fd);
		if (stat(full, &st) != 0 || (uint64_t)st.st_size > TEXTURE_FILE_MAX_BYTES)
			return sj_fail(s, AA_ERR_LIMIT, "image '%s' is larger than %u bytes", rel,
				       (unsigned)TEXTURE_FILE_MAX_BYTES);
		struct aa_image_rgba8 img = {0};
		if (aa_image_read_rgba8(full, &img, &e))
			return sj_fail(s, e.code ? e.code : AA_ERR_IO, "cannot read image '%s': %s", rel, e.message);
		int rc = 0;
		if (img.width > AA_TEXTURE_MAX_SIZE || img.height > AA_TEXTURE_MAX_SIZE)
			rc = sj_fail(s, AA_ERR_LIMIT, "image '%s' is %dx%d; textures may be at most %dx%d", rel, img.width,
				     img.height, AA_TEXTURE_MAX_SIZE, AA_TEXTURE_MAX_SIZE);
		else if (aa_texture_bytes(img.width, img.height) > budget)
			rc = sj_fail(s, AA_ERR_LIMIT, "image '%s' (%dx%d) exceeds the scene's texture memory limit of %u bytes",
				     rel, img.width, img.height, (unsigned)AA_SCENE_MAX_TEXTURE_BYTES);
		else if (aa_texture_from_rgba8(out, img.pixels, img.width, img.height, &e))
			rc = sj_fail(s, e.code, "image '%s': %s", rel, e.message);
		aa_image_rgba8_free(&img);
		if (rc)
			return -1;
		sj_pop(s, mark);
		snprintf(out->source, sizeof out->source, "%s", rel);
	}
	if (aa_texture_bytes(out->width, out->height) > budget) {
		aa_texture_free(out);
		return sj_fail(s, AA_ERR_LIMIT, "textures exceed the scene's texture memory limit of %u bytes",
			       (unsigned)AA_SCENE_MAX_TEXTURE_BYTES);
	}
	return 0;
}
