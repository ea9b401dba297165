/* Generates SMAA's area and search textures from the published method (notes/smaa.md §5, §6). The
 * arithmetic is IEEE double in the reference scripts' operation order, so the bytes come out identical
 * to the published ones; fused multiply-add or fast-math would change a few of them (§5.9). */
#if defined(__FAST_MATH__)
#error "smaa_textures.c must be built without -ffast-math: the texture bytes depend on exact doubles"
#endif
#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif

#include <math.h>
#include <pthread.h>
#include <stdbool.h>
#include <string.h>

#include "methods/smaa_textures.h"

struct pair {
	double a, b; /* R: coverage on the current pixel's side; G: on the other side */
};

static struct pair pair_avg(struct pair x, struct pair y)
{
	return (struct pair){(x.a + y.a) / 2.0, (x.b + y.b) / 2.0};
}

/* ------------------------------------------------------------------ orthogonal patterns (§5.2-§5.4) */

/* Subsample offsets of the 7 orthogonal slots (1x, 2x and 4x modes); 1x uses slot 0. */
static const double ortho_offsets[7] = {0.0, -0.25, 0.25, -0.125, 0.125, -0.375, 0.375};
/* Block (bx, by) of each crossing-edge pattern: bx = 3*bit0 + bit2, by = 3*bit1 + bit3. */
static const int ortho_blocks[16][2] = {
	{0, 0}, {3, 0}, {0, 3}, {3, 3}, {1, 0}, {4, 0}, {1, 3}, {4, 3},
	{0, 1}, {3, 1}, {0, 4}, {3, 4}, {1, 1}, {4, 1}, {1, 4}, {4, 4},
};
#define ORTHO_BLOCK 16     /* SMAA_AREATEX_MAX_DISTANCE */
#define SMOOTH_MAX_DISTANCE 32.0

/* Area between the segment p1->p2 (p1.x < p2.x) and the line y = 0 over the pixel column [x, x+1],
 * as (below, above). The segment may cross y = 0 inside the column: then two triangles. */
static struct pair segment_area(double p1x, double p1y, double p2x, double p2y, double x)
{
	double dx = p2x - p1x, dy = p2y - p1y;
	double x1 = x, x2 = x + 1.0;
	double y1 = p1y + dy * (x1 - p1x) / dx;
	double y2 = p1y + dy * (x2 - p1x) / dx;
	bool inside = (x1 >= p1x && x1 < p2x) || (x2 > p1x && x2 <= p2x);
	if (!inside)
		return (struct pair){0.0, 0.0};
	bool trapezoid = !signbit(y1) == !signbit(y2) || fabs(y1) < 1e-4 || fabs(y2) < 1e-4;
	if (trapezoid) {
		double a = (y1 + y2) / 2.0;
		return a < 0.0 ? (struct pair){fabs(a), 0.0} : (struct pair){0.0, fabs(a)};
	}
	double xc = -p1y * dx / dy + p1x;
	double whole;
	double f = modf(xc, &whole);
	double a1 = xc > p1x ? y1 * f / 2.0 : 0.0;
	double a2 = xc < p2x ? y2 * (1.0 - f) / 2.0 : 0.0;
	double a = fabs(a1) > fabs(a2) ? a1 : -a2;
	return a < 0.0 ? (struct pair){fabs(a1), fabs(a2)} : (struct pair){fabs(a2), fabs(a1)};
}

/* U shapes (patterns 3 and 12): short ones are pulled toward sqrt(2a)/2, which rounds their corners. */
static struct pair smooth_u(struct pair a1, struct pair a2, double d)
{
	double p = d / SMOOTH_MAX_DISTANCE;
	p = p < 0.0 ? 0.0 : p > 1.0 ? 1.0 : p;
	struct pair b1 = {sqrt(2.0 * a1.a) * 0.5, sqrt(2.0 * a1.b) * 0.5};
	struct pair b2 = {sqrt(2.0 * a2.a) * 0.5, sqrt(2.0 * a2.b) * 0.5};
	a1 = (struct pair){b1.a + (a1.a - b1.a) * p, b1.b + (a1.b - b1.b) * p};
	a2 = (struct pair){b2.a + (a2.a - b2.a) * p, b2.b + (a2.b - b2.b) * p};
	return (struct pair){a1.a + a2.a, a1.b + a2.b};
}

/* Coverage of the pixel at distance `left` from the left end of a line of left + right + 1 pixels whose
 * ends have the crossing edges of `pattern`; the revectorised line passes through the middle. */
static struct pair area_ortho(int pattern, int left, int right, double offset)
{
	double d = (double)(left + right + 1), h = d / 2.0, x = (double)left;
	double o1 = 0.5 + offset, o2 = 0.5 + offset - 1.0;
	struct pair zero = {0.0, 0.0};
	switch (pattern) {
	case 1: /* left end down: only from the nearer end, so it converges with pattern 0 */
		return left <= right ? segment_area(0.0, o2, h, 0.0, x) : zero;
	case 2: /* right end down */
		return left >= right ? segment_area(h, 0.0, d, o2, x) : zero;
	case 3: /* U, both ends down */
		return smooth_u(segment_area(0.0, o2, h, 0.0, x), segment_area(h, 0.0, d, o2, x), d);
	case 4: /* left end up */
		return left <= right ? segment_area(0.0, o1, h, 0.0, x) : zero;
	case 6: /* Z: with a subsample offset, blended with the two-L version to avoid seams */
		if (fabs(offset) > 0.0) {
			struct pair z = segment_area(0.0, o1, d, o2, x);
			struct pair l1 = segment_area(0.0, o1, h, 0.0, x), l2 = segment_area(h, 0.0, d, o2, x);
			return pair_avg(z, (struct pair){l1.a + l2.a, l1.b + l2.b});
		}
		return segment_area(0.0, o1, d, o2, x);
	case 7:
	case 14:
		return segment_area(0.0, o1, d, o2, x);
	case 8: /* right end up */
		return left >= right ? segment_area(h, 0.0, d, o1, x) : zero;
	case 9: /* mirrored Z */
		if (fabs(offset) > 0.0) {
			struct pair z = segment_area(0.0, o2, d, o1, x);
			struct pair l1 = segment_area(0.0, o2, h, 0.0, x), l2 = segment_area(h, 0.0, d, o1, x);
			return pair_avg(z, (struct pair){l1.a + l2.a, l1.b + l2.b});
		}
		return segment_area(0.0, o2, d, o1, x);
	case 11:
	case 13:
		return segment_area(0.0, o2, d, o1, x);
	case 12: /* U, both ends up */
		return smooth_u(segment_area(0.0, o1, h, 0.0, x), segment_area(h, 0.0, d, o1, x), d);
	default: /* 0 flat, 5 / 10 / 15 crossings ("+") on the ends: nothing to revectorise */
		return zero;
	}
}

/* ------------------------------------------------------------------ diagonal patterns (§5.5-§5.6) */

static const double diag_offsets[5][2] = {{0.0, 0.0}, {0.25, -0.25}, {-0.25, 0.25}, {0.125, -0.125},
					  {-0.125, 0.125}};
/* Block (bx, by) of each pattern: bx = bit0 + 2*bit2, by = 2*bit1 + bit3. */
static const int diag_blocks[16][2] = {
	{0, 0}, {1, 0}, {0, 2}, {1, 2}, {2, 0}, {3, 0}, {2, 2}, {3, 2},
	{0, 1}, {1, 1}, {0, 3}, {1, 3}, {2, 1}, {3, 1}, {2, 3}, {3, 3},
};
#define DIAG_BLOCK 20      /* SMAA_AREATEX_MAX_DISTANCE_DIAG */
#define DIAG_SAMPLES 30    /* per axis, borders included */

/* Fraction of a 30x30 lattice over the unit square at corner (qx, qy) strictly on the positive side of
 * the line p1->p2; a degenerate line (p1 == p2) counts every sample. */
static double lattice_coverage(const double p1[2], const double p2[2], double qx, double qy)
{
	if (p1[0] == p2[0] && p1[1] == p2[1])
		return 1.0;
	double mx = (p1[0] + p2[0]) / 2.0, my = (p1[1] + p2[1]) / 2.0;
	double a = p2[1] - p1[1], b = p1[0] - p2[0];
	int n = 0;
	for (int i = 0; i < DIAG_SAMPLES; i++) {
		double sx = qx + i / (double)(DIAG_SAMPLES - 1);
		for (int j = 0; j < DIAG_SAMPLES; j++) {
			double sy = qy + j / (double)(DIAG_SAMPLES - 1);
			double c = a * (sx - mx) + b * (sy - my);
			if (c > 0)
				n++;
		}
	}
	return n / (double)(DIAG_SAMPLES * DIAG_SAMPLES);
}

/* The area of one candidate line from p1 to p2 (in pattern space), for the pixel at `left` and the
 * pixel across the edge; only ends with a crossing edge move by the subsample offset. */
static struct pair diag_line(int pattern, double p1x, double p1y, double p2x, double p2y, int left,
			     const double offset[2])
{
	double p1[2] = {p1x, p1y}, p2[2] = {p2x, p2y};
	if (diag_blocks[pattern][0] > 0) {
		p1[0] += offset[0];
		p1[1] += offset[1];
	}
	if (diag_blocks[pattern][1] > 0) {
		p2[0] += offset[0];
		p2[1] += offset[1];
	}
	double a1 = lattice_coverage(p1, p2, 1.0 + left, (double)left);
	double a2 = lattice_coverage(p1, p2, 1.0 + left, 1.0 + left);
	return (struct pair){1.0 - a1, a2};
}

/* Each diagonal pattern's ends are not known exactly (L and U endings differ, and the next pattern is
 * unknown), so most entries blend two candidate lines; unlike the orthogonal case pattern 0 is filtered.
 * Each row: the start (x, y) and end offset (x, y) added to (d, d) of the first and second line; a
 * pattern with a single line repeats it (the average of equal values is exact). */
static const double diag_lines[16][2][4] = {
	{{1, 1, 1, 1}, {1, 0, 1, 0}}, {{1, 0, 0, 0}, {1, 0, 1, 0}}, {{0, 0, 1, 0}, {1, 0, 1, 0}},
	{{1, 0, 1, 0}, {1, 0, 1, 0}}, {{1, 1, 0, 0}, {1, 1, 1, 0}}, {{1, 1, 0, 0}, {1, 0, 1, 0}},
	{{1, 1, 1, 0}, {1, 1, 1, 0}}, {{1, 1, 1, 0}, {1, 0, 1, 0}}, {{0, 0, 1, 1}, {1, 0, 1, 1}},
	{{1, 0, 1, 1}, {1, 0, 1, 1}}, {{0, 0, 1, 1}, {1, 0, 1, 0}}, {{1, 0, 1, 1}, {1, 0, 1, 0}},
	{{1, 1, 1, 1}, {1, 1, 1, 1}}, {{1, 1, 1, 1}, {1, 0, 1, 1}}, {{1, 1, 1, 1}, {1, 1, 1, 0}},
	{{1, 1, 1, 1}, {1, 0, 1, 0}},
};

static struct pair area_diag(int pattern, int left, int right, const double offset[2])
{
	double d = (double)(left + right + 1);
	const double *l1 = diag_lines[pattern][0], *l2 = diag_lines[pattern][1];
	struct pair a1 = diag_line(pattern, l1[0], l1[1], l1[2] + d, l1[3] + d, left, offset);
	if (memcmp(l1, l2, sizeof diag_lines[0][0]) == 0)
		return a1; /* patterns 3, 6, 9 and 12 have one line */
	struct pair a2 = diag_line(pattern, l2[0], l2[1], l2[2] + d, l2[3] + d, left, offset);
	return pair_avg(a1, a2);
}

/* ------------------------------------------------------------------ assembly (§5.1, §5.8) */

static uint8_t to_byte(double v)
{
	return (uint8_t)(int)(255.0 * v); /* the scripts truncate, they do not round */
}

static void put_texel(uint8_t *out, int x, int y, struct pair v)
{
	out[(size_t)y * AA_SMAA_AREA_WIDTH * 2 + (size_t)x * 2] = to_byte(v.a);
	out[(size_t)y * AA_SMAA_AREA_WIDTH * 2 + (size_t)x * 2 + 1] = to_byte(v.b);
}

void aa_smaa_area_generate(uint8_t out[AA_SMAA_AREA_BYTES])
{
	memset(out, 0, AA_SMAA_AREA_BYTES);
	/* left half: 7 slots of 5x5 blocks of 16x16; distances are stored quadratically (index i holds
	 * distance i*i) so that 16 texels reach 225 pixels */
	for (int k = 0; k < 7; k++)
		for (int p = 0; p < 16; p++)
			for (int j = 0; j < ORTHO_BLOCK; j++)
				for (int i = 0; i < ORTHO_BLOCK; i++)
					put_texel(out, ORTHO_BLOCK * ortho_blocks[p][0] + i,
						  80 * k + ORTHO_BLOCK * ortho_blocks[p][1] + j,
						  area_ortho(p, i * i, j * j, ortho_offsets[k]));
	/* right half: 5 slots of 4x4 blocks of 20x20, distances stored linearly */
	for (int k = 0; k < 5; k++)
		for (int p = 0; p < 16; p++)
			for (int j = 0; j < DIAG_BLOCK; j++)
				for (int i = 0; i < DIAG_BLOCK; i++)
					put_texel(out, 80 + DIAG_BLOCK * diag_blocks[p][0] + i,
						  80 * k + DIAG_BLOCK * diag_blocks[p][1] + j,
						  area_diag(p, i, j, diag_offsets[k]));
}

/* ------------------------------------------------------------------ search texture (§6) */

/* A bilinear search fetch mixes a 2x2 block as (b0 + 3*b1 + 7*b2 + 21*b3)/32: b0 far/outer row, b1
 * near/outer row, b2 far/line row, b3 near/line row. Decodes v = 32*value into the four edges. */
static bool decode_fetch(int v, int e[4])
{
	for (int bits = 0; bits < 16; bits++) {
		e[0] = bits & 1;
		e[1] = (bits >> 1) & 1;
		e[2] = (bits >> 2) & 1;
		e[3] = (bits >> 3) & 1;
		if (e[0] + 3 * e[1] + 7 * e[2] + 21 * e[3] == v)
			return true;
	}
	return false;
}

/* How many of the last two pixels (0, 1, 2) still belong to the line: `top` are the line's own edges
 * (it continues while the near, then the far pixel has one), `left` the crossing edges that end it. */
static int search_delta_left(const int left[4], const int top[4])
{
	int d = top[3] == 1;
	if (d == 1 && top[2] == 1 && left[1] != 1 && left[3] != 1)
		d = 2;
	return d;
}

static int search_delta_right(const int left[4], const int top[4])
{
	int d = top[3] == 1 && left[1] != 1 && left[3] != 1;
	if (d == 1 && top[2] == 1 && left[0] != 1 && left[2] != 1)
		d = 2;
	return d;
}

void aa_smaa_search_generate(uint8_t out[AA_SMAA_SEARCH_BYTES])
{
	/* The logical table is 66x33 (left search in columns 0-32, right search in 33-65, row = 32*e.g);
	 * the stored texture keeps columns 0-63 and rows 17-32 flipped, which drops only zeros. */
	for (int y = 0; y < AA_SMAA_SEARCH_HEIGHT; y++)
		for (int x = 0; x < AA_SMAA_SEARCH_WIDTH; x++) {
			bool right = x >= 33;
			int left_edges[4], top_edges[4], delta = 0;
			if (decode_fetch(right ? x - 33 : x, left_edges) && decode_fetch(32 - y, top_edges))
				delta = right ? search_delta_right(left_edges, top_edges)
					      : search_delta_left(left_edges, top_edges);
			out[y * AA_SMAA_SEARCH_WIDTH + x] = (uint8_t)(127 * delta);
		}
}

/* ------------------------------------------------------------------ cache */

static uint8_t area_cache[AA_SMAA_AREA_BYTES];
static uint8_t search_cache[AA_SMAA_SEARCH_BYTES];
static pthread_once_t cache_once = PTHREAD_ONCE_INIT;

static void cache_fill(void)
{
	aa_smaa_area_generate(area_cache);
	aa_smaa_search_generate(search_cache);
}

const uint8_t *aa_smaa_area_texture(void)
{
	pthread_once(&cache_once, cache_fill);
	return area_cache;
}

const uint8_t *aa_smaa_search_texture(void)
{
	pthread_once(&cache_once, cache_fill);
	return search_cache;
}
