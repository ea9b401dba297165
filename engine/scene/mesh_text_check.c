/* OBJ (+ .mtl), OFF, PLY (ASCII and binary) and STL (ASCII and binary) read strictly by aalab before
 * assimp 5.2 sees them. Its readers trust the file: an OFF face of more than 9 vertices leaves faces without
 * indices that crash its post-processing, an OFF file without its keyword whose vertex count starts with 4
 * is read one number off, a header count allocates before the data is there, a binary STL count wraps
 * 32-bit arithmetic, a PLY header it cannot parse makes it loop (fuzz_mesh, tests/fuzz). So every file
 * here must be in one form that assimp and aalab read the same way: counts that match what follows, every
 * index in range, every number finite (positions within 1e7), faces of at least 3 vertices, declarations
 * that make sense, text that is text, binary lengths that add up. Anything else is refused, naming the
 * line (or element and byte offset) and what is wrong. Nothing is allocated from a count in the file. */
#include "mesh_text_check.h"

#include <ctype.h>
#include <errno.h>
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "mesh_file.h"
#include "scene.h"

#define POSITION_MAX 1e7  /* as every number in a scene file */
#define MAX_TOKENS 1024   /* values on one line */
#define OFF_MAX_LINE 4000 /* assimp's OFF reader copies lines into 4096 bytes and writes one past a longer one */
#define TEXT_MAX_LINE 65536
#define OFF_MAX_FACE 9 /* assimp's OFF reader drops larger faces and leaves faces without indices behind */

/* ---------------------------------------------------------------- lines and tokens */

struct text {
	const char *p, *end; /* what is left to read */
	int line;            /* the line last read, 1-based */
	size_t max_line;
	bool ascii_only; /* bytes from 0x80 up refused (OFF, PLY, STL); OBJ and .mtl names may be UTF-8 */
	char *why;
	size_t why_size;
	/* the line last read, split at spaces and tabs */
	bool crlf; /* it ended with a carriage return and a line feed */
	size_t len;
	int n;
	const char *tok[MAX_TOKENS];
	size_t tlen[MAX_TOKENS];
};

__attribute__((format(printf, 2, 3))) static int fail_at(struct text *t, const char *fmt, ...)
{
	int k = snprintf(t->why, t->why_size, "line %d: ", t->line);
	va_list ap;
	va_start(ap, fmt);
	if (k >= 0 && (size_t)k < t->why_size)
		vsnprintf(t->why + k, t->why_size - (size_t)k, fmt, ap);
	va_end(ap);
	return -1;
}

__attribute__((format(printf, 2, 3))) static int fail_plain(struct text *t, const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(t->why, t->why_size, fmt, ap);
	va_end(ap);
	return -1;
}

/* The next line into t's tokens: 1, 0 at the end of the data, -1 (refused) on a byte that is not text,
 * a carriage return not before a line feed, or a line over max_line. */
static int next_line(struct text *t)
{
	if (t->p >= t->end)
		return 0;
	t->line++;
	const char *start = t->p, *nl = memchr(start, '\n', (size_t)(t->end - start));
	const char *stop = nl ? nl : t->end;
	t->p = nl ? nl + 1 : t->end;
	t->crlf = stop > start && stop[-1] == '\r';
	if (t->crlf)
		stop--;
	t->len = (size_t)(stop - start);
	if (t->len > t->max_line)
		return fail_at(t, "longer than %zu characters", t->max_line);
	t->n = 0;
	for (const char *c = start; c < stop; c++) {
		unsigned char b = (unsigned char)*c;
		if (b == ' ' || b == '\t')
			continue;
		if (b < 0x20 || b == 0x7f || (b >= 0x80 && t->ascii_only))
			return fail_at(t, "holds a byte that is not text (0x%02x at column %zu)", b, (size_t)(c - start) + 1);
		if (c == start || c[-1] == ' ' || c[-1] == '\t') {
			if (t->n == MAX_TOKENS)
				return fail_at(t, "has more than %d values", MAX_TOKENS);
			t->tok[t->n] = c;
			t->tlen[t->n++] = 0;
		}
		t->tlen[t->n - 1]++;
	}
	return 1;
}

/* Tokens from the first that starts with '#' on are a comment. */
static void drop_comment(struct text *t)
{
	for (int i = 0; i < t->n; i++)
		if (t->tok[i][0] == '#') {
			t->n = i;
			return;
		}
}

static bool is(const struct text *t, int i, const char *word)
{
	return i < t->n && t->tlen[i] == strlen(word) && memcmp(t->tok[i], word, t->tlen[i]) == 0;
}

/* A token for messages, cut short. */
static const char *shown(const struct text *t, int i, char *buf, size_t size)
{
	size_t n = t->tlen[i] < size - 1 ? t->tlen[i] : size - 1;
	memcpy(buf, t->tok[i], n);
	buf[n] = '\0';
	return buf;
}

/* A decimal number as assimp's fast_atof and strtod both read it alike: [+-] digits [. digits] [e [+-]
 * digits] (or .digits); no nan, inf, hex or trailing text. */
static bool parse_number(const char *s, size_t n, double *out)
{
	size_t i = 0, digits = 0;
	if (i < n && (s[i] == '+' || s[i] == '-'))
		i++;
	for (; i < n && isdigit((unsigned char)s[i]); i++)
		digits++;
	if (i < n && s[i] == '.')
		for (i++; i < n && isdigit((unsigned char)s[i]); i++)
			digits++;
	if (!digits)
		return false;
	if (i < n && (s[i] == 'e' || s[i] == 'E')) {
		i++;
		if (i < n && (s[i] == '+' || s[i] == '-'))
			i++;
		size_t e0 = i;
		while (i < n && isdigit((unsigned char)s[i]))
			i++;
		if (i == e0)
			return false;
	}
	char buf[80];
	if (i != n || n >= sizeof buf)
		return false;
	memcpy(buf, s, n);
	buf[n] = '\0';
	*out = strtod(buf, NULL);
	return true;
}

/* Token i as a number a float holds; what names the value in the message. */
static int number(struct text *t, int i, const char *what, double *out)
{
	char b[40];
	if (!parse_number(t->tok[i], t->tlen[i], out) || !(fabs(*out) <= FLT_MAX))
		return fail_at(t, "%s: '%s' is not a finite number", what, shown(t, i, b, sizeof b));
	return 0;
}

/* Three numbers from token i: a position, finite and within 1e7 of the origin. */
static int position(struct text *t, int i, const char *what, uint64_t vertex)
{
	double p[3];
	for (int k = 0; k < 3; k++)
		if (number(t, i + k, what, &p[k]))
			return -1;
	if (fabs(p[0]) > POSITION_MAX || fabs(p[1]) > POSITION_MAX || fabs(p[2]) > POSITION_MAX)
		return fail_at(t, "vertex %llu is at (%g, %g, %g): positions must be within %g of the origin",
			       (unsigned long long)vertex, p[0], p[1], p[2], POSITION_MAX);
	return 0;
}

/* Digits only (what assimp's strtoul10 reads whole), at most max. */
static bool parse_count(const char *s, size_t n, uint64_t max, uint64_t *out)
{
	uint64_t v = 0;
	if (n == 0 || n > 19)
		return false;
	for (size_t i = 0; i < n; i++) {
		if (!isdigit((unsigned char)s[i]))
			return false;
		v = v * 10 + (uint64_t)(s[i] - '0');
	}
	*out = v;
	return v <= max;
}

static int count(struct text *t, int i, const char *what, uint64_t max, uint64_t *out)
{
	char b[40];
	if (!parse_count(t->tok[i], t->tlen[i], max, out))
		return fail_at(t, "%s: '%s' is not a whole number from 0 to %llu", what, shown(t, i, b, sizeof b),
			       (unsigned long long)max);
	return 0;
}

/* ---------------------------------------------------------------- OFF */

static int check_off(struct text *t)
{
	int r;
	while ((r = next_line(t)) > 0 && (t->n == 0 || t->tok[0][0] == '#'))
		;
	if (r <= 0)
		return r ? -1 : fail_plain(t, "is empty: an OFF file starts with OFF and the vertex, face and edge counts");
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
	drop_comment(t);
	if (kl != 3 || memcmp(k, "OFF", 3) != 0 || t->n != 1)
		return fail_at(t, "the file must start with OFF (or COFF, NOFF, STOFF and their combinations) alone on "
			       "its line");
	while ((r = next_line(t)) > 0 && (drop_comment(t), t->n == 0))
		;
	if (r <= 0)
		return r ? -1 : fail_plain(t, "ends before the vertex, face and edge counts");
	uint64_t vertices, faces, edges;
	if (t->n != 3)
		return fail_at(t, "the counts line must hold 3 whole numbers (vertices, faces, edges), it has %d values",
			       t->n);
	if (count(t, 0, "vertex count", UINT32_MAX, &vertices) || count(t, 1, "face count", UINT32_MAX, &faces) ||
	    count(t, 2, "edge count", UINT32_MAX, &edges))
		return -1;
	if (vertices < 3 || faces < 1)
		return fail_at(t, "the counts say %llu vertices and %llu faces: a mesh needs at least 3 and 1",
			       (unsigned long long)vertices, (unsigned long long)faces);
	/* each vertex or face is a line of at least 6 bytes */
	if ((vertices + faces) * 6 > (uint64_t)(t->end - t->p) + 1)
		return fail_at(t, "the counts say %llu vertices and %llu faces, more than the file's remaining %zu bytes "
			       "can hold", (unsigned long long)vertices, (unsigned long long)faces,
			       (size_t)(t->end - t->p));
	int per_vertex = 3 + (normals ? 3 : 0) + (colors ? 4 : 0) + (uv ? 2 : 0);
	bool first = true;
	for (uint64_t i = 0; i < vertices + faces;) {
		if ((r = next_line(t)) <= 0) {
			if (r)
				return -1;
			return i < vertices ? fail_plain(t, "the counts say %llu vertices, the file ends after %llu",
							 (unsigned long long)vertices, (unsigned long long)i)
					    : fail_plain(t, "the counts say %llu faces, the file ends after %llu",
							 (unsigned long long)faces, (unsigned long long)(i - vertices));
		}
		if (t->len == 0) /* assimp skips empty lines, */
			continue;
		drop_comment(t);
		if (first && t->n == 0) /* and spaces and comments only before the first vertex */
			continue;
		first = false;
		if (t->n == 0)
			return fail_at(t, "a comment or blank line among the vertices and faces (assimp reads it as one)");
		char what[64];
		if (i < vertices) {
			snprintf(what, sizeof what, "vertex %llu", (unsigned long long)i);
			if (t->n != per_vertex)
				return fail_at(t, "%s must have %d values (x y z%s%s%s), it has %d", what, per_vertex,
					       normals ? " nx ny nz" : "", colors ? " r g b a" : "", uv ? " u v" : "", t->n);
			if (position(t, 0, what, i))
				return -1;
			double v;
			for (int k2 = 3; k2 < t->n; k2++)
				if (number(t, k2, what, &v))
					return -1;
		} else {
			uint64_t f = i - vertices, n, index;
			snprintf(what, sizeof what, "face %llu", (unsigned long long)f);
			if (count(t, 0, what, UINT32_MAX, &n))
				return -1;
			if (n < 3 || n > OFF_MAX_FACE)
				return fail_at(t, "%s has %llu vertices: OFF faces must have 3 to %d", what,
					       (unsigned long long)n, OFF_MAX_FACE);
			if ((uint64_t)t->n < 1 + n || (uint64_t)t->n > 1 + n + 4)
				return fail_at(t, "%s says %llu vertices, the line has %d indices and colour values", what,
					       (unsigned long long)n, t->n - 1);
			for (uint64_t k2 = 1; k2 <= n; k2++) {
				if (count(t, (int)k2, what, UINT32_MAX, &index))
					return -1;
				if (index >= vertices)
					return fail_at(t, "%s names vertex %llu, but the file has %llu vertices", what,
						       (unsigned long long)index, (unsigned long long)vertices);
			}
			double v;
			for (int k2 = (int)n + 1; k2 < t->n; k2++)
				if (number(t, k2, what, &v))
					return -1;
		}
		i++;
	}
	while ((r = next_line(t)) > 0)
		if (drop_comment(t), t->n)
			return fail_at(t, "more data after the %llu faces the counts declare", (unsigned long long)faces);
	return r;
}

/* ---------------------------------------------------------------- OBJ and .mtl */

struct obj_refs {
	uint64_t max[3];  /* the largest 1-based index named of v, vt, vn */
	int line[3];      /* and where */
};

static const char *const obj_kinds[3] = {"vertex (v)", "texture coordinate (vt)", "normal (vn)"};

/* One vertex of a face (a, a/b, a//c, a/b/c) or line (a, a/b): the indices against what is defined so
 * far (negative ones) or at the end (positive ones). Returns its form (bit 0 vt, bit 1 vn) or -1. */
static int obj_corner(struct text *t, int i, const uint64_t have[3], struct obj_refs *refs, bool lines)
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
		if (!parse_count(s + negative, (size_t)(stop - s - negative), UINT32_MAX, &v) || v == 0)
			return fail_at(t, "'%s' is not a vertex reference (v, v/vt, v//vn or v/vt/vn, each a whole "
				       "number other than 0)", shown(t, i, b, sizeof b));
		if (negative) {
			if (v > have[kind])
				return fail_at(t, "'%s' names %s %lld, before the first", shown(t, i, b, sizeof b),
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
		return fail_at(t, "'%s' is not a vertex reference", shown(t, i, b, sizeof b));
	return form;
}

static int check_obj(struct text *t, aa_mesh_library_fn library, void *ctx)
{
	uint64_t have[3] = {0, 0, 0}, faces = 0;
	struct obj_refs refs = {{0, 0, 0}, {0, 0, 0}};
	int r;
	char b[40];
	while ((r = next_line(t)) > 0) {
		if (t->n == 0 || t->tok[0][0] == '#')
			continue;
		if (t->tok[t->n - 1][t->tlen[t->n - 1] - 1] == '\\')
			return fail_at(t, "a line continued with \\ is not supported");
		if (is(t, 0, "v")) {
			char what[64];
			snprintf(what, sizeof what, "vertex %llu (v)", (unsigned long long)have[0]);
			if (t->n != 4 && t->n != 5 && t->n != 7)
				return fail_at(t, "%s must be x y z, x y z w or x y z r g b, it has %d values", what, t->n - 1);
			double v[6];
			for (int k = 1; k < t->n; k++)
				if (number(t, k, what, &v[k - 1]))
					return -1;
			if (t->n == 5) { /* homogeneous: assimp divides by w */
				if (!(fabs(v[3]) >= 1e-30))
					return fail_at(t, "%s has w = %g", what, v[3]);
				for (int k = 0; k < 3; k++)
					v[k] /= v[3];
			}
			if (fabs(v[0]) > POSITION_MAX || fabs(v[1]) > POSITION_MAX || fabs(v[2]) > POSITION_MAX)
				return fail_at(t, "vertex %llu is at (%g, %g, %g): positions must be within %g of the origin",
					       (unsigned long long)have[0], v[0], v[1], v[2], POSITION_MAX);
			have[0]++;
		} else if (is(t, 0, "vt") || is(t, 0, "vn")) {
			bool normal = t->tok[0][1] == 'n';
			char what[64];
			snprintf(what, sizeof what, "%s %llu", normal ? "normal (vn)" : "texture coordinate (vt)",
				 (unsigned long long)have[normal ? 2 : 1]);
			if (normal ? t->n != 4 : t->n != 3 && t->n != 4)
				return fail_at(t, "%s must have %s values, it has %d", what, normal ? "3" : "2 or 3", t->n - 1);
			double v;
			for (int k = 1; k < t->n; k++)
				if (number(t, k, what, &v))
					return -1;
			have[normal ? 2 : 1]++;
		} else if (is(t, 0, "f") || is(t, 0, "l") || is(t, 0, "p")) {
			char kind = t->tok[0][0];
			int least = kind == 'f' ? 3 : kind == 'l' ? 2 : 1;
			if (t->n - 1 < least)
				return fail_at(t, "a %s needs at least %d vertices, it has %d",
					       kind == 'f' ? "face (f)" : kind == 'l' ? "line (l)" : "point (p)", least, t->n - 1);
			int form = -1;
			for (int k = 1; k < t->n; k++) {
				int c = obj_corner(t, k, have, &refs, kind != 'f');
				if (c < 0)
					return -1;
				if (kind == 'p' && c)
					return fail_at(t, "a point (p) names vertices alone");
				if (form >= 0 && c != form)
					return fail_at(t, "'%s' is not in the form of the face's first vertex",
						       shown(t, k, b, sizeof b));
				form = c;
			}
			faces += kind == 'f';
		} else if (is(t, 0, "o") || is(t, 0, "g")) {
			if (is(t, 0, "o") && t->n < 2)
				return fail_at(t, "an object (o) needs a name");
		} else if (is(t, 0, "s")) {
			uint64_t v;
			if (t->n != 2 || !(is(t, 1, "off") || parse_count(t->tok[1], t->tlen[1], UINT32_MAX, &v)))
				return fail_at(t, "a smoothing group (s) is off or a whole number");
		} else if (is(t, 0, "usemtl")) {
			if (t->n != 2)
				return fail_at(t, "usemtl names one material");
		} else if (is(t, 0, "mtllib")) {
			if (t->n < 2)
				return fail_at(t, "mtllib names no material library");
			for (int k = 1; k < t->n; k++) {
				char name[1024];
				if (t->tlen[k] >= sizeof name)
					return fail_at(t, "a material library name longer than %zu characters", sizeof name - 1);
				memcpy(name, t->tok[k], t->tlen[k]);
				name[t->tlen[k]] = '\0';
				if (library && (r = library(ctx, name, t->line)) != 0)
					return r;
			}
		} else {
			return fail_at(t, "'%s' is not an OBJ statement aalab reads (v, vt, vn, f, l, p, o, g, s, usemtl, "
				       "mtllib, #)", shown(t, 0, b, sizeof b));
		}
	}
	if (r < 0)
		return -1;
	for (int k = 0; k < 3; k++)
		if (refs.max[k] > have[k]) {
			t->line = refs.line[k];
			return fail_at(t, "a face names a vertex that does not exist: %s %llu, but the file has %llu",
				       obj_kinds[k], (unsigned long long)refs.max[k], (unsigned long long)have[k]);
		}
	if (!faces)
		return fail_plain(t, "has no faces (f)");
	return 0;
}

static int check_mtl(struct text *t)
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
	while ((r = next_line(t)) > 0) {
		if (t->n == 0 || t->tok[0][0] == '#')
			continue;
		if (is(t, 0, "newmtl")) {
			if (t->n != 2)
				return fail_at(t, "newmtl names one material");
			material = true;
			continue;
		}
		int kind = 0; /* 1 colour, 2 number, 3 map */
		for (int k = 0; !kind && colors[k]; k++)
			kind = is(t, 0, colors[k]) ? 1 : 0;
		for (int k = 0; !kind && scalars[k]; k++)
			kind = is(t, 0, scalars[k]) ? 2 : 0;
		for (int k = 0; !kind && maps[k]; k++)
			kind = is(t, 0, maps[k]) ? 3 : 0;
		if (!kind)
			return fail_at(t, "'%s' is not a material statement aalab reads", shown(t, 0, b, sizeof b));
		if (!material)
			return fail_at(t, "'%s' before the first newmtl", shown(t, 0, b, sizeof b));
		char what[64];
		snprintf(what, sizeof what, "%s", shown(t, 0, b, sizeof b));
		int first = 1 + (kind == 2 && is(t, 1, "-halo"));
		int values = t->n - first;
		if (kind == 3) {
			if (values < 1)
				return fail_at(t, "%s names no texture file", what);
			continue;
		}
		if (kind == 1 ? values != 1 && values != 3 : values != 1)
			return fail_at(t, "%s must have %s, it has %d values", what, kind == 1 ? "1 or 3 numbers" : "1 number",
				       values);
		double v;
		for (int k = first; k < t->n; k++)
			if (number(t, k, what, &v))
				return -1;
	}
	return r;
}

/* ---------------------------------------------------------------- PLY */

enum ply_type { PLY_NONE, PLY_I8, PLY_U8, PLY_I16, PLY_U16, PLY_I32, PLY_U32, PLY_F32, PLY_F64 };
static const struct {
	const char *name;
	enum ply_type type;
} ply_types[] = {{"char", PLY_I8},    {"int8", PLY_I8},     {"uchar", PLY_U8},   {"uint8", PLY_U8},
		 {"short", PLY_I16},  {"int16", PLY_I16},   {"ushort", PLY_U16}, {"uint16", PLY_U16},
		 {"int", PLY_I32},    {"int32", PLY_I32},   {"uint", PLY_U32},   {"uint32", PLY_U32},
		 {"float", PLY_F32},  {"float32", PLY_F32}, {"double", PLY_F64}, {"float64", PLY_F64}};
static const int ply_size[] = {0, 1, 1, 2, 2, 4, 4, 4, 8};

#define PLY_MAX_PROPERTIES 64

struct ply_property {
	char name[64];
	enum ply_type type, count_type; /* count_type: a list's */
};

struct ply_element {
	uint64_t count;
	int property_count;
	int indices; /* face: the list of vertex indices */
	struct ply_property props[PLY_MAX_PROPERTIES];
};

struct ply {
	bool binary, big_endian;
	int elements; /* 1 once the vertex element is declared, 2 with the face element */
	struct ply_element e[2];
};

static enum ply_type ply_type_of(struct text *t, int i)
{
	for (size_t k = 0; k < sizeof ply_types / sizeof ply_types[0]; k++)
		if (is(t, i, ply_types[k].name))
			return ply_types[k].type;
	return PLY_NONE;
}

static bool ply_integer(enum ply_type type)
{
	return type != PLY_F32 && type != PLY_F64;
}

static int ply_header(struct text *t, struct ply *ply)
{
	int r;
	char b[64];
	bool format = false, carriage_return = false;
	if ((r = next_line(t)) <= 0 || !(t->n == 1 && is(t, 0, "ply")))
		return r < 0 ? -1 : fail_plain(t, "line 1: a PLY file starts with the line ply");
	carriage_return = t->crlf;
	for (;;) {
		if ((r = next_line(t)) <= 0)
			return r < 0 ? -1 : fail_plain(t, "the header has no end_header line");
		carriage_return |= t->crlf;
		if (t->n == 0)
			return fail_at(t, "an empty line in the header");
		if (!format && !is(t, 0, "format")) /* assimp reads the format from line 2 alone */
			return fail_at(t, "the second line must be the format line");
		if (is(t, 0, "comment") || is(t, 0, "obj_info"))
			continue;
		if (is(t, 0, "end_header") && t->n == 1)
			break;
		if (is(t, 0, "format")) {
			if (format || t->n != 3 || !is(t, 2, "1.0"))
				return fail_at(t, "one format line: format ascii 1.0, binary_little_endian 1.0 or "
					       "binary_big_endian 1.0");
			format = true;
			ply->binary = !is(t, 1, "ascii");
			ply->big_endian = is(t, 1, "binary_big_endian");
			if (ply->binary && !ply->big_endian && !is(t, 1, "binary_little_endian"))
				return fail_at(t, "format '%s' is not ascii, binary_little_endian or binary_big_endian",
					       shown(t, 1, b, sizeof b));
			continue;
		}
		if (is(t, 0, "element")) {
			const char *want = ply->elements == 0 ? "vertex" : "face";
			if (t->n != 3)
				return fail_at(t, "an element line is: element NAME COUNT");
			if (ply->elements == 2 || !is(t, 1, want))
				return fail_at(t, "element '%s': aalab reads the elements vertex and then face, no others",
					       shown(t, 1, b, sizeof b));
			struct ply_element *e = &ply->e[ply->elements++];
			e->indices = -1;
			if (count(t, 2, "the element count", UINT32_MAX, &e->count))
				return -1;
			continue;
		}
		if (!is(t, 0, "property"))
			return fail_at(t, "'%s' is not one of ply, format, comment, obj_info, element, property, end_header",
				       shown(t, 0, b, sizeof b));
		if (ply->elements == 0)
			return fail_at(t, "a property before any element");
		struct ply_element *e = &ply->e[ply->elements - 1];
		bool face = ply->elements == 2;
		if (e->property_count == PLY_MAX_PROPERTIES)
			return fail_at(t, "more than %d properties in one element", PLY_MAX_PROPERTIES);
		struct ply_property *p = &e->props[e->property_count];
		bool list = is(t, 1, "list");
		if (t->n != (list ? 5 : 3))
			return fail_at(t, "a property line is: property TYPE NAME or property list COUNT_TYPE TYPE NAME");
		if (t->tlen[t->n - 1] >= sizeof p->name)
			return fail_at(t, "a property name longer than %zu characters", sizeof p->name - 1);
		memcpy(p->name, t->tok[t->n - 1], t->tlen[t->n - 1]);
		p->name[t->tlen[t->n - 1]] = '\0';
		for (int k = 0; k < e->property_count; k++)
			if (strcmp(e->props[k].name, p->name) == 0)
				return fail_at(t, "property '%s' is declared twice", p->name);
		if ((p->type = ply_type_of(t, t->n - 2)) == PLY_NONE)
			return fail_at(t, "property '%s': '%s' is not a PLY type", p->name, shown(t, t->n - 2, b, sizeof b));
		if (list) {
			p->count_type = ply_type_of(t, 2);
			bool index_list = strcmp(p->name, "vertex_indices") == 0 || strcmp(p->name, "vertex_index") == 0;
			if (!face || !index_list || e->indices >= 0)
				return fail_at(t, "list property '%s': aalab reads one list, the face's vertex_indices",
					       p->name);
			if (!ply_integer(p->count_type) || !ply_integer(p->type))
				return fail_at(t, "list property '%s' must have integer count and index types", p->name);
			e->indices = e->property_count;
		} else if (face && strcmp(p->name, "material_index") == 0) {
			return fail_at(t, "property 'material_index': PLY materials are not read by aalab");
		}
		e->property_count++;
	}
	if (!format || ply->elements != 2)
		return fail_at(t, "the header must declare the elements vertex and face");
	if (ply->binary && carriage_return)
		return fail_plain(t, "a binary PLY header's lines must end with a line feed alone");
	const char *axes[3] = {"x", "y", "z"};
	for (int a = 0; a < 3; a++) {
		int found = 0;
		for (int k = 0; k < ply->e[0].property_count; k++)
			found += strcmp(ply->e[0].props[k].name, axes[a]) == 0;
		if (!found)
			return fail_plain(t, "element vertex has no property %s", axes[a]);
	}
	if (ply->e[1].indices < 0)
		return fail_plain(t, "element face has no list property vertex_indices");
	if (ply->e[0].count < 3 || ply->e[1].count < 1)
		return fail_plain(t, "the header declares %llu vertices and %llu faces: a mesh needs at least 3 and 1",
				  (unsigned long long)ply->e[0].count, (unsigned long long)ply->e[1].count);
	return 0;
}

/* One value of a type as text: integers as whole numbers in the type's range, floats finite. */
static int ply_ascii_value(struct text *t, int i, enum ply_type type, const char *what, double *out)
{
	if (!ply_integer(type))
		return number(t, i, what, out);
	static const double lo[] = {0, -128, 0, -32768, 0, -2147483648.0, 0}, hi[] = {0, 127, 255, 32767, 65535,
										     2147483647.0, 4294967295.0};
	char b[40];
	const char *s = t->tok[i];
	bool negative = t->tlen[i] > 1 && s[0] == '-';
	uint64_t v;
	if (!parse_count(s + negative, t->tlen[i] - negative, UINT32_MAX + 1ull, &v) ||
	    (negative ? -(double)v : (double)v) < lo[type] || (negative ? -(double)v : (double)v) > hi[type])
		return fail_at(t, "%s: '%s' is not a whole number from %.0f to %.0f", what, shown(t, i, b, sizeof b),
			       lo[type], hi[type]);
	*out = negative ? -(double)v : (double)v;
	return 0;
}

static int ply_ascii(struct text *t, struct ply *ply)
{
	int r;
	for (int el = 0; el < 2; el++) {
		struct ply_element *e = &ply->e[el];
		const char *name = el ? "face" : "vertex";
		for (uint64_t i = 0; i < e->count; i++) {
			if ((r = next_line(t)) <= 0)
				return r < 0 ? -1 : fail_plain(t, "the header declares %llu %s elements, the file ends after %llu",
							       (unsigned long long)e->count, name, (unsigned long long)i);
			char what[64];
			snprintf(what, sizeof what, "%s %llu", name, (unsigned long long)i);
			int tok = 0;
			double xyz[3] = {0, 0, 0};
			for (int k = 0; k < e->property_count; k++) {
				const struct ply_property *p = &e->props[k];
				double v;
				if (tok >= t->n)
					return fail_at(t, "%s ends before its property %s", what, p->name);
				if (k == e->indices) {
					if (ply_ascii_value(t, tok++, p->count_type, what, &v))
						return -1;
					if (v < 3 || tok + v > t->n)
						return fail_at(t, "%s has %.0f vertices (at least 3, and the line has %d values "
							       "after the count)", what, v, t->n - tok);
					for (int c = 0; c < (int)v; c++) {
						double index;
						if (ply_ascii_value(t, tok++, p->type, what, &index))
							return -1;
						if (index < 0 || index >= (double)ply->e[0].count)
							return fail_at(t, "%s names vertex %.0f, but the file has %llu vertices", what,
								       index, (unsigned long long)ply->e[0].count);
					}
					continue;
				}
				if (ply_ascii_value(t, tok++, p->type, what, &v))
					return -1;
				for (int a = 0; a < 3 && !el; a++)
					if (strcmp(p->name, (const char *[]){"x", "y", "z"}[a]) == 0)
						xyz[a] = v;
			}
			if (tok != t->n)
				return fail_at(t, "%s has %d values, its properties take %d", what, t->n, tok);
			if (!el && (fabs(xyz[0]) > POSITION_MAX || fabs(xyz[1]) > POSITION_MAX || fabs(xyz[2]) > POSITION_MAX))
				return fail_at(t, "vertex %llu is at (%g, %g, %g): positions must be within %g of the origin",
					       (unsigned long long)i, xyz[0], xyz[1], xyz[2], POSITION_MAX);
		}
	}
	while ((r = next_line(t)) > 0)
		if (t->n)
			return fail_at(t, "more data after the %llu faces the header declares",
				       (unsigned long long)ply->e[1].count);
	return r;
}

static double ply_read(const unsigned char *p, enum ply_type type, bool big_endian)
{
	unsigned char b[8];
	int n = ply_size[type];
	for (int k = 0; k < n; k++)
		b[k] = p[big_endian ? n - 1 - k : k];
	uint64_t u = 0;
	for (int k = n - 1; k >= 0; k--)
		u = u << 8 | b[k];
	switch (type) {
	case PLY_I8: return (int8_t)u;
	case PLY_U8: return (uint8_t)u;
	case PLY_I16: return (int16_t)u;
	case PLY_U16: return (uint16_t)u;
	case PLY_I32: return (int32_t)u;
	case PLY_U32: return (uint32_t)u;
	case PLY_F32: {
		uint32_t w = (uint32_t)u;
		float f;
		memcpy(&f, &w, sizeof f);
		return f;
	}
	case PLY_F64: {
		double d;
		memcpy(&d, &u, sizeof d);
		return d;
	}
	default: return 0;
	}
}

static int ply_binary(struct text *t, struct ply *ply)
{
	const unsigned char *data = (const unsigned char *)t->p, *at = data;
	size_t left = (size_t)(t->end - t->p);
	for (int el = 0; el < 2; el++) {
		struct ply_element *e = &ply->e[el];
		const char *name = el ? "face" : "vertex";
		uint64_t least = 0; /* bytes one element takes at the least */
		for (int k = 0; k < e->property_count; k++)
			least += k == e->indices ? (uint64_t)ply_size[e->props[k].count_type] + 3u * ply_size[e->props[k].type]
						 : (uint64_t)ply_size[e->props[k].type];
		if (e->count * least > (uint64_t)(left - (size_t)(at - data)))
			return fail_plain(t, "the header declares %llu %s elements of at least %llu bytes, more than the "
					  "%zu bytes of data left", (unsigned long long)e->count, name,
					  (unsigned long long)least, left - (size_t)(at - data));
		for (uint64_t i = 0; i < e->count; i++) {
			double xyz[3] = {0, 0, 0};
			for (int k = 0; k < e->property_count; k++) {
				const struct ply_property *p = &e->props[k];
				enum ply_type type = k == e->indices ? p->count_type : p->type;
				size_t here = (size_t)(at - data); /* the byte of the data this value starts at */
				if (here + (size_t)ply_size[type] > left)
					return fail_plain(t, "%s %llu (byte %zu of the data): the file ends in property %s", name,
							  (unsigned long long)i, here, p->name);
				double v = ply_read(at, type, ply->big_endian);
				if (!(fabs(v) <= FLT_MAX))
					return fail_plain(t, "%s %llu (byte %zu of the data): property %s is not a finite number",
							  name, (unsigned long long)i, here, p->name);
				at += ply_size[type];
				for (int a = 0; a < 3 && !el; a++)
					if (strcmp(p->name, (const char *[]){"x", "y", "z"}[a]) == 0)
						xyz[a] = v;
				if (k != e->indices)
					continue;
				if (v < 3)
					return fail_plain(t, "face %llu (byte %zu of the data) has %.0f vertices, at least 3",
							  (unsigned long long)i, here, v);
				if ((size_t)(at - data) + (uint64_t)v * (size_t)ply_size[p->type] > left)
					return fail_plain(t, "face %llu (byte %zu of the data): the file ends in its %.0f indices",
							  (unsigned long long)i, here, v);
				for (uint64_t c = 0; c < (uint64_t)v; c++, at += ply_size[p->type]) {
					double index = ply_read(at, p->type, ply->big_endian);
					if (index < 0 || index >= (double)ply->e[0].count)
						return fail_plain(t, "face %llu (byte %zu of the data) names vertex %.0f, but the "
								  "file has %llu vertices", (unsigned long long)i,
								  (size_t)(at - data), index, (unsigned long long)ply->e[0].count);
				}
			}
			if (!el && (fabs(xyz[0]) > POSITION_MAX || fabs(xyz[1]) > POSITION_MAX || fabs(xyz[2]) > POSITION_MAX))
				return fail_plain(t, "vertex %llu is at (%g, %g, %g): positions must be within %g of the origin",
						  (unsigned long long)i, xyz[0], xyz[1], xyz[2], POSITION_MAX);
		}
	}
	if ((size_t)(at - data) != left)
		return fail_plain(t, "%zu bytes after the last face the header declares", left - (size_t)(at - data));
	return 0;
}

static int check_ply(struct text *t)
{
	struct ply *ply = calloc(1, sizeof *ply);
	if (!ply)
		return fail_plain(t, "out of memory");
	int rc = ply_header(t, ply);
	if (rc == 0)
		rc = ply->binary ? ply_binary(t, ply) : ply_ascii(t, ply);
	free(ply);
	return rc;
}

/* ---------------------------------------------------------------- STL */

static float stl_float(const unsigned char *p)
{
	uint32_t u = (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
	float f;
	memcpy(&f, &u, sizeof f);
	return f;
}

static int check_stl_binary(struct text *t, uint64_t triangles)
{
	const unsigned char *p = (const unsigned char *)t->p + 84;
	if (triangles == 0)
		return fail_plain(t, "a binary STL file of no triangles");
	for (uint64_t i = 0; i < triangles; i++, p += 50) {
		float v[12];
		for (int k = 0; k < 12; k++)
			if (!isfinite(v[k] = stl_float(p + 4 * k)))
				return fail_plain(t, "triangle %llu (byte %llu) has a %s that is not a finite number",
						  (unsigned long long)i, (unsigned long long)(84 + 50 * i), k < 3 ? "normal" : "position");
		for (int k = 3; k < 12; k++)
			if (fabsf(v[k]) > POSITION_MAX)
				return fail_plain(t, "triangle %llu (byte %llu): vertex %llu is at (%g, %g, %g): positions must be "
						  "within %g of the origin", (unsigned long long)i,
						  (unsigned long long)(84 + 50 * i), (unsigned long long)(3 * i + (k - 3) / 3),
						  v[k - (k % 3)], v[k - (k % 3) + 1], v[k - (k % 3) + 2], POSITION_MAX);
	}
	return 0;
}

/* The next line that is not blank, which must start with `word` and have n tokens (n < 0: at least -n). */
static int stl_expect(struct text *t, const char *word, int n)
{
	int r;
	while ((r = next_line(t)) > 0 && t->n == 0)
		;
	if (r < 0)
		return -1;
	if (r == 0)
		return fail_plain(t, "ends where '%s' should be", word);
	if (!is(t, 0, word) || (n >= 0 ? t->n != n : t->n < -n))
		return fail_at(t, "expected '%s%s'", word, !strcmp(word, "facet") ? " normal nx ny nz" :
							    !strcmp(word, "vertex") ? " x y z" :
							    !strcmp(word, "outer") ? " loop" : "");
	return 0;
}

static int check_stl(struct text *t)
{
	size_t size = (size_t)(t->end - t->p);
	/* binary when the size is 84 + 50 x the count, as assimp decides (before looking for "solid") */
	if (size >= 84) {
		const unsigned char *c = (const unsigned char *)t->p + 80;
		uint32_t n = (uint32_t)c[0] | (uint32_t)c[1] << 8 | (uint32_t)c[2] << 16 | (uint32_t)c[3] << 24;
		if (84 + 50 * (uint64_t)n == size)
			return check_stl_binary(t, n);
		if ((uint32_t)(84u + 50u * n) == (uint32_t)size) /* assimp's 32-bit sum wraps to the size */
			return fail_plain(t, "binary STL header says %u triangles, which would be %llu bytes, the file has %zu",
					  n, (unsigned long long)(84 + 50 * (uint64_t)n), size);
	}
	const char *s = t->p;
	while (s < t->end && (*s == ' ' || *s == '\t')) /* as assimp: not line ends */
		s++;
	if (t->end - s < 5 || memcmp(s, "solid", 5) != 0) {
		if (size >= 84) {
			const unsigned char *c = (const unsigned char *)t->p + 80;
			uint32_t n = (uint32_t)c[0] | (uint32_t)c[1] << 8 | (uint32_t)c[2] << 16 | (uint32_t)c[3] << 24;
			return fail_plain(t, "is neither ASCII STL (starting with solid) nor binary STL: its header says %u "
					  "triangles, %llu bytes, the file has %zu", n,
					  (unsigned long long)(84 + 50 * (uint64_t)n), size);
		}
		return fail_plain(t, "is neither ASCII STL (starting with solid) nor binary STL (at least 84 bytes)");
	}
	uint64_t triangles = 0;
	if (stl_expect(t, "solid", -1))
		return -1;
	for (;;) {
		int r;
		while ((r = next_line(t)) > 0 && t->n == 0)
			;
		if (r <= 0)
			return r < 0 ? -1 : fail_plain(t, "ends before endsolid");
		if (is(t, 0, "endsolid")) {
			while ((r = next_line(t)) > 0 && t->n == 0)
				;
			if (r <= 0)
				break;
			if (!is(t, 0, "solid"))
				return fail_at(t, "expected 'solid' or the end of the file after endsolid");
			continue;
		}
		char what[64];
		snprintf(what, sizeof what, "triangle %llu normal", (unsigned long long)triangles);
		double v;
		if (!is(t, 0, "facet") || t->n != 5 || !is(t, 1, "normal"))
			return fail_at(t, "expected 'facet normal nx ny nz' or 'endsolid'");
		for (int k = 2; k < 5; k++)
			if (number(t, k, what, &v))
				return -1;
		if (stl_expect(t, "outer", 2) || (!is(t, 1, "loop") && fail_at(t, "expected 'outer loop'")))
			return -1;
		for (int k = 0; k < 3; k++) {
			snprintf(what, sizeof what, "vertex %llu", (unsigned long long)(3 * triangles + (uint64_t)k));
			if (stl_expect(t, "vertex", 4) || position(t, 1, what, 3 * triangles + (uint64_t)k))
				return -1;
		}
		if (stl_expect(t, "endloop", 1) || stl_expect(t, "endfacet", 1))
			return -1;
		triangles++;
	}
	if (!triangles)
		return fail_plain(t, "has no facets");
	return 0;
}

/* ---------------------------------------------------------------- entry points */

static bool ends_with(const char *s, const char *suffix)
{
	size_t a = strlen(s), b = strlen(suffix);
	return a >= b && strcasecmp(s + a - b, suffix) == 0;
}

enum aa_mesh_format aa_mesh_format_of(const char *path)
{
	return ends_with(path, ".obj") ? AA_MESH_FORMAT_OBJ : ends_with(path, ".mtl") ? AA_MESH_FORMAT_MTL :
	       ends_with(path, ".off") ? AA_MESH_FORMAT_OFF : ends_with(path, ".ply") ? AA_MESH_FORMAT_PLY :
	       ends_with(path, ".stl") ? AA_MESH_FORMAT_STL : AA_MESH_FORMAT_OTHER;
}

int aa_mesh_text_check(enum aa_mesh_format format, const char *data, size_t size, aa_mesh_library_fn library,
		       void *ctx, char *why, size_t why_size)
{
	struct text *t = calloc(1, sizeof *t);
	if (!t) {
		snprintf(why, why_size, "out of memory");
		return -1;
	}
	*t = (struct text){.p = data, .end = data + size, .max_line = TEXT_MAX_LINE, .ascii_only = true,
			   .why = why, .why_size = why_size};
	int rc;
	switch (format) {
	case AA_MESH_FORMAT_OBJ:
		t->ascii_only = false;
		rc = check_obj(t, library, ctx);
		break;
	case AA_MESH_FORMAT_MTL:
		t->ascii_only = false;
		rc = check_mtl(t);
		break;
	case AA_MESH_FORMAT_OFF:
		t->max_line = OFF_MAX_LINE;
		rc = check_off(t);
		break;
	case AA_MESH_FORMAT_PLY: rc = check_ply(t); break;
	case AA_MESH_FORMAT_STL: rc = check_stl(t); break;
	default: rc = fail_plain(t, "is not OBJ, OFF, PLY or STL");
	}
	free(t);
	return rc;
}

/* The whole file in memory (the scene loader has checked its size). */
static char *read_all(const char *path, size_t *size, struct aa_error *e)
{
	FILE *f = fopen(path, "rb");
	struct stat st;
	if (!f || fstat(fileno(f), &st) != 0) {
		aa_error_set(e, AA_ERR_IO, "", "cannot open: %s", strerror(errno));
		if (f)
			fclose(f);
		return NULL;
	}
	if ((uint64_t)st.st_size > AA_MESH_FILE_MAX_BYTES) {
		fclose(f);
		aa_error_set(e, AA_ERR_LIMIT, "", "is %lld bytes, over the limit of %u", (long long)st.st_size,
			     (unsigned)AA_MESH_FILE_MAX_BYTES);
		return NULL;
	}
	char *data = malloc((size_t)st.st_size + 1);
	*size = data ? fread(data, 1, (size_t)st.st_size, f) : 0;
	fclose(f);
	if (!data || *size != (size_t)st.st_size) {
		free(data);
		aa_error_set(e, AA_ERR_IO, "", "cannot be read");
		return NULL;
	}
	return data;
}

struct file_check {
	struct sj *s;
	struct aa_scene *scene;
	const char *path, *shown, *base_dir;
	bool missing_warn;
};

/* An OBJ file's mtllib: beside it, inside the scene's directory, and a good .mtl. */
static int check_library(void *ctx, const char *name, int line)
{
	struct file_check *c = ctx;
	char full[PATH_MAX];
	struct aa_error e = {0};
	if (aa_resolve_beside(c->path, c->base_dir, name, full, sizeof full, &e) != 0) {
		if (c->missing_warn && e.code == AA_ERR_NOT_FOUND) {
			aa_scene_warn(c->scene, "%s: line %d: material library '%s' not found: drawn without its materials",
				      c->shown, line, name);
			return 0;
		}
		return sj_fail(c->s, e.code, "mesh file '%s': line %d: material library (mtllib) %s", c->shown, line,
			       e.message);
	}
	size_t size;
	char *data = read_all(full, &size, &e), why[600];
	if (!data)
		return sj_fail(c->s, e.code, "mesh file '%s': line %d: material library '%s' %s", c->shown, line, name,
			       e.message);
	int rc = aa_mesh_text_check(AA_MESH_FORMAT_MTL, data, size, NULL, NULL, why, sizeof why);
	free(data);
	return rc ? sj_fail(c->s, AA_ERR_INVALID, "mesh file '%s': material library '%s': %s", c->shown, name, why) : 0;
}

int aa_mesh_text_check_file(struct sj *s, struct aa_scene *scene, const char *path, const char *shown,
			    const char *base_dir, bool missing_warn)
{
	struct file_check c = {s, scene, path, shown, base_dir, missing_warn};
	enum aa_mesh_format format = aa_mesh_format_of(path);
	if (format == AA_MESH_FORMAT_OTHER || format == AA_MESH_FORMAT_MTL)
		return sj_fail(s, AA_ERR_INVALID, "mesh file '%s' is not in a format aalab reads (glTF 2.0 .gltf or .glb, "
			       "OBJ .obj, PLY .ply, STL .stl, OFF .off)", shown);
	struct aa_error e = {0};
	size_t size;
	char *data = read_all(path, &size, &e), why[600];
	if (!data)
		return sj_fail(s, e.code, "mesh file '%s' %s", shown, e.message);
	why[0] = '\0';
	int rc = aa_mesh_text_check(format, data, size, check_library, &c, why, sizeof why);
	free(data);
	if (rc == -1 && why[0])
		return sj_fail(s, AA_ERR_INVALID, "mesh file '%s': %s", shown, why);
	return rc ? -1 : 0;
}
