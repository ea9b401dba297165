/* STL read strictly before assimp (mesh_text_check.c): binary when the file is 84 + 50 bytes per
 * triangle as its header counts them (assimp decides so, in 32-bit arithmetic that a large count wraps
 * round to the file's size), otherwise ASCII solids of facets of three vertices. */
#include <ctype.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/mesh_text.h"

static float stl_float(const unsigned char *p)
{
	uint32_t u = (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
	float f;
	memcpy(&f, &u, sizeof f);
	return f;
}

static int check_stl_binary(struct mesh_text *t, uint64_t triangles)
{
	const unsigned char *p = (const unsigned char *)t->p + 84;
	if (triangles == 0)
		return mt_fail_plain(t, "a binary STL file of no triangles");
	for (uint64_t i = 0; i < triangles; i++, p += 50) {
		float v[12];
		for (int k = 0; k < 12; k++)
			if (!isfinite(v[k] = stl_float(p + 4 * k)))
				return mt_fail_plain(t, "triangle %llu (byte %llu) has a %s that is not a finite number",
						  (unsigned long long)i, (unsigned long long)(84 + 50 * i), k < 3 ? "normal" : "position");
		for (int k = 3; k < 12; k++)
			if (fabsf(v[k]) > POSITION_MAX)
				return mt_fail_plain(t, "triangle %llu (byte %llu): vertex %llu is at (%g, %g, %g): positions must be "
						  "within %g of the origin", (unsigned long long)i,
						  (unsigned long long)(84 + 50 * i), (unsigned long long)(3 * i + (k - 3) / 3),
						  v[k - (k % 3)], v[k - (k % 3) + 1], v[k - (k % 3) + 2], POSITION_MAX);
	}
	return 0;
}

/* The next line that is not blank, which must start with `word` and have n tokens (n < 0: at least -n). */
static int stl_expect(struct mesh_text *t, const char *word, int n)
{
	int r;
	while ((r = mt_next_line(t)) > 0 && t->n == 0)
		;
	if (r < 0)
		return -1;
	if (r == 0)
		return mt_fail_plain(t, "ends where '%s' should be", word);
	if (!mt_is(t, 0, word) || (n >= 0 ? t->n != n : t->n < -n))
		return mt_fail_at(t, "expected '%s%s'", word, !strcmp(word, "facet") ? " normal nx ny nz" :
							    !strcmp(word, "vertex") ? " x y z" :
							    !strcmp(word, "outer") ? " loop" : "");
	return 0;
}

int mt_check_stl(struct mesh_text *t)
{
	size_t size = (size_t)(t->end - t->p);
	/* binary when the size is 84 + 50 x the count, as assimp decides (before looking for "solid") */
	if (size >= 84) {
		const unsigned char *c = (const unsigned char *)t->p + 80;
		uint32_t n = (uint32_t)c[0] | (uint32_t)c[1] << 8 | (uint32_t)c[2] << 16 | (uint32_t)c[3] << 24;
		if (84 + 50 * (uint64_t)n == size)
			return check_stl_binary(t, n);
		if ((uint32_t)(84u + 50u * n) == (uint32_t)size) /* assimp's 32-bit sum wraps to the size */
			return mt_fail_plain(t, "binary STL header says %u triangles, which would be %llu bytes, the file has %zu",
					  n, (unsigned long long)(84 + 50 * (uint64_t)n), size);
	}
	const char *s = t->p;
	while (s < t->end && (*s == ' ' || *s == '\t')) /* as assimp: not line ends */
		s++;
	if (t->end - s < 5 || memcmp(s, "solid", 5) != 0) {
		if (size >= 84) {
			const unsigned char *c = (const unsigned char *)t->p + 80;
			uint32_t n = (uint32_t)c[0] | (uint32_t)c[1] << 8 | (uint32_t)c[2] << 16 | (uint32_t)c[3] << 24;
			return mt_fail_plain(t, "is neither ASCII STL (starting with solid) nor binary STL: its header says %u "
					  "triangles, %llu bytes, the file has %zu", n,
					  (unsigned long long)(84 + 50 * (uint64_t)n), size);
		}
		return mt_fail_plain(t, "is neither ASCII STL (starting with solid) nor binary STL (at least 84 bytes)");
	}
	uint64_t triangles = 0;
	if (stl_expect(t, "solid", -1))
		return -1;
	for (;;) {
		int r;
		while ((r = mt_next_line(t)) > 0 && t->n == 0)
			;
		if (r <= 0)
			return r < 0 ? -1 : mt_fail_plain(t, "ends before endsolid");
		if (mt_is(t, 0, "endsolid")) {
			while ((r = mt_next_line(t)) > 0 && t->n == 0)
				;
			if (r <= 0)
				break;
			if (!mt_is(t, 0, "solid"))
				return mt_fail_at(t, "expected 'solid' or the end of the file after endsolid");
			continue;
		}
		char what[64];
		snprintf(what, sizeof what, "triangle %llu normal", (unsigned long long)triangles);
		double v;
		if (!mt_is(t, 0, "facet") || t->n != 5 || !mt_is(t, 1, "normal"))
			return mt_fail_at(t, "expected 'facet normal nx ny nz' or 'endsolid'");
		for (int k = 2; k < 5; k++)
			if (mt_number(t, k, what, &v))
				return -1;
		if (stl_expect(t, "outer", 2) || (!mt_is(t, 1, "loop") && mt_fail_at(t, "expected 'outer loop'")))
			return -1;
		for (int k = 0; k < 3; k++) {
			snprintf(what, sizeof what, "vertex %llu", (unsigned long long)(3 * triangles + (uint64_t)k));
			if (stl_expect(t, "vertex", 4) || mt_position(t, 1, what, 3 * triangles + (uint64_t)k))
				return -1;
		}
		if (stl_expect(t, "endloop", 1) || stl_expect(t, "endfacet", 1))
			return -1;
		triangles++;
	}
	if (!triangles)
		return mt_fail_plain(t, "has no facets");
	return 0;
}
