/* Textures for scenes: image files and generated text, each with a full mip chain built on the CPU. */
#ifndef AA_TEXTURE_H
#define AA_TEXTURE_H

#include "scene/scene.h"

void aa_texture_free(struct aa_texture *tex);
/* 1 + floor(log2(max(w, h))). */
int aa_texture_mip_count(int width, int height);
/* CPU bytes of a width x height RGBA8 texture with all its mips. */
size_t aa_texture_bytes(int width, int height);

/* What a texture's texels are, which decides how its mips are filtered. */
enum aa_texels {
	AA_TEXELS_COLOR = 0, /* sRGB colour, alpha not coverage (glTF OPAQUE, emissive): colour averaged alone */
	AA_TEXELS_COVERAGE,  /* sRGB colour whose alpha is coverage (MASK, BLEND, scene cut-outs): colour
			      * weighted by alpha, so transparent texels do not darken cut-out edges */
	AA_TEXELS_DATA,      /* data such as normal maps: stored and filtered as is, no sRGB decoding */
};

/* Copies w x h RGBA8 pixels as level 0 and builds the mips with a box filter (in linear light for colour). */
int aa_texture_from_rgba8_as(struct aa_texture *out, const uint8_t *pixels, int width, int height,
			     enum aa_texels kind, struct aa_error *err);
/* AA_TEXELS_COLOR. */
int aa_texture_from_rgba8(struct aa_texture *out, const uint8_t *pixels, int width, int height,
			  struct aa_error *err);
/* AA_TEXELS_DATA when linear, else AA_TEXELS_COLOR. */
int aa_texture_from_rgba8_data(struct aa_texture *out, const uint8_t *pixels, int width, int height, bool linear,
			       struct aa_error *err);
/* Rebuilds the mips of a colour texture from level 0 with alpha as coverage or not. */
int aa_texture_rebuild(struct aa_texture *tex, bool coverage, struct aa_error *err);
/* A deep copy (every level). */
int aa_texture_copy(struct aa_texture *dst, const struct aa_texture *src, struct aa_error *err);
/* After loading: the base-colour textures of cut-out and blended materials get coverage mips, the rest
 * keep colour mips; a texture used both ways is copied (the copy is appended and those materials
 * repointed). Fails only on memory or the scene's texture limits. */
int aa_scene_fit_texture_alpha(struct aa_scene *sc, struct aa_error *err);

/* Renders text with the 5x7 font: each dot becomes scale x scale texels, glyphs sit in 6x8-dot cells,
 * `padding` dots of background surround the text; '\n' starts a new line (lines centred when `center`).
 * Colours are linear RGBA. Characters outside the font are an error. */
int aa_texture_text(struct aa_texture *out, const char *text, const float fg[4], const float bg[4], int scale,
		    int padding, bool center, struct aa_error *err);

/* font5x7.c: a glyph's 7 rows, bit 4 = leftmost of the 5 columns; lower case maps to upper case.
 * Returns -1 for characters the font lacks. */
int aa_font5x7_glyph(int c, uint8_t rows[7]);
const char *aa_font5x7_charset(void);

#endif
