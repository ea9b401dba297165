/* Procedural meshes: shapes that stress anti-aliasing (thin wires, slats, near-horizontal edges, spokes)
 * built from a few primitives (grids, disks, boxes, tubes) with parameters read from the scene file. */
#include "scene/mesh_procedural.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI_F 3.14159265358979f

const char *const aa_mesh_type_names[] = {"plane", "box",    "sphere", "cylinder", "wires", "fence",
					  "blinds", "stairs", "wheel", "hairball", "file", NULL};

void aa_mesh_free(struct aa_mesh *mesh)
{
	if (!mesh)
		return;
	free(mesh->vertices);
	free(mesh->indices);
	free(mesh->skin);
	mesh->vertices = NULL;
	mesh->indices = NULL;
	mesh->skin = NULL;
	mesh->vertex_count = mesh->index_count = 0;
}

void aa_mesh_compute_bounds(struct aa_mesh *m)
{
	for (int k = 0; k < 3; k++) {
		m->bounds_min[k] = m->vertex_count ? m->vertices[0].position[k] : 0.0f;
		m->bounds_max[k] = m->bounds_min[k];
	}
	for (uint32_t v = 1; v < m->vertex_count; v++)
		for (int k = 0; k < 3; k++) {
			m->bounds_min[k] = fminf(m->bounds_min[k], m->vertices[v].position[k]);
			m->bounds_max[k] = fmaxf(m->bounds_max[k], m->vertices[v].position[k]);
		}
}

/* ---------------------------------------------------------------- mesh builder */

struct mb {
	struct aa_mesh *m;
	uint32_t vcap, icap;
	uint64_t max_triangles;
	bool overflow; /* more triangles than allowed, or out of memory: the build fails */
};

static uint32_t mb_vertex(struct mb *b, mat4 xf, vec3 p, vec3 n, float u, float v)
{
	struct aa_mesh *m = b->m;
	if (b->overflow)
		return 0;
	if (m->vertex_count == b->vcap) {
		uint32_t cap = b->vcap ? b->vcap * 2 : 256;
		if ((uint64_t)cap > 3 * b->max_triangles + 1024) {
			b->overflow = true;
			return 0;
		}
		struct aa_vertex *nv = realloc(m->vertices, cap * sizeof *nv);
		if (!nv) {
			b->overflow = true;
			return 0;
		}
		m->vertices = nv;
		b->vcap = cap;
	}
	vec3 wp = mat4_transform_point(xf, p);
	vec3 wn = v3_normalize(mat4_transform_dir(xf, n));
	struct aa_vertex *out = &m->vertices[m->vertex_count];
	out->position[0] = wp.x, out->position[1] = wp.y, out->position[2] = wp.z;
	out->normal[0] = wn.x, out->normal[1] = wn.y, out->normal[2] = wn.z;
	out->uv[0] = u, out->uv[1] = v;
	out->tangent[0] = 1.0f, out->tangent[1] = out->tangent[2] = 0.0f, out->tangent[3] = 1.0f; /* no normal maps */
	for (int c = 0; c < 4; c++)
		out->color[c] = 1.0f;
	return m->vertex_count++;
}

static vec3 vpos(const struct aa_mesh *m, uint32_t i)
{
	const float *p = m->vertices[i].position;
	return v3(p[0], p[1], p[2]);
}

static vec3 vnormal(const struct aa_mesh *m, uint32_t i)
{
	const float *n = m->vertices[i].normal;
	return v3(n[0], n[1], n[2]);
}

/* Adds a triangle facing the way its vertex normals point (so generators need not track winding) and
 * drops degenerate ones (sphere poles, zero-length edges). */
static void mb_tri(struct mb *b, uint32_t i0, uint32_t i1, uint32_t i2)
{
	struct aa_mesh *m = b->m;
	if (b->overflow || i0 >= m->vertex_count || i1 >= m->vertex_count || i2 >= m->vertex_count)
		return;
	vec3 e1 = v3_sub(vpos(m, i1), vpos(m, i0)), e2 = v3_sub(vpos(m, i2), vpos(m, i0));
	vec3 g = v3_cross(e1, e2);
	float scale = fmaxf(v3_dot(e1, e1), v3_dot(e2, e2));
	if (!(v3_length(g) > 1e-6f * scale))
		return;
	vec3 ns = v3_add(v3_add(vnormal(m, i0), vnormal(m, i1)), vnormal(m, i2));
	if (v3_dot(g, ns) < 0.0f) {
		uint32_t t = i1;
		i1 = i2;
		i2 = t;
	}
	if (m->index_count / 3 >= b->max_triangles) {
		b->overflow = true;
		return;
	}
	if (m->index_count + 3 > b->icap) {
		uint32_t cap = b->icap ? b->icap * 2 : 768;
		uint32_t *ni = realloc(m->indices, cap * sizeof *ni);
		if (!ni) {
			b->overflow = true;
			return;
		}
		m->indices = ni;
		b->icap = cap;
	}
	m->indices[m->index_count++] = i0;
	m->indices[m->index_count++] = i1;
	m->indices[m->index_count++] = i2;
}

/* A quad given in cyclic order (either direction). */
static void mb_quad(struct mb *b, uint32_t i0, uint32_t i1, uint32_t i2, uint32_t i3)
{
	mb_tri(b, i0, i1, i2);
	mb_tri(b, i0, i2, i3);
}

/* A parametric surface over (u,v) in [0,1]^2 sampled on a cols x rows grid. */
typedef void (*surface_fn)(const void *ctx, float u, float v, vec3 *p, vec3 *n, float uv[2]);

static void mb_surface(struct mb *b, mat4 xf, int cols, int rows, surface_fn f, const void *ctx)
{
	uint32_t base = b->m->vertex_count;
	for (int r = 0; r <= rows; r++)
		for (int c = 0; c <= cols; c++) {
			vec3 p, n;
			float uv[2];
			f(ctx, (float)c / (float)cols, (float)r / (float)rows, &p, &n, uv);
			mb_vertex(b, xf, p, n, uv[0], uv[1]);
		}
	uint32_t stride = (uint32_t)cols + 1;
	for (int r = 0; r < rows; r++)
		for (int c = 0; c < cols; c++) {
			uint32_t i = base + (uint32_t)r * stride + (uint32_t)c;
			mb_quad(b, i, i + 1, i + stride + 1, i + stride);
		}
}

/* A flat disk of `radius` at height y in the xz plane, facing +y (up) or -y. */
static void mb_disk(struct mb *b, mat4 xf, float y, float radius, int segments, bool up)
{
	vec3 n = v3(0, up ? 1.0f : -1.0f, 0);
	uint32_t c = mb_vertex(b, xf, v3(0, y, 0), n, 0.5f, 0.5f);
	for (int j = 0; j <= segments; j++) {
		float a = 2.0f * PI_F * (float)j / (float)segments, sa = sinf(a), ca = cosf(a);
		mb_vertex(b, xf, v3(radius * sa, y, radius * ca), n, 0.5f + 0.5f * sa, 0.5f - 0.5f * ca);
	}
	for (int j = 0; j < segments; j++)
		mb_tri(b, c, c + 1 + (uint32_t)j, c + 2 + (uint32_t)j);
}

struct cyl_ctx { float radius, height; };

static void cylinder_side(const void *ctx, float u, float v, vec3 *p, vec3 *n, float uv[2])
{
	const struct cyl_ctx *c = ctx;
	float a = 2.0f * PI_F * u;
	*n = v3(sinf(a), 0, cosf(a));
	*p = v3(c->radius * n->x, c->height * (0.5f - v), c->radius * n->z);
	uv[0] = u, uv[1] = v;
}

/* A cylinder along the y axis of xf, centred on its origin. */
static void mb_cylinder(struct mb *b, mat4 xf, float radius, float height, int segments, bool caps)
{
	struct cyl_ctx c = {radius, height};
	mb_surface(b, xf, segments, 1, cylinder_side, &c);
	if (caps) {
		mb_disk(b, xf, height * 0.5f, radius, segments, true);
		mb_disk(b, xf, -height * 0.5f, radius, segments, false);
	}
}

/* A rigid transform whose y axis runs from p0 to p1, with its origin at their midpoint. */
static mat4 frame_between(vec3 p0, vec3 p1)
{
	vec3 d = v3_normalize(v3_sub(p1, p0));
	vec3 helper = fabsf(d.y) < 0.9f ? v3(0, 1, 0) : v3(1, 0, 0);
	vec3 x = v3_normalize(v3_cross(helper, d));
	vec3 z = v3_cross(x, d);
	mat4 r = mat4_identity();
	r.m[0] = x.x, r.m[1] = x.y, r.m[2] = x.z;
	r.m[4] = d.x, r.m[5] = d.y, r.m[6] = d.z;
	r.m[8] = z.x, r.m[9] = z.y, r.m[10] = z.z;
	vec3 mid = v3_scale(v3_add(p0, p1), 0.5f);
	r.m[12] = mid.x, r.m[13] = mid.y, r.m[14] = mid.z;
	return r;
}

static void mb_tube(struct mb *b, vec3 p0, vec3 p1, float radius, int sides)
{
	mb_cylinder(b, frame_between(p0, p1), radius, v3_length(v3_sub(p1, p0)), sides, true);
}

/* A box of `size` centred on xf's origin: 24 vertices so each face has its own normal and 0..1 uvs. */
static void mb_box(struct mb *b, mat4 xf, vec3 size, const float uv_repeat[2])
{
	static const float faces[6][9] = {
		/* normal, tangent (u), bitangent (v up) */
		{1, 0, 0, 0, 0, -1, 0, 1, 0},  {-1, 0, 0, 0, 0, 1, 0, 1, 0}, {0, 1, 0, 1, 0, 0, 0, 0, -1},
		{0, -1, 0, 1, 0, 0, 0, 0, 1}, {0, 0, 1, 1, 0, 0, 0, 1, 0},  {0, 0, -1, -1, 0, 0, 0, 1, 0},
	};
	vec3 h = v3_scale(size, 0.5f);
	for (int f = 0; f < 6; f++) {
		vec3 n = v3(faces[f][0], faces[f][1], faces[f][2]);
		vec3 t = v3(faces[f][3], faces[f][4], faces[f][5]);
		vec3 bt = v3(faces[f][6], faces[f][7], faces[f][8]);
		vec3 c = v3(n.x * h.x, n.y * h.y, n.z * h.z);
		vec3 tu = v3(t.x * h.x, t.y * h.y, t.z * h.z), tv = v3(bt.x * h.x, bt.y * h.y, bt.z * h.z);
		uint32_t i[4];
		static const float corner[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
		for (int k = 0; k < 4; k++) {
			vec3 p = v3_add(c, v3_add(v3_scale(tu, corner[k][0]), v3_scale(tv, corner[k][1])));
			i[k] = mb_vertex(b, xf, p, n, 0.5f * (corner[k][0] + 1) * uv_repeat[0],
					 0.5f * (1 - corner[k][1]) * uv_repeat[1]);
		}
		mb_quad(b, i[0], i[1], i[2], i[3]);
	}
}

static const float uv_one[2] = {1, 1};

/* A flat cap closing a tube ring: the ring at centre c spanned by axes x, z, facing `normal`. */
static void mb_ring_cap(struct mb *b, vec3 c, vec3 x, vec3 z, float radius, int sides, vec3 normal)
{
	mat4 id = mat4_identity();
	uint32_t ci = mb_vertex(b, id, c, normal, 0.5f, 0.5f);
	for (int j = 0; j <= sides; j++) {
		float ang = 2.0f * PI_F * (float)j / (float)sides, sa = sinf(ang), ca = cosf(ang);
		vec3 dir = v3_add(v3_scale(x, sa), v3_scale(z, ca));
		mb_vertex(b, id, v3_add(c, v3_scale(dir, radius)), normal, 0.5f + 0.5f * sa, 0.5f - 0.5f * ca);
	}
	for (int j = 0; j < sides; j++)
		mb_tri(b, ci, ci + 1 + (uint32_t)j, ci + 2 + (uint32_t)j);
}

/* A closed tube of `sides` along a polyline, with frames carried along so the rings do not twist. */
static void mb_tube_path(struct mb *b, const vec3 *pts, int n, float radius, int sides)
{
	mat4 id = mat4_identity();
	vec3 x = v3(0, 0, 0), z = x, t = x;
	uint32_t first = b->m->vertex_count, stride = (uint32_t)sides + 1;
	float along = 0.0f;
	for (int i = 0; i < n; i++) {
		vec3 a = pts[i > 0 ? i - 1 : 0], c = pts[i < n - 1 ? i + 1 : n - 1];
		t = v3_normalize(v3_sub(c, a));
		if (i == 0) {
			vec3 helper = fabsf(t.y) < 0.9f ? v3(0, 1, 0) : v3(1, 0, 0);
			x = v3_normalize(v3_cross(helper, t));
		} else {
			x = v3_normalize(v3_sub(x, v3_scale(t, v3_dot(x, t))));
			along += v3_length(v3_sub(pts[i], pts[i - 1]));
		}
		z = v3_cross(x, t);
		if (i == 0)
			mb_ring_cap(b, pts[0], x, z, radius, sides, v3_scale(t, -1.0f));
		uint32_t ring = b->m->vertex_count;
		for (int j = 0; j <= sides; j++) {
			float ang = 2.0f * PI_F * (float)j / (float)sides;
			vec3 dir = v3_add(v3_scale(x, sinf(ang)), v3_scale(z, cosf(ang)));
			mb_vertex(b, id, v3_add(pts[i], v3_scale(dir, radius)), dir, (float)j / (float)sides, along);
		}
		if (i == 0)
			first = ring;
	}
	mb_ring_cap(b, pts[n - 1], x, z, radius, sides, t);
	for (int i = 0; i + 1 < n; i++)
		for (int j = 0; j < sides; j++) {
			uint32_t k = first + (uint32_t)i * stride + (uint32_t)j;
			mb_quad(b, k, k + 1, k + 1 + stride, k + stride);
		}
}

/* ---------------------------------------------------------------- mesh types */

static int check_estimate(struct sj *s, const struct mb *b, double triangles, const char *what)
{
	if (triangles <= (double)b->max_triangles)
		return 0;
	return sj_fail(s, AA_ERR_LIMIT, "this mesh would have about %.0f triangles, over the limit of %llu: reduce %s",
		       triangles, (unsigned long long)b->max_triangles, what);
}

/* Sizes: not absurdly small (degenerate triangles) nor large. */
#define SIZE_RANGE SJ_CLOSED(1e-4, 1e5)
#define THIN_RANGE SJ_CLOSED(1e-5, 1e4)

struct plane_ctx { float size[2], repeat[2]; };

static void plane_surface(const void *ctx, float u, float v, vec3 *p, vec3 *n, float uv[2])
{
	const struct plane_ctx *c = ctx;
	*p = v3(c->size[0] * (u - 0.5f), 0, c->size[1] * (v - 0.5f));
	*n = v3(0, 1, 0);
	uv[0] = u * c->repeat[0], uv[1] = v * c->repeat[1];
}

static int build_plane(struct sj *s, const json_t *o, struct mb *b)
{
	static const float one[2] = {1, 1};
	static const int one_i[2] = {1, 1};
	struct plane_ctx c;
	int sub[2];
	if (sj_floats_or_scalar(s, o, "size", 2, SIZE_RANGE, one, c.size) ||
	    sj_ints_or_scalar(s, o, "subdivisions", 2, 1, 1024, one_i, sub) ||
	    sj_floats_or_scalar(s, o, "uv_repeat", 2, SJ_CLOSED(1e-3, 1e4), one, c.repeat) ||
	    check_estimate(s, b, 2.0 * sub[0] * sub[1], "subdivisions"))
		return -1;
	mb_surface(b, mat4_identity(), sub[0], sub[1], plane_surface, &c);
	return 0;
}

static int build_box(struct sj *s, const json_t *o, struct mb *b)
{
	static const float one[3] = {1, 1, 1};
	float size[3], rep[2];
	if (sj_floats_or_scalar(s, o, "size", 3, SIZE_RANGE, one, size) ||
	    sj_floats_or_scalar(s, o, "uv_repeat", 2, SJ_CLOSED(1e-3, 1e4), one, rep))
		return -1;
	mb_box(b, mat4_identity(), v3(size[0], size[1], size[2]), rep);
	return 0;
}

struct sphere_ctx { float radius; };

static void sphere_surface(const void *ctx, float u, float v, vec3 *p, vec3 *n, float uv[2])
{
	const struct sphere_ctx *c = ctx;
	float th = PI_F * v, ph = 2.0f * PI_F * u;
	/* u runs eastward seen from outside, v from the north pole (+y) down: textures are not mirrored. */
	*n = v3(sinf(th) * sinf(ph), cosf(th), sinf(th) * cosf(ph));
	*p = v3_scale(*n, c->radius);
	uv[0] = u, uv[1] = v;
}

static int build_sphere(struct sj *s, const json_t *o, struct mb *b)
{
	struct sphere_ctx c;
	int stacks, slices;
	if (sj_float(s, o, "radius", SIZE_RANGE, 0.5f, &c.radius) || sj_int(s, o, "stacks", 2, 512, 16, &stacks) ||
	    sj_int(s, o, "slices", 3, 1024, 32, &slices) ||
	    check_estimate(s, b, 2.0 * stacks * slices, "stacks or slices"))
		return -1;
	mb_surface(b, mat4_identity(), slices, stacks, sphere_surface, &c);
	return 0;
}

static int build_cylinder(struct sj *s, const json_t *o, struct mb *b)
{
	float radius, height;
	int segments;
	bool caps;
	if (sj_float(s, o, "radius", SIZE_RANGE, 0.5f, &radius) || sj_float(s, o, "height", SIZE_RANGE, 1.0f, &height) ||
	    sj_int(s, o, "segments", 3, 1024, 24, &segments) || sj_bool(s, o, "caps", true, &caps))
		return -1;
	mb_cylinder(b, mat4_identity(), radius, height, segments, caps);
	return 0;
}

/* Power lines: `count` parallel wires hung between support points, each span sagging as a parabola
 * (close to a catenary for shallow sag), spread sideways by `spacing`. */
static int build_wires(struct sj *s, const json_t *o, struct mb *b)
{
	enum { MAX_POINTS = 64 };
	vec3 sup[MAX_POINTS];
	int n = 2, count, segments, sides;
	float spacing, radius, sag;
	sup[0] = v3(-5, 5, 0), sup[1] = v3(5, 5, 0);
	const json_t *pts = json_object_get(o, "points");
	if (pts) {
		size_t mark = sj_push_key(s, "points");
		if (!json_is_array(pts) || json_array_size(pts) < 2 || json_array_size(pts) > MAX_POINTS)
			return sj_fail(s, AA_ERR_INVALID, "expected an array of 2 to %d points [x, y, z]", MAX_POINTS);
		n = (int)json_array_size(pts);
		for (int i = 0; i < n; i++) {
			size_t m2 = sj_push_index(s, (size_t)i);
			if (sj_vec3_value(s, json_array_get(pts, (size_t)i), SJ_ANY, &sup[i]))
				return -1;
			if (i > 0 && v3_length(v3_sub(sup[i], sup[i - 1])) < 1e-3f)
				return sj_fail(s, AA_ERR_INVALID, "support points must be at least 0.001 apart");
			sj_pop(s, m2);
		}
		sj_pop(s, mark);
	}
	if (sj_int(s, o, "count", 1, 64, 3, &count) || sj_float(s, o, "spacing", SJ_NONNEG, 0.4f, &spacing) ||
	    sj_float(s, o, "radius", THIN_RANGE, 0.01f, &radius) || sj_float(s, o, "sag", SJ_NONNEG, 0.3f, &sag) ||
	    sj_int(s, o, "segments", 1, 256, 24, &segments) || sj_int(s, o, "sides", 3, 32, 6, &sides) ||
	    check_estimate(s, b, (double)count * ((n - 1) * segments + 1) * sides * 2.0 + count * sides * 2.0,
			   "count, segments or sides"))
		return -1;
	/* Wires spread across the line's overall horizontal direction. */
	vec3 dir = v3_sub(sup[n - 1], sup[0]);
	dir.y = 0;
	vec3 side = v3_length(dir) > 1e-6f ? v3_normalize(v3_cross(dir, v3(0, 1, 0))) : v3(0, 0, 1);
	int np = (n - 1) * segments + 1;
	vec3 *line = malloc((size_t)np * sizeof *line);
	if (!line)
		return sj_fail(s, AA_ERR_INTERNAL, "out of memory");
	for (int w = 0; w < count; w++) {
		vec3 off = v3_scale(side, ((float)w - 0.5f * (float)(count - 1)) * spacing);
		for (int span = 0; span < n - 1; span++)
			for (int k = (span ? 1 : 0); k <= segments; k++) {
				float t = (float)k / (float)segments;
				vec3 p = v3_lerp(sup[span], sup[span + 1], t);
				p.y -= sag * 4.0f * t * (1.0f - t);
				line[span * segments + k] = v3_add(p, off);
			}
		mb_tube_path(b, line, np, radius, sides);
	}
	free(line);
	return 0;
}

/* A fence along x, base at y = 0: posts plus rails, or posts plus a grid of thin wires. */
static int build_fence(struct sj *s, const json_t *o, struct mb *b)
{
	static const char *const styles[] = {"rails", "grid", NULL};
	float len, h, pw, rh, rd, gs, wt;
	int posts, rails, style;
	if (sj_float(s, o, "length", SIZE_RANGE, 4.0f, &len) || sj_float(s, o, "height", SIZE_RANGE, 1.2f, &h) ||
	    sj_int(s, o, "posts", 2, 256, 5, &posts) || sj_float(s, o, "post_width", THIN_RANGE, 0.08f, &pw) ||
	    sj_enum(s, o, "style", styles, 0, &style) || sj_int(s, o, "rails", 0, 16, 2, &rails) ||
	    sj_float(s, o, "rail_height", THIN_RANGE, 0.08f, &rh) || sj_float(s, o, "rail_depth", THIN_RANGE, 0.04f, &rd) ||
	    sj_float(s, o, "grid_spacing", SJ_CLOSED(0.005, 1e4), 0.1f, &gs) ||
	    sj_float(s, o, "wire_thickness", THIN_RANGE, 0.01f, &wt))
		return -1;
	int nx = style == 1 ? (int)fminf(len / gs, 1e6f) + 1 : 0, ny = style == 1 ? (int)fminf(h / gs, 1e6f) : 0;
	if (nx + ny > 8192)
		return sj_fail_key(s, "grid_spacing", AA_ERR_LIMIT,
				   "%d grid wires is too many (limit 8192): increase grid_spacing", nx + ny);
	if (check_estimate(s, b, 12.0 * (posts + rails + 2 + nx + ny), "posts, rails or grid density"))
		return -1;
	for (int i = 0; i < posts; i++) {
		float x = -0.5f * len + len * (float)i / (float)(posts - 1);
		mb_box(b, mat4_translate(v3(x, 0.5f * h, 0)), v3(pw, h, pw), uv_one);
	}
	if (style == 0) {
		for (int j = 0; j < rails; j++)
			mb_box(b, mat4_translate(v3(0, h * (float)(j + 1) / (float)(rails + 1), 0)), v3(len, rh, rd),
			       uv_one);
		return 0;
	}
	/* Grid: a top and a bottom rail framing square cells of thin wires. */
	mb_box(b, mat4_translate(v3(0, h - 0.5f * rh, 0)), v3(len, rh, rd), uv_one);
	mb_box(b, mat4_translate(v3(0, 0.5f * rh, 0)), v3(len, rh, rd), uv_one);
	for (int i = 0; i < nx; i++)
		mb_box(b, mat4_translate(v3(-0.5f * len + gs * (float)i, 0.5f * h, 0)), v3(wt, h, wt), uv_one);
	for (int j = 1; j <= ny; j++)
		if (gs * (float)j < h)
			mb_box(b, mat4_translate(v3(0, gs * (float)j, 0)), v3(len, wt, wt), uv_one);
	return 0;
}

/* Window blinds: thin slats tilted about their long (x) axis, a head rail and two ladder cords. */
static int build_blinds(struct sj *s, const json_t *o, struct mb *b)
{
	float w, h, depth, thick, tilt;
	int slats;
	bool cords;
	if (sj_float(s, o, "width", SIZE_RANGE, 1.2f, &w) || sj_float(s, o, "height", SIZE_RANGE, 1.4f, &h) ||
	    sj_int(s, o, "slats", 1, 1024, 24, &slats) || sj_float(s, o, "slat_depth", THIN_RANGE, 0.05f, &depth) ||
	    sj_float(s, o, "slat_thickness", THIN_RANGE, 0.004f, &thick) ||
	    sj_float(s, o, "tilt", SJ_CLOSED(-90, 90), 20.0f, &tilt) || sj_bool(s, o, "cords", true, &cords))
		return -1;
	float pitch = h / (float)slats;
	for (int i = 0; i < slats; i++) {
		mat4 xf = mat4_mul(mat4_translate(v3(0, h - (0.5f + (float)i) * pitch, 0)),
				   mat4_rotate(v3(1, 0, 0), tilt * PI_F / 180.0f));
		mb_box(b, xf, v3(w, thick, depth), uv_one);
	}
	mb_box(b, mat4_translate(v3(0, h + 0.02f, 0)), v3(w * 1.02f, 0.04f, depth * 1.3f), uv_one);
	if (cords)
		for (int k = -1; k <= 1; k += 2)
			mb_box(b, mat4_translate(v3(0.3f * w * (float)k, 0.5f * h, 0.5f * depth)),
			       v3(0.003f, h, 0.003f), uv_one);
	return 0;
}

/* Solid stairs: step i spans z in [-(i+1)d, -i d] and rises to (i+1)h, so they climb toward -z. */
static int build_stairs(struct sj *s, const json_t *o, struct mb *b)
{
	float w, sh, sd;
	int steps;
	if (sj_int(s, o, "steps", 1, 256, 8, &steps) || sj_float(s, o, "width", SIZE_RANGE, 1.2f, &w) ||
	    sj_float(s, o, "step_height", SIZE_RANGE, 0.18f, &sh) || sj_float(s, o, "step_depth", SIZE_RANGE, 0.28f, &sd))
		return -1;
	for (int i = 0; i < steps; i++) {
		float top = sh * (float)(i + 1);
		mb_box(b, mat4_translate(v3(0, 0.5f * top, -sd * ((float)i + 0.5f))), v3(w, top, sd), uv_one);
	}
	return 0;
}

/* Wheel rim: an annulus of square section in the xy plane (axle along z). */
struct rim_ctx { float outer, inner, depth; int face; };

static void rim_surface(const void *ctx, float u, float v, vec3 *p, vec3 *n, float uv[2])
{
	const struct rim_ctx *c = ctx;
	float a = 2.0f * PI_F * u, ca = cosf(a), sa = sinf(a);
	float r = c->face == 0 ? c->outer : c->face == 1 ? c->inner : c->inner + (c->outer - c->inner) * v;
	float z = c->face < 2 ? c->depth * (v - 0.5f) : (c->face == 2 ? 0.5f : -0.5f) * c->depth;
	*p = v3(r * ca, r * sa, z);
	*n = c->face == 0 ? v3(ca, sa, 0) : c->face == 1 ? v3(-ca, -sa, 0) : v3(0, 0, c->face == 2 ? 1.0f : -1.0f);
	uv[0] = u, uv[1] = v;
}

static int build_wheel(struct sj *s, const json_t *o, struct mb *b)
{
	float radius, rim_w, depth, spoke_w, hub_r;
	int spokes, segments;
	if (sj_float(s, o, "radius", SIZE_RANGE, 1.0f, &radius) || sj_float(s, o, "rim_width", THIN_RANGE, 0.06f, &rim_w) ||
	    sj_float(s, o, "depth", THIN_RANGE, 0.08f, &depth) || sj_int(s, o, "spokes", 0, 256, 16, &spokes) ||
	    sj_float(s, o, "spoke_width", THIN_RANGE, 0.02f, &spoke_w) ||
	    sj_float(s, o, "hub_radius", THIN_RANGE, 0.12f, &hub_r) || sj_int(s, o, "segments", 8, 1024, 64, &segments))
		return -1;
	if (rim_w >= radius)
		return sj_fail_key(s, "rim_width", AA_ERR_INVALID, "rim_width must be less than radius (%g)", radius);
	if (hub_r >= radius - rim_w)
		return sj_fail_key(s, "hub_radius", AA_ERR_INVALID, "hub_radius must be less than radius - rim_width (%g)",
				   radius - rim_w);
	for (int face = 0; face < 4; face++) {
		struct rim_ctx c = {radius, radius - rim_w, depth, face};
		mb_surface(b, mat4_identity(), segments, 1, rim_surface, &c);
	}
	mb_cylinder(b, mat4_rotate(v3(1, 0, 0), 0.5f * PI_F), hub_r, depth * 1.5f, segments / 2, true);
	/* Spokes run from inside the hub into the rim so no seams show. */
	float r0 = 0.7f * hub_r, r1 = radius - 0.5f * rim_w;
	for (int k = 0; k < spokes; k++) {
		float a = 2.0f * PI_F * (float)k / (float)spokes - 0.5f * PI_F;
		mat4 xf = mat4_mul(mat4_rotate(v3(0, 0, 1), a), mat4_translate(v3(0, 0.5f * (r0 + r1), 0)));
		mb_box(b, xf, v3(spoke_w, r1 - r0, spoke_w * 0.8f), uv_one);
	}
	return 0;
}

/* A dense ball of thin straight strands (random chords of a sphere), deterministic for a given seed. */
static uint32_t xorshift(uint32_t *state)
{
	uint32_t x = *state;
	x ^= x << 13;
	x ^= x >> 17;
	x ^= x << 5;
	return *state = x;
}

static vec3 random_on_sphere(uint32_t *state, float r)
{
	float z = 2.0f * (float)(xorshift(state) >> 8) / 16777216.0f - 1.0f;
	float a = 2.0f * PI_F * (float)(xorshift(state) >> 8) / 16777216.0f;
	float q = sqrtf(fmaxf(0.0f, 1.0f - z * z));
	return v3(r * q * cosf(a), r * z, r * q * sinf(a));
}

static int build_hairball(struct sj *s, const json_t *o, struct mb *b)
{
	float radius, thick;
	int count, sides, seed;
	if (sj_float(s, o, "radius", SIZE_RANGE, 1.0f, &radius) || sj_int(s, o, "count", 1, 100000, 600, &count) ||
	    sj_float(s, o, "thickness", THIN_RANGE, 0.006f, &thick) || sj_int(s, o, "sides", 3, 16, 3, &sides) ||
	    sj_int(s, o, "seed", 0, 1 << 30, 1, &seed) ||
	    check_estimate(s, b, (double)count * sides * 4.0, "count or sides"))
		return -1;
	uint32_t state = (uint32_t)seed * 2654435761u + 12345u;
	for (int i = 0; i < count; i++) {
		vec3 p0 = random_on_sphere(&state, radius), p1 = random_on_sphere(&state, radius);
		/* Short chords would be specks; pick again (bounded, so it always ends). */
		for (int tries = 0; tries < 8 && v3_length(v3_sub(p1, p0)) < 0.6f * radius; tries++)
			p1 = random_on_sphere(&state, radius);
		mb_tube(b, p0, p1, 0.5f * thick, sides);
	}
	return 0;
}

/* ---------------------------------------------------------------- dispatch */

struct mesh_type {
	const char *name;
	const char *const keys[14];
	int (*build)(struct sj *s, const json_t *spec, struct mb *b);
};

static const struct mesh_type mesh_types[] = {
	{"plane", {"type", "size", "subdivisions", "uv_repeat", NULL}, build_plane},
	{"box", {"type", "size", "uv_repeat", NULL}, build_box},
	{"sphere", {"type", "radius", "stacks", "slices", NULL}, build_sphere},
	{"cylinder", {"type", "radius", "height", "segments", "caps", NULL}, build_cylinder},
	{"wires", {"type", "points", "count", "spacing", "radius", "sag", "segments", "sides", NULL}, build_wires},
	{"fence", {"type", "length", "height", "posts", "post_width", "style", "rails", "rail_height", "rail_depth",
		   "grid_spacing", "wire_thickness", NULL}, build_fence},
	{"blinds", {"type", "width", "height", "slats", "slat_depth", "slat_thickness", "tilt", "cords", NULL},
	 build_blinds},
	{"stairs", {"type", "steps", "width", "step_height", "step_depth", NULL}, build_stairs},
	{"wheel", {"type", "radius", "rim_width", "depth", "spokes", "spoke_width", "hub_radius", "segments", NULL},
	 build_wheel},
	{"hairball", {"type", "radius", "count", "thickness", "sides", "seed", NULL}, build_hairball},
};

int aa_mesh_from_json(struct sj *s, const json_t *spec, const char *base_dir, uint64_t max_triangles,
		      struct aa_mesh *out)
{
	int type;
	memset(out, 0, sizeof *out);
	if (sj_expect_object(s, spec) || sj_require(s, spec, "type") ||
	    sj_enum(s, spec, "type", aa_mesh_type_names, 0, &type))
		return -1;
	const char *name = aa_mesh_type_names[type];
	(void)base_dir; /* file meshes are loaded by the scene loader (mesh_file.c), which adds their parts */
	out->part_count = 1;
	out->file_material = -1;
	out->rig = -1;
	const struct mesh_type *mt = NULL;
	for (size_t i = 0; i < sizeof mesh_types / sizeof mesh_types[0]; i++)
		if (strcmp(mesh_types[i].name, name) == 0)
			mt = &mesh_types[i];
	if (!mt || sj_check_keys(s, spec, mt->keys))
		return -1;
	struct mb b = {.m = out, .max_triangles = max_triangles};
	snprintf(out->name, sizeof out->name, "%s", name);
	if (mt->build(s, spec, &b)) {
		aa_mesh_free(out);
		return -1;
	}
	if (b.overflow) {
		aa_mesh_free(out);
		return sj_fail(s, AA_ERR_LIMIT, "this %s mesh has more than %llu triangles (the limit left for it)",
			       name, (unsigned long long)max_triangles);
	}
	if (out->index_count == 0) {
		aa_mesh_free(out);
		return sj_fail(s, AA_ERR_INVALID, "this %s mesh has no triangles (is it too small?)", name);
	}
	aa_mesh_compute_bounds(out);
	return 0;
}
