/* OFF read strictly before assimp (mesh_text_check.c): [ST][C][N]OFF alone on its first line, the
 * vertex, face and edge counts, then exactly that many vertex and face lines. assimp 5.2 takes a leading 4
 * of a count for its 4OFF flag when the keyword is missing, copies lines into 4096 bytes (one past on a
 * longer one), reads a comment or blank line among the data as a vertex or face, and drops faces of more
 * than 9 vertices, leaving faces without indices that crash its post-processing (fuzz_mesh). */
#include <ctype.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/mesh_text.h"

#define OFF_MAX_LINE 4000 /* assimp's OFF reader copies lines into 4096 bytes and writes one past a longer one */
#define OFF_MAX_FACE 9    /* assimp's OFF reader drops larger faces and leaves faces without indices behind */

int mt_check_off(struct mesh_text *t)
{
	int r;
	t->max_line = OFF_MAX_LINE;
	while ((r = mt_next_line(t)) > 0 && (t->n == 0 || t->tok[0][0] == '#'))
		;
	if (r <= 0)
		return r ? -1 : mt_fail_plain(t, "is empty: an OFF file starts with OFF and the vertex, face and edge counts");
	/* [ST][C][N]OFF alone on its line; a file without it is refused (assimp takes a leading 4 of the
	 * vertex count for its 4OFF flag and reads every count one number off) */
	const char *k = t->tok[0];
	size_t kl = t->tlen[0];
	bool uv = kl >= 2 && k[0] == 'S' && k[1] == 'T';
	k += uv ? 2 : 0, kl -= uv ? 2 : 0;
	bool colors = kl >= 1 && k[0] == 'C';
	k += colors, kl -= colors;
	bool normals = kl >= 1 && k[0] == 'N';
	k += normals, kl -= normals;
	mt_drop_comment(t);
	if (kl != 3 || memcmp(k, "OFF", 3) != 0 || t->n != 1)
		return mt_fail_at(t, "the file must start with OFF (or COFF, NOFF, STOFF and their combinations) alone on "
			       "its line");
	while ((r = mt_next_line(t)) > 0 && (mt_drop_comment(t), t->n == 0))
		;
	if (r <= 0)
		return r ? -1 : mt_fail_plain(t, "ends before the vertex, face and edge counts");
	uint64_t vertices, faces, edges;
	if (t->n != 3)
		return mt_fail_at(t, "the counts line must hold 3 whole numbers (vertices, faces, edges), it has %d values",
			       t->n);
	if (mt_count(t, 0, "vertex count", UINT32_MAX, &vertices) || mt_count(t, 1, "face count", UINT32_MAX, &faces) ||
	    mt_count(t, 2, "edge count", UINT32_MAX, &edges))
		return -1;
	if (vertices < 3 || faces < 1)
		return mt_fail_at(t, "the counts say %llu vertices and %llu faces: a mesh needs at least 3 and 1",
			       (unsigned long long)vertices, (unsigned long long)faces);
	/* each vertex or face is a line of at least 6 bytes */
	if ((vertices + faces) * 6 > (uint64_t)(t->end - t->p) + 1)
		return mt_fail_at(t, "the counts say %llu vertices and %llu faces, more than the file's remaining %zu bytes "
			       "can hold", (unsigned long long)vertices, (unsigned long long)faces,
			       (size_t)(t->end - t->p));
	int per_vertex = 3 + (normals ? 3 : 0) + (colors ? 4 : 0) + (uv ? 2 : 0);
	bool first = true;
	for (uint64_t i = 0; i < vertices + faces;) {
		if ((r = mt_next_line(t)) <= 0) {
			if (r)
				return -1;
			return i < vertices ? mt_fail_plain(t, "the counts say %llu vertices, the file ends after %llu",
							 (unsigned long long)vertices, (unsigned long long)i)
					    : mt_fail_plain(t, "the counts say %llu faces, the file ends after %llu",
							 (unsigned long long)faces, (unsigned long long)(i - vertices));
		}
		if (t->len == 0) /* assimp skips empty lines, */
			continue;
		mt_drop_comment(t);
		if (first && t->n == 0) /* and spaces and comments only before the first vertex */
			continue;
		first = false;
		if (t->n == 0)
			return mt_fail_at(t, "a comment or blank line among the vertices and faces (assimp reads it as one)");
		char what[64];
		if (i < vertices) {
			snprintf(what, sizeof what, "vertex %llu", (unsigned long long)i);
			if (t->n != per_vertex)
				return mt_fail_at(t, "%s must have %d values (x y z%s%s%s), it has %d", what, per_vertex,
					       normals ? " nx ny nz" : "", colors ? " r g b a" : "", uv ? " u v" : "", t->n);
			if (mt_position(t, 0, what, i))
				return -1;
			double v;
			for (int k2 = 3; k2 < t->n; k2++)
				if (mt_number(t, k2, what, &v))
					return -1;
		} else {
			uint64_t f = i - vertices, n, index;
			snprintf(what, sizeof what, "face %llu", (unsigned long long)f);
			if (mt_count(t, 0, what, UINT32_MAX, &n))
				return -1;
			if (n < 3 || n > OFF_MAX_FACE)
				return mt_fail_at(t, "%s has %llu vertices: OFF faces must have 3 to %d", what,
					       (unsigned long long)n, OFF_MAX_FACE);
			if ((uint64_t)t->n < 1 + n || (uint64_t)t->n > 1 + n + 4)
				return mt_fail_at(t, "%s says %llu vertices, the line has %d indices and colour values", what,
					       (unsigned long long)n, t->n - 1);
			for (uint64_t k2 = 1; k2 <= n; k2++) {
				if (mt_count(t, (int)k2, what, UINT32_MAX, &index))
					return -1;
				if (index >= vertices)
					return mt_fail_at(t, "%s names vertex %llu, but the file has %llu vertices", what,
						       (unsigned long long)index, (unsigned long long)vertices);
			}
			double v;
			for (int k2 = (int)n + 1; k2 < t->n; k2++)
				if (mt_number(t, k2, what, &v))
					return -1;
		}
		i++;
	}
	while ((r = mt_next_line(t)) > 0)
		if (mt_drop_comment(t), t->n)
			return mt_fail_at(t, "more data after the %llu faces the counts declare", (unsigned long long)faces);
	return r;
}
