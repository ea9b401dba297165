/* SMAA's two look-up textures, generated here from the published method (the SMAA paper and the
 * reference scripts AreaTex.py / SearchTex.py), not copied:
 * the area texture (160x560, R8G8: coverage for each crossing-edge pattern and distance pair) and the
 * search texture (64x16, R8: how many pixels of the last bilinear search step still belong to the line).
 * The bytes match the published Textures/AreaTex.h and SearchTex.h byte for byte (tests/unit). */
#ifndef AA_SMAA_TEXTURES_H
#define AA_SMAA_TEXTURES_H

#include <stdint.h>

#define AA_SMAA_AREA_WIDTH 160
#define AA_SMAA_AREA_HEIGHT 560
#define AA_SMAA_AREA_BYTES (AA_SMAA_AREA_WIDTH * AA_SMAA_AREA_HEIGHT * 2)
#define AA_SMAA_SEARCH_WIDTH 64
#define AA_SMAA_SEARCH_HEIGHT 16
#define AA_SMAA_SEARCH_BYTES (AA_SMAA_SEARCH_WIDTH * AA_SMAA_SEARCH_HEIGHT)

/* Writes the textures, row 0 first; the area texture stores R then G per texel. */
void aa_smaa_area_generate(uint8_t out[AA_SMAA_AREA_BYTES]);
void aa_smaa_search_generate(uint8_t out[AA_SMAA_SEARCH_BYTES]);

/* The same bytes, generated on first use and kept for the life of the process (thread-safe). */
const uint8_t *aa_smaa_area_texture(void);
const uint8_t *aa_smaa_search_texture(void);

#endif
