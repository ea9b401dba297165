/* Test images for the FLIP tests: hard-edged shapes over a gradient, with noise (edges, points and flat
 * areas for both of FLIP's pipelines). Include after <cmocka.h>. */
#ifndef AALAB_TEST_FLIP_IMAGES_H
#define AALAB_TEST_FLIP_IMAGES_H

#include <stdint.h>

#include "image/image.h"

static inline uint32_t next_random(uint32_t *state)
{
	uint32_t x = *state;
	x ^= x << 13;
	x ^= x >> 17;
	x ^= x << 5;
	return *state = x;
}

static inline void make_image(struct aa_image_rgba8 *img, int w, int h, uint32_t seed, int noise)
{
	assert_int_equal(aa_image_rgba8_alloc(img, w, h), 0);
	uint32_t state = seed;
	for (int y = 0; y < h; y++)
		for (int x = 0; x < w; x++) {
			uint8_t *px = img->pixels + 4 * ((size_t)y * w + x);
			int inside = ((x / 7 + y / 5) % 3 == 0) || (x - w / 2) * (x - w / 2) + (y - h / 2) * (y - h / 2) < 40;
			for (int c = 0; c < 3; c++) {
				int v = inside ? 200 - 60 * c : 30 + (x * (c + 1) * 255) / (w * 3);
				v += noise ? (int)(next_random(&state) % (2 * noise + 1)) - noise : 0;
				px[c] = (uint8_t)(v < 0 ? 0 : v > 255 ? 255 : v);
			}
			px[3] = 255;
		}
}

#endif
