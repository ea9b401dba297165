/* OBJ (+ .mtl), OFF, PLY (ASCII and binary) and STL (ASCII and binary) read strictly by aalab before
 * assimp 5.2 sees them. Its readers trust the file: an OFF face of more than 9 vertices leaves faces without
 * indices that crash its post-processing, an OFF file without its keyword whose vertex count starts with 4
 * is read one number off, a header count allocates before the data is there, a binary STL count wraps
 * 32-bit arithmetic, a PLY header it cannot parse makes it loop (fuzz_mesh, tests/fuzz). So every file
 * here must be in one form that assimp and aalab read the same way: counts that match what follows, every
 * index in range, every number finite (positions within 1e7), faces of at least 3 vertices, declarations
 * that make sense, text that is text, binary lengths that add up. Anything else is refused, naming the
 * line (or element and byte offset) and what is wrong. Nothing is allocated from a count in the file.
 * This file: lines, tokens and numbers, and the entry points; one file per format (mesh_text_*.c). */
#include "scene/mesh_text_check.h"

#include <ctype.h>
#include <errno.h>
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "scene/mesh_file.h"
#include "scene/mesh_text.h"
#include "scene/scene.h"
#include "util/file_open.h"

#define TEXT_MAX_LINE 65536

/* ---------------------------------------------------------------- lines and tokens */

int mt_fail_at(struct mesh_text *t, const char *fmt, ...)
{
	int k = snprintf(t->why, t->why_size, "line %d: ", t->line);
	va_list ap;
	va_start(ap, fmt);
	if (k >= 0 && (size_t)k < t->why_size)
		vsnprintf(t->why + k, t->why_size - (size_t)k, fmt, ap);
	va_end(ap);
	return -1;
}

int mt_fail_plain(struct mesh_text *t, const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(t->why, t->why_size, fmt, ap);
	va_end(ap);
	return -1;
}

/* The next line into t's tokens: 1, 0 at the end of the data, -1 (refused) on a byte that is not text,
 * a carriage return not before a line feed, or a line over max_line. */
int mt_next_line(struct mesh_text *t)
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
		return mt_fail_at(t, "longer than %zu characters", t->max_line);
	t->n = 0;
	for (const char *c = start; c < stop; c++) {
		unsigned char b = (unsigned char)*c;
		if (b == ' ' || b == '\t')
			continue;
		if (b < 0x20 || b == 0x7f || (b >= 0x80 && t->ascii_only))
			return mt_fail_at(t, "holds a byte that is not text (0x%02x at column %zu)", b, (size_t)(c - start) + 1);
		if (c == start || c[-1] == ' ' || c[-1] == '\t') {
			if (t->n == MAX_TOKENS)
				return mt_fail_at(t, "has more than %d values", MAX_TOKENS);
			t->tok[t->n] = c;
			t->tlen[t->n++] = 0;
		}
		t->tlen[t->n - 1]++;
	}
	return 1;
}

/* Tokens from the first that starts with '#' on are a comment. */
void mt_drop_comment(struct mesh_text *t)
{
	for (int i = 0; i < t->n; i++)
		if (t->tok[i][0] == '#') {
			t->n = i;
			return;
		}
}

bool mt_is(const struct mesh_text *t, int i, const char *word)
{
	return i < t->n && t->tlen[i] == strlen(word) && memcmp(t->tok[i], word, t->tlen[i]) == 0;
}

/* A token for messages, cut short. */
const char *mt_shown(const struct mesh_text *t, int i, char *buf, size_t size)
{
	size_t n = t->tlen[i] < size - 1 ? t->tlen[i] : size - 1;
	memcpy(buf, t->tok[i], n);
	buf[n] = '\0';
	return buf;
}

/* A decimal number as assimp's fast_atof and strtod both read it alike: [+-] digits [. digits] [e [+-]
 * digits] (or .digits); no nan, inf, hex or trailing text. */
bool mt_parse_number(const char *s, size_t n, double *out)
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
int mt_number(struct mesh_text *t, int i, const char *what, double *out)
{
	char b[40];
	if (!mt_parse_number(t->tok[i], t->tlen[i], out) || !(fabs(*out) <= FLT_MAX))
		return mt_fail_at(t, "%s: '%s' is not a finite number", what, mt_shown(t, i, b, sizeof b));
	return 0;
}

/* Three numbers from token i: a position, finite and within 1e7 of the origin. */
int mt_position(struct mesh_text *t, int i, const char *what, uint64_t vertex)
{
	double p[3];
	for (int k = 0; k < 3; k++)
		if (mt_number(t, i + k, what, &p[k]))
			return -1;
	if (fabs(p[0]) > POSITION_MAX || fabs(p[1]) > POSITION_MAX || fabs(p[2]) > POSITION_MAX)
		return mt_fail_at(t, "vertex %llu is at (%g, %g, %g): positions must be within %g of the origin",
			       (unsigned long long)vertex, p[0], p[1], p[2], POSITION_MAX);
	return 0;
}

/* Digits only (what assimp's strtoul10 reads whole), at most max. */
bool mt_parse_count(const char *s, size_t n, uint64_t max, uint64_t *out)
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

int mt_count(struct mesh_text *t, int i, const char *what, uint64_t max, uint64_t *out)
{
	char b[40];
	if (!mt_parse_count(t->tok[i], t->tlen[i], max, out))
		return mt_fail_at(t, "%s: '%s' is not a whole number from 0 to %llu", what, mt_shown(t, i, b, sizeof b),
			       (unsigned long long)max);
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
	struct mesh_text *t = calloc(1, sizeof *t);
	if (!t) {
		snprintf(why, why_size, "out of memory");
		return -1;
	}
	*t = (struct mesh_text){.p = data, .end = data + size, .max_line = TEXT_MAX_LINE, .ascii_only = true,
			   .why = why, .why_size = why_size};
	int rc;
	switch (format) {
	case AA_MESH_FORMAT_OBJ:
		t->ascii_only = false;
		rc = mt_check_obj(t, library, ctx);
		break;
	case AA_MESH_FORMAT_MTL:
		t->ascii_only = false;
		rc = mt_check_mtl(t);
		break;
	case AA_MESH_FORMAT_OFF: rc = mt_check_off(t); break;
	case AA_MESH_FORMAT_PLY: rc = mt_check_ply(t); break;
	case AA_MESH_FORMAT_STL: rc = mt_check_stl(t); break;
	default: rc = mt_fail_plain(t, "is not OBJ, OFF, PLY or STL");
	}
	free(t);
	return rc;
}

/* The whole file in memory (the scene loader has checked its size). */
static char *read_all(const char *path, size_t *size, struct aa_error *e)
{
	struct aa_error oe = {0};
	FILE *f = aa_file_fopen_regular(path, "", &oe); /* never blocks on a FIFO */
	struct stat st;
	if (!f && oe.code == AA_ERR_INVALID) {
		aa_error_set(e, AA_ERR_INVALID, "", "is not a regular file (a FIFO, socket or device)");
		return NULL;
	}
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
