/* SMAA's generated look-up textures against the published ones (iryoku/smaa, Textures/AreaTex.h and
 * SearchTex.h at commit 71c806a8): whole-array fingerprints (CRC-32, byte sum, non-zero count; the
 * SHA-256 in notes/smaa.md §8.3 matches too) and a handful of texels read from the published headers.
 * Every comparison is exact: the generator reproduces the published bytes, not just within 1 LSB. */
#include <setjmp.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <time.h>
#include <cmocka.h>

#include "methods/smaa_textures.h"

static uint8_t area[AA_SMAA_AREA_BYTES];
static uint8_t search[AA_SMAA_SEARCH_BYTES];

static uint32_t crc32(const uint8_t *p, size_t n)
{
	uint32_t c = 0xffffffffu;
	for (size_t i = 0; i < n; i++) {
		c ^= p[i];
		for (int k = 0; k < 8; k++)
			c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
	}
	return ~c;
}

static int setup(void **state)
{
	(void)state;
	clock_t t = clock();
	aa_smaa_area_generate(area);
	aa_smaa_search_generate(search);
	print_message("generated both textures in %.3f s of CPU time\n", (double)(clock() - t) / CLOCKS_PER_SEC);
	return 0;
}

/* (x, y, R, G) of the published area texture, read from AreaTex.h (row-major, R then G per texel). */
static const int published_texels[][4] = {
	/* orthogonal half, slot 0: pattern 4 (block (1,0)) and pattern 1 (block (3,0)) */
	{16, 0, 0, 31}, {16, 1, 0, 63}, {17, 1, 0, 10}, {16, 2, 0, 102}, {17, 2, 0, 63}, {18, 2, 0, 3},
	{48, 0, 31, 0}, {48, 1, 63, 0}, {49, 1, 10, 0},
	/* diagonal half, slot 0 (x >= 80); (120, 0) is the degenerate P1 == P2 case of pattern 4 */
	{80, 0, 64, 61}, {81, 0, 65, 61}, {80, 1, 65, 61}, {100, 0, 68, 123}, {101, 0, 65, 93},
	{100, 1, 98, 32}, {101, 1, 77, 42}, {120, 0, 4, 127}, {121, 0, 34, 61}, {120, 1, 0, 93},
	{121, 1, 12, 73}, {140, 0, 64, 127},
};

static void test_area_texels(void **state)
{
	(void)state;
	int n = (int)(sizeof published_texels / sizeof published_texels[0]);
	for (int i = 0; i < n; i++) {
		const int *t = published_texels[i];
		size_t at = (size_t)t[1] * AA_SMAA_AREA_WIDTH * 2 + (size_t)t[0] * 2;
		if (area[at] != t[2] || area[at + 1] != t[3])
			fail_msg("area texel (%d, %d): generated (%d, %d), published (%d, %d)", t[0], t[1], area[at],
				 area[at + 1], t[2], t[3]);
	}
	print_message("%d published area texels match exactly\n", n);
}

/* Pattern values of notes/smaa.md §8.4 that exercise U smoothing, Z patterns and other slots. */
static void test_area_patterns(void **state)
{
	(void)state;
	static const int expect[][4] = {
		{48 + 0, 48 + 0, 125, 0}, {48 + 1, 48 + 1, 68, 0}, {48 + 2, 48 + 3, 62, 0}, {48 + 3, 48 + 2, 62, 0},
		{64 + 0, 48 + 0, 31, 31}, {64 + 1, 48 + 1, 10, 10}, {64 + 2, 48 + 3, 0, 45}, {64 + 3, 48 + 2, 45, 0},
		{17, 17, 0, 68}, {49, 81, 15, 0}, {16, 5, 0, 122}, {103, 2, 74, 34}, {100, 40, 129, 0},
		{120, 20, 0, 123},
	};
	for (size_t i = 0; i < sizeof expect / sizeof expect[0]; i++) {
		size_t at = (size_t)expect[i][1] * AA_SMAA_AREA_WIDTH * 2 + (size_t)expect[i][0] * 2;
		assert_int_equal(area[at], expect[i][2]);
		assert_int_equal(area[at + 1], expect[i][3]);
	}
}

static void test_area_fingerprint(void **state)
{
	(void)state;
	uint64_t sum = 0;
	int nonzero = 0, largest = 0;
	for (size_t i = 0; i < AA_SMAA_AREA_BYTES; i++) {
		sum += area[i];
		nonzero += area[i] != 0;
		largest = area[i] > largest ? area[i] : largest;
	}
	assert_int_equal(sum, 5292436);
	assert_int_equal(nonzero, 75849);
	assert_int_equal(largest, 222);
	assert_int_equal(crc32(area, AA_SMAA_AREA_BYTES), 0xed2bc181u);
	/* unused regions stay zero: orthogonal block column 2, block row 2 of each slot, diagonal rows >= 400 */
	for (int y = 0; y < AA_SMAA_AREA_HEIGHT; y++)
		for (int x = 0; x < AA_SMAA_AREA_WIDTH; x++) {
			bool unused = x < 80 ? (x >= 32 && x < 48) || (y % 80 >= 32 && y % 80 < 48) : y >= 400;
			size_t at = (size_t)y * AA_SMAA_AREA_WIDTH * 2 + (size_t)x * 2;
			if (unused && (area[at] || area[at + 1]))
				fail_msg("texel (%d, %d) should be unused", x, y);
		}
	print_message("area texture: all %d bytes equal the published ones (CRC-32 %08x)\n", AA_SMAA_AREA_BYTES,
		      crc32(area, AA_SMAA_AREA_BYTES));
}

static void test_search_texture(void **state)
{
	(void)state;
	/* packed row 0 of the published SearchTex.h (then zeros) */
	static const uint8_t row0[42] = {
		0xfe, 0xfe, 0x00, 0x7f, 0x7f, 0x00, 0x00, 0xfe, 0xfe, 0x00, 0x7f, 0x7f, 0x00, 0x00,
		0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x7f, 0x7f, 0x00, 0x7f, 0x7f, 0x00, 0x00,
		0x7f, 0x7f, 0x00, 0x7f, 0x7f, 0xfe, 0x7f, 0x00, 0x00, 0x00, 0x00, 0x00, 0x7f, 0x7f,
	};
	assert_memory_equal(search, row0, sizeof row0);
	for (int x = (int)sizeof row0; x < AA_SMAA_SEARCH_WIDTH; x++)
		assert_int_equal(search[x], 0);
	/* rows 1, 3, 4 repeat row 0; rows 7, 8, 10, 11 are row 0 with 0xfe -> 0x7f; the rest are zero */
	for (int y = 1; y < AA_SMAA_SEARCH_HEIGHT; y++)
		for (int x = 0; x < AA_SMAA_SEARCH_WIDTH; x++) {
			uint8_t v = search[y * AA_SMAA_SEARCH_WIDTH + x], r = search[x], want = 0;
			if (y == 1 || y == 3 || y == 4)
				want = r;
			else if (y == 7 || y == 8 || y == 10 || y == 11)
				want = r == 0xfe ? 0x7f : r;
			assert_int_equal(v, want);
		}
	uint32_t sum = 0;
	int n7f = 0, nfe = 0;
	for (int i = 0; i < AA_SMAA_SEARCH_BYTES; i++) {
		sum += search[i];
		n7f += search[i] == 0x7f;
		nfe += search[i] == 0xfe;
	}
	assert_int_equal(sum, 22860);
	assert_int_equal(n7f, 140);
	assert_int_equal(nfe, 20);
	assert_int_equal(crc32(search, AA_SMAA_SEARCH_BYTES), 0x77423453u);
}

/* The cached copies are the generated bytes, and stay the same pointer. */
static void test_cache(void **state)
{
	(void)state;
	const uint8_t *a = aa_smaa_area_texture(), *s = aa_smaa_search_texture();
	assert_memory_equal(a, area, AA_SMAA_AREA_BYTES);
	assert_memory_equal(s, search, AA_SMAA_SEARCH_BYTES);
	assert_ptr_equal(a, aa_smaa_area_texture());
	assert_ptr_equal(s, aa_smaa_search_texture());
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_area_texels),
		cmocka_unit_test(test_area_patterns),
		cmocka_unit_test(test_area_fingerprint),
		cmocka_unit_test(test_search_texture),
		cmocka_unit_test(test_cache),
	};
	return cmocka_run_group_tests(tests, setup, NULL);
}
