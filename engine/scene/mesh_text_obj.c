/* OBJ and its .mtl libraries read strictly before assimp (mesh_text_check.c): the statements aalab
 * reads, each with the values it takes, every vertex reference in range (negative ones against what is
 * defined so far, positive ones against the whole file), at least one face. */
#include <ctype.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/mesh_text.h"

struct obj_refs {
	uint64_t max[3];  /* the largest 1-based index named of v, vt, vn */
	int line[3];      /* and where */
};

static const char *const obj_kinds[3] = {"vertex (v)", "texture coordinate (vt)", "normal (vn)"};

/* One vertex of a face (a, a/b, a//c, a/b/c) or line (a, a/b): the indices against what is defined so
 * far (negative ones) or at the end (positive ones). Returns its form (bit 0 vt, bit 1 vn) or -1. */
static int obj_corner(struct mesh_text *t, int i, const uint64_t have[3], struct obj_refs *refs, bool lines)
{
	const char *s = t->tok[i], *end = s + t->tlen[i];
	int form = 0, kind = 0;
	char b[40];
	while (kind < 3) {
		const char *slash = memchr(s, '/', (size_t)(end - s));
		const char *stop = slash ? slash : end;
		if (stop == s && kind == 1 && slash && !lines) { /* a//c */
			s = slash + 1, kind = 2;
			continue;
		}
		bool negative = stop > s && *s == '-';
		uint64_t v;
		if (!mt_parse_count(s + negative, (size_t)(stop - s - negative), UINT32_MAX, &v) || v == 0)
			return mt_fail_at(t, "'%s' is not a vertex reference (v, v/vt, v//vn or v/vt/vn, each a whole "
				       "number other than 0)", mt_shown(t, i, b, sizeof b));
		if (negative) {
			if (v > have[kind])
				return mt_fail_at(t, "'%s' names %s %lld, before the first", mt_shown(t, i, b, sizeof b),
					       obj_kinds[kind], -(long long)v);
		} else if (v > refs->max[kind]) {
			refs->max[kind] = v;
			refs->line[kind] = t->line;
		}
		form |= kind ? 1 << (kind - 1) : 0;
		if (!slash)
			break;
		s = slash + 1, kind++;
		if (kind == 2 && lines)
			break;
	}
	if (kind >= 3 || (lines && kind >= 2))
		return mt_fail_at(t, "'%s' is not a vertex reference", mt_shown(t, i, b, sizeof b));
	return form;
}

int mt_check_obj(struct mesh_text *t, aa_mesh_library_fn library, void *ctx)
{
	uint64_t have[3] = {0, 0, 0}, faces = 0;
	struct obj_refs refs = {{0, 0, 0}, {0, 0, 0}};
	int r;
	char b[40];
	while ((r = mt_next_line(t)) > 0) {
		if (t->n == 0 || t->tok[0][0] == '#')
			continue;
		if (t->tok[t->n - 1][t->tlen[t->n - 1] - 1] == '\\')
			return mt_fail_at(t, "a line continued with \\ is not supported");
		if (mt_is(t, 0, "v")) {
			char what[64];
			snprintf(what, sizeof what, "vertex %llu (v)", (unsigned long long)have[0]);
			if (t->n != 4 && t->n != 5 && t->n != 7)
				return mt_fail_at(t, "%s must be x y z, x y z w or x y z r g b, it has %d values", what, t->n - 1);
			double v[6];
			for (int k = 1; k < t->n; k++)
				if (mt_number(t, k, what, &v[k - 1]))
					return -1;
			if (t->n == 5) { /* homogeneous: assimp divides by w */
				if (!(fabs(v[3]) >= 1e-30))
					return mt_fail_at(t, "%s has w = %g", what, v[3]);
				for (int k = 0; k < 3; k++)
					v[k] /= v[3];
			}
			if (fabs(v[0]) > POSITION_MAX || fabs(v[1]) > POSITION_MAX || fabs(v[2]) > POSITION_MAX)
				return mt_fail_at(t, "vertex %llu is at (%g, %g, %g): positions must be within %g of the origin",
					       (unsigned long long)have[0], v[0], v[1], v[2], POSITION_MAX);
			have[0]++;
		} else if (mt_is(t, 0, "vt") || mt_is(t, 0, "vn")) {
			bool normal = t->tok[0][1] == 'n';
			char what[64];
			snprintf(what, sizeof what, "%s %llu", normal ? "normal (vn)" : "texture coordinate (vt)",
				 (unsigned long long)have[normal ? 2 : 1]);
			if (normal ? t->n != 4 : t->n != 3 && t->n != 4)
				return mt_fail_at(t, "%s must have %s values, it has %d", what, normal ? "3" : "2 or 3", t->n - 1);
			double v;
			for (int k = 1; k < t->n; k++)
				if (mt_number(t, k, what, &v))
					return -1;
			have[normal ? 2 : 1]++;
		} else if (mt_is(t, 0, "f") || mt_is(t, 0, "l") || mt_is(t, 0, "p")) {
			char kind = t->tok[0][0];
			int least = kind == 'f' ? 3 : kind == 'l' ? 2 : 1;
			if (t->n - 1 < least)
				return mt_fail_at(t, "a %s needs at least %d vertices, it has %d",
					       kind == 'f' ? "face (f)" : kind == 'l' ? "line (l)" : "point (p)", least, t->n - 1);
			int form = -1;
			for (int k = 1; k < t->n; k++) {
				int c = obj_corner(t, k, have, &refs, kind != 'f');
				if (c < 0)
					return -1;
				if (kind == 'p' && c)
					return mt_fail_at(t, "a point (p) names vertices alone");
				if (form >= 0 && c != form)
					return mt_fail_at(t, "'%s' is not in the form of the face's first vertex",
						       mt_shown(t, k, b, sizeof b));
				form = c;
			}
			faces += kind == 'f';
		} else if (mt_is(t, 0, "o") || mt_is(t, 0, "g")) {
			if (mt_is(t, 0, "o") && t->n < 2)
				return mt_fail_at(t, "an object (o) needs a name");
		} else if (mt_is(t, 0, "s")) {
			uint64_t v;
			if (t->n != 2 || !(mt_is(t, 1, "off") || mt_parse_count(t->tok[1], t->tlen[1], UINT32_MAX, &v)))
				return mt_fail_at(t, "a smoothing group (s) is off or a whole number");
		} else if (mt_is(t, 0, "usemtl")) {
			if (t->n != 2)
				return mt_fail_at(t, "usemtl names one material");
		} else if (mt_is(t, 0, "mtllib")) {
			if (t->n < 2)
				return mt_fail_at(t, "mtllib names no material library");
			for (int k = 1; k < t->n; k++) {
				char name[1024];
				if (t->tlen[k] >= sizeof name)
					return mt_fail_at(t, "a material library name longer than %zu characters", sizeof name - 1);
				memcpy(name, t->tok[k], t->tlen[k]);
				name[t->tlen[k]] = '\0';
				if (library && (r = library(ctx, name, t->line)) != 0)
					return r;
			}
		} else {
			return mt_fail_at(t, "'%s' is not an OBJ statement aalab reads (v, vt, vn, f, l, p, o, g, s, usemtl, "
				       "mtllib, #)", mt_shown(t, 0, b, sizeof b));
		}
	}
	if (r < 0)
		return -1;
	for (int k = 0; k < 3; k++)
		if (refs.max[k] > have[k]) {
			t->line = refs.line[k];
			return mt_fail_at(t, "a face names a vertex that does not exist: %s %llu, but the file has %llu",
				       obj_kinds[k], (unsigned long long)refs.max[k], (unsigned long long)have[k]);
		}
	if (!faces)
		return mt_fail_plain(t, "has no faces (f)");
	return 0;
}

int mt_check_mtl(struct mesh_text *t)
{
	static const char *const colors[] = {"Ka", "Kd", "Ks", "Ke", "Tf", NULL};
	static const char *const scalars[] = {"Ns", "Ni", "d", "Tr", "illum", "sharpness", "Pr", "Pm", "Ps", "Pc",
					      "Pcr", "aniso", "anisor", NULL};
	static const char *const maps[] = {"map_Ka", "map_Kd", "map_Ks", "map_Ke", "map_Ns", "map_d", "map_Tr",
					   "map_bump", "map_Bump", "bump", "norm", "map_Kn", "disp", "decal", "refl",
					   "map_Pr", "map_Pm", "map_Ps", "map_Pc", "map_Pcr", "map_disp", "map_refl", NULL};
	bool material = false;
	int r;
	char b[40];
	while ((r = mt_next_line(t)) > 0) {
		if (t->n == 0 || t->tok[0][0] == '#')
			continue;
		if (mt_is(t, 0, "newmtl")) {
			if (t->n != 2)
				return mt_fail_at(t, "newmtl names one material");
			material = true;
			continue;
		}
		int kind = 0; /* 1 colour, 2 number, 3 map */
		for (int k = 0; !kind && colors[k]; k++)
			kind = mt_is(t, 0, colors[k]) ? 1 : 0;
		for (int k = 0; !kind && scalars[k]; k++)
			kind = mt_is(t, 0, scalars[k]) ? 2 : 0;
		for (int k = 0; !kind && maps[k]; k++)
			kind = mt_is(t, 0, maps[k]) ? 3 : 0;
		if (!kind)
			return mt_fail_at(t, "'%s' is not a material statement aalab reads", mt_shown(t, 0, b, sizeof b));
		if (!material)
			return mt_fail_at(t, "'%s' before the first newmtl", mt_shown(t, 0, b, sizeof b));
		char what[64];
		snprintf(what, sizeof what, "%s", mt_shown(t, 0, b, sizeof b));
		int first = 1 + (kind == 2 && mt_is(t, 1, "-halo"));
		int values = t->n - first;
		if (kind == 3) {
			if (values < 1)
				return mt_fail_at(t, "%s names no texture file", what);
			continue;
		}
		if (kind == 1 ? values != 1 && values != 3 : values != 1)
			return mt_fail_at(t, "%s must have %s, it has %d values", what, kind == 1 ? "1 or 3 numbers" : "1 number",
				       values);
		double v;
		for (int k = first; k < t->n; k++)
			if (mt_number(t, k, what, &v))
				return -1;
	}
	return r;
}
