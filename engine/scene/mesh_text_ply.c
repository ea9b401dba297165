/* PLY (ASCII and binary, either byte order) read strictly before assimp (mesh_text_check.c): a header of
 * the vertex element (scalar properties with x, y, z) and the face element (one integer list of vertex
 * indices), then exactly the data it declares: one line per element in ASCII, the declared bytes in
 * binary. assimp 5.2's PLY reader looped without end on header lines it could not parse (fuzz_mesh) and
 * sizes its arrays from the header's counts before the data is read. */
#include <ctype.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/mesh_text.h"

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

static enum ply_type ply_type_of(struct mesh_text *t, int i)
{
	for (size_t k = 0; k < sizeof ply_types / sizeof ply_types[0]; k++)
		if (mt_is(t, i, ply_types[k].name))
			return ply_types[k].type;
	return PLY_NONE;
}

static bool ply_integer(enum ply_type type)
{
	return type != PLY_F32 && type != PLY_F64;
}

static int ply_header(struct mesh_text *t, struct ply *ply)
{
	int r;
	char b[64];
	bool format = false, carriage_return = false;
	if ((r = mt_next_line(t)) <= 0 || !(t->n == 1 && mt_is(t, 0, "ply")))
		return r < 0 ? -1 : mt_fail_plain(t, "line 1: a PLY file starts with the line ply");
	carriage_return = t->crlf;
	for (;;) {
		if ((r = mt_next_line(t)) <= 0)
			return r < 0 ? -1 : mt_fail_plain(t, "the header has no end_header line");
		carriage_return |= t->crlf;
		if (t->n == 0)
			return mt_fail_at(t, "an empty line in the header");
		if (!format && !mt_is(t, 0, "format")) /* assimp reads the format from line 2 alone */
			return mt_fail_at(t, "the second line must be the format line");
		if (mt_is(t, 0, "comment") || mt_is(t, 0, "obj_info"))
			continue;
		if (mt_is(t, 0, "end_header") && t->n == 1)
			break;
		if (mt_is(t, 0, "format")) {
			if (format || t->n != 3 || !mt_is(t, 2, "1.0"))
				return mt_fail_at(t, "one format line: format ascii 1.0, binary_little_endian 1.0 or "
					       "binary_big_endian 1.0");
			format = true;
			ply->binary = !mt_is(t, 1, "ascii");
			ply->big_endian = mt_is(t, 1, "binary_big_endian");
			if (ply->binary && !ply->big_endian && !mt_is(t, 1, "binary_little_endian"))
				return mt_fail_at(t, "format '%s' is not ascii, binary_little_endian or binary_big_endian",
					       mt_shown(t, 1, b, sizeof b));
			continue;
		}
		if (mt_is(t, 0, "element")) {
			const char *want = ply->elements == 0 ? "vertex" : "face";
			if (t->n != 3)
				return mt_fail_at(t, "an element line is: element NAME COUNT");
			if (ply->elements == 2 || !mt_is(t, 1, want))
				return mt_fail_at(t, "element '%s': aalab reads the elements vertex and then face, no others",
					       mt_shown(t, 1, b, sizeof b));
			struct ply_element *e = &ply->e[ply->elements++];
			e->indices = -1;
			if (mt_count(t, 2, "the element count", UINT32_MAX, &e->count))
				return -1;
			continue;
		}
		if (!mt_is(t, 0, "property"))
			return mt_fail_at(t, "'%s' is not one of ply, format, comment, obj_info, element, property, end_header",
				       mt_shown(t, 0, b, sizeof b));
		if (ply->elements == 0)
			return mt_fail_at(t, "a property before any element");
		struct ply_element *e = &ply->e[ply->elements - 1];
		bool face = ply->elements == 2;
		if (e->property_count == PLY_MAX_PROPERTIES)
			return mt_fail_at(t, "more than %d properties in one element", PLY_MAX_PROPERTIES);
		struct ply_property *p = &e->props[e->property_count];
		bool list = mt_is(t, 1, "list");
		if (t->n != (list ? 5 : 3))
			return mt_fail_at(t, "a property line is: property TYPE NAME or property list COUNT_TYPE TYPE NAME");
		if (t->tlen[t->n - 1] >= sizeof p->name)
			return mt_fail_at(t, "a property name longer than %zu characters", sizeof p->name - 1);
		memcpy(p->name, t->tok[t->n - 1], t->tlen[t->n - 1]);
		p->name[t->tlen[t->n - 1]] = '\0';
		for (int k = 0; k < e->property_count; k++)
			if (strcmp(e->props[k].name, p->name) == 0)
				return mt_fail_at(t, "property '%s' is declared twice", p->name);
		if ((p->type = ply_type_of(t, t->n - 2)) == PLY_NONE)
			return mt_fail_at(t, "property '%s': '%s' is not a PLY type", p->name, mt_shown(t, t->n - 2, b, sizeof b));
		if (list) {
			p->count_type = ply_type_of(t, 2);
			bool index_list = strcmp(p->name, "vertex_indices") == 0 || strcmp(p->name, "vertex_index") == 0;
			if (!face || !index_list || e->indices >= 0)
				return mt_fail_at(t, "list property '%s': aalab reads one list, the face's vertex_indices",
					       p->name);
			if (!ply_integer(p->count_type) || !ply_integer(p->type))
				return mt_fail_at(t, "list property '%s' must have integer count and index types", p->name);
			e->indices = e->property_count;
		} else if (face && strcmp(p->name, "material_index") == 0) {
			return mt_fail_at(t, "property 'material_index': PLY materials are not read by aalab");
		}
		e->property_count++;
	}
	if (!format || ply->elements != 2)
		return mt_fail_at(t, "the header must declare the elements vertex and face");
	if (ply->binary && carriage_return)
		return mt_fail_plain(t, "a binary PLY header's lines must end with a line feed alone");
	const char *axes[3] = {"x", "y", "z"};
	for (int a = 0; a < 3; a++) {
		int found = 0;
		for (int k = 0; k < ply->e[0].property_count; k++)
			found += strcmp(ply->e[0].props[k].name, axes[a]) == 0;
		if (!found)
			return mt_fail_plain(t, "element vertex has no property %s", axes[a]);
	}
	if (ply->e[1].indices < 0)
		return mt_fail_plain(t, "element face has no list property vertex_indices");
	if (ply->e[0].count < 3 || ply->e[1].count < 1)
		return mt_fail_plain(t, "the header declares %llu vertices and %llu faces: a mesh needs at least 3 and 1",
				  (unsigned long long)ply->e[0].count, (unsigned long long)ply->e[1].count);
	return 0;
}

/* One value of a type as text: integers as whole numbers in the type's range, floats finite. */
static int ply_ascii_value(struct mesh_text *t, int i, enum ply_type type, const char *what, double *out)
{
	if (!ply_integer(type))
		return mt_number(t, i, what, out);
	static const double lo[] = {0, -128, 0, -32768, 0, -2147483648.0, 0}, hi[] = {0, 127, 255, 32767, 65535,
										     2147483647.0, 4294967295.0};
	char b[40];
	const char *s = t->tok[i];
	bool negative = t->tlen[i] > 1 && s[0] == '-';
	uint64_t v;
	if (!mt_parse_count(s + negative, t->tlen[i] - negative, UINT32_MAX + 1ull, &v) ||
	    (negative ? -(double)v : (double)v) < lo[type] || (negative ? -(double)v : (double)v) > hi[type])
		return mt_fail_at(t, "%s: '%s' is not a whole number from %.0f to %.0f", what, mt_shown(t, i, b, sizeof b),
			       lo[type], hi[type]);
	*out = negative ? -(double)v : (double)v;
	return 0;
}

static int ply_ascii(struct mesh_text *t, struct ply *ply)
{
	int r;
	for (int el = 0; el < 2; el++) {
		struct ply_element *e = &ply->e[el];
		const char *name = el ? "face" : "vertex";
		for (uint64_t i = 0; i < e->count; i++) {
			if ((r = mt_next_line(t)) <= 0)
				return r < 0 ? -1 : mt_fail_plain(t, "the header declares %llu %s elements, the file ends after %llu",
							       (unsigned long long)e->count, name, (unsigned long long)i);
			char what[64];
			snprintf(what, sizeof what, "%s %llu", name, (unsigned long long)i);
			int tok = 0;
			double xyz[3] = {0, 0, 0};
			for (int k = 0; k < e->property_count; k++) {
				const struct ply_property *p = &e->props[k];
				double v;
				if (tok >= t->n)
					return mt_fail_at(t, "%s ends before its property %s", what, p->name);
				if (k == e->indices) {
					if (ply_ascii_value(t, tok++, p->count_type, what, &v))
						return -1;
					if (v < 3 || tok + v > t->n)
						return mt_fail_at(t, "%s has %.0f vertices (at least 3, and the line has %d values "
							       "after the count)", what, v, t->n - tok);
					for (int c = 0; c < (int)v; c++) {
						double index;
						if (ply_ascii_value(t, tok++, p->type, what, &index))
							return -1;
						if (index < 0 || index >= (double)ply->e[0].count)
							return mt_fail_at(t, "%s names vertex %.0f, but the file has %llu vertices", what,
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
				return mt_fail_at(t, "%s has %d values, its properties take %d", what, t->n, tok);
			if (!el && (fabs(xyz[0]) > POSITION_MAX || fabs(xyz[1]) > POSITION_MAX || fabs(xyz[2]) > POSITION_MAX))
				return mt_fail_at(t, "vertex %llu is at (%g, %g, %g): positions must be within %g of the origin",
					       (unsigned long long)i, xyz[0], xyz[1], xyz[2], POSITION_MAX);
		}
	}
	while ((r = mt_next_line(t)) > 0)
		if (t->n)
			return mt_fail_at(t, "more data after the %llu faces the header declares",
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

static int ply_binary(struct mesh_text *t, struct ply *ply)
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
			return mt_fail_plain(t, "the header declares %llu %s elements of at least %llu bytes, more than the "
					  "%zu bytes of data left", (unsigned long long)e->count, name,
					  (unsigned long long)least, left - (size_t)(at - data));
		for (uint64_t i = 0; i < e->count; i++) {
			double xyz[3] = {0, 0, 0};
			for (int k = 0; k < e->property_count; k++) {
				const struct ply_property *p = &e->props[k];
				enum ply_type type = k == e->indices ? p->count_type : p->type;
				size_t here = (size_t)(at - data); /* the byte of the data this value starts at */
				if (here + (size_t)ply_size[type] > left)
					return mt_fail_plain(t, "%s %llu (byte %zu of the data): the file ends in property %s", name,
							  (unsigned long long)i, here, p->name);
				double v = ply_read(at, type, ply->big_endian);
				if (!(fabs(v) <= FLT_MAX))
					return mt_fail_plain(t, "%s %llu (byte %zu of the data): property %s is not a finite number",
							  name, (unsigned long long)i, here, p->name);
				at += ply_size[type];
				for (int a = 0; a < 3 && !el; a++)
					if (strcmp(p->name, (const char *[]){"x", "y", "z"}[a]) == 0)
						xyz[a] = v;
				if (k != e->indices)
					continue;
				if (v < 3)
					return mt_fail_plain(t, "face %llu (byte %zu of the data) has %.0f vertices, at least 3",
							  (unsigned long long)i, here, v);
				if ((size_t)(at - data) + (uint64_t)v * (size_t)ply_size[p->type] > left)
					return mt_fail_plain(t, "face %llu (byte %zu of the data): the file ends in its %.0f indices",
							  (unsigned long long)i, here, v);
				for (uint64_t c = 0; c < (uint64_t)v; c++, at += ply_size[p->type]) {
					double index = ply_read(at, p->type, ply->big_endian);
					if (index < 0 || index >= (double)ply->e[0].count)
						return mt_fail_plain(t, "face %llu (byte %zu of the data) names vertex %.0f, but the "
								  "file has %llu vertices", (unsigned long long)i,
								  (size_t)(at - data), index, (unsigned long long)ply->e[0].count);
				}
			}
			if (!el && (fabs(xyz[0]) > POSITION_MAX || fabs(xyz[1]) > POSITION_MAX || fabs(xyz[2]) > POSITION_MAX))
				return mt_fail_plain(t, "vertex %llu is at (%g, %g, %g): positions must be within %g of the origin",
						  (unsigned long long)i, xyz[0], xyz[1], xyz[2], POSITION_MAX);
		}
	}
	if ((size_t)(at - data) != left)
		return mt_fail_plain(t, "%zu bytes after the last face the header declares", left - (size_t)(at - data));
	return 0;
}

int mt_check_ply(struct mesh_text *t)
{
	struct ply *ply = calloc(1, sizeof *ply);
	if (!ply)
		return mt_fail_plain(t, "out of memory");
	int rc = ply_header(t, ply);
	if (rc == 0)
		rc = ply->binary ? ply_binary(t, ply) : ply_ascii(t, ply);
	free(ply);
	return rc;
}
