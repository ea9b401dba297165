/* Cameras and camera paths: reading them from a scene file and evaluating them at a time t
 * (Catmull-Rom keyframes with cuts, static, orbit, dolly, pan). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/scene_json.h"

#define DEG2RAD 0.017453292519943295

static const char *const camera_keys[] = {"position", "target", "up", "projection", "fov", "ortho_height",
					  "near", "far", NULL};

static int check_camera(struct sj *s, const struct aa_camera *c)
{
	vec3 f = v3_sub(c->target, c->position);
	if (v3_length(f) < 1e-6f)
		return sj_fail_key(s, "target", AA_ERR_INVALID, "target must differ from position");
	if (v3_length(v3_cross(v3_normalize(f), v3_normalize(c->up))) < 1e-4f)
		return sj_fail_key(s, "up", AA_ERR_INVALID, "up must not be parallel to the view direction");
	if (!(c->far_plane > c->near_plane))
		return sj_fail_key(s, "far", AA_ERR_INVALID, "far (%g) must be greater than near (%g)", c->far_plane,
				   c->near_plane);
	return 0;
}

/* Reads the camera fields present in obj over *base (or the defaults when base is NULL). */
static int read_camera_fields(struct sj *s, const json_t *obj, const struct aa_camera *base, bool need_position,
			      struct aa_camera *out)
{
	static const char *const projections[] = {"perspective", "orthographic", NULL};
	struct aa_camera d = {
		.position = v3(0, 1, 5), .target = v3(0, 1, 0), .up = v3(0, 1, 0),
		.projection = AA_PROJECTION_PERSPECTIVE, .fov_y_degrees = 50.0f, .ortho_height = 10.0f,
		.near_plane = 0.1f, .far_plane = 1000.0f,
	};
	if (base)
		d = *base;
	int proj;
	/* position and target in double, kept relative to the scene camera's origin (struct aa_camera) */
	double def_position[3] = {d.origin[0] + d.position.x, d.origin[1] + d.position.y, d.origin[2] + d.position.z};
	double def_target[3] = {d.origin[0] + d.target.x, d.origin[1] + d.target.y, d.origin[2] + d.target.z};
	double position[3], target[3];
	if ((need_position && (sj_require(s, obj, "position") || sj_require(s, obj, "target"))) ||
	    sj_dvec3(s, obj, "position", SJ_ANY, def_position, position) ||
	    sj_dvec3(s, obj, "target", SJ_ANY, def_target, target) ||
	    sj_vec3(s, obj, "up", SJ_CLOSED(-1e3, 1e3), d.up, &out->up) ||
	    sj_enum(s, obj, "projection", projections, (int)d.projection, &proj) ||
	    sj_float(s, obj, "fov", SJ_CLOSED(1, 179), d.fov_y_degrees, &out->fov_y_degrees) ||
	    sj_float(s, obj, "ortho_height", SJ_POSITIVE, d.ortho_height, &out->ortho_height) ||
	    sj_float(s, obj, "near", SJ_CLOSED(1e-4, 1e6), d.near_plane, &out->near_plane) ||
	    sj_float(s, obj, "far", SJ_CLOSED(1e-3, 1e7), d.far_plane, &out->far_plane))
		return -1;
	out->projection = (enum aa_projection)proj;
	for (int k = 0; k < 3; k++)
		out->origin[k] = base ? base->origin[k] : 1024.0 * round(position[k] / 1024.0);
	out->position = v3((float)(position[0] - out->origin[0]), (float)(position[1] - out->origin[1]),
			   (float)(position[2] - out->origin[2]));
	out->target = v3((float)(target[0] - out->origin[0]), (float)(target[1] - out->origin[1]),
			 (float)(target[2] - out->origin[2]));
	if (v3_length(out->up) < 1e-6f)
		return sj_fail_key(s, "up", AA_ERR_INVALID, "up must not be zero");
	out->up = v3_normalize(out->up);
	return 0;
}

int aa_camera_from_json(struct sj *s, const json_t *obj, const struct aa_camera *base, bool need_position,
			struct aa_camera *out)
{
	if (sj_check_keys(s, obj, camera_keys) || read_camera_fields(s, obj, base, need_position, out))
		return -1;
	return check_camera(s, out);
}

static const char *const path_types[] = {"keyframes", "static", "orbit", "dolly", "pan", NULL};

static int read_keys(struct sj *s, const json_t *keys, const struct aa_camera *camera, struct aa_camera_path *p)
{
	static const char *const key_keys[] = {"time", "cut", "position", "target", "up", "projection", "fov",
					       "ortho_height", "near", "far", NULL};
	size_t mark = sj_push_key(s, "keys");
	if (!json_is_array(keys) || json_array_size(keys) < 1 || json_array_size(keys) > AA_SCENE_MAX_KEYS)
		return sj_fail(s, AA_ERR_INVALID, "expected an array of 1 to %d camera keys", AA_SCENE_MAX_KEYS);
	p->key_count = (int)json_array_size(keys);
	p->keys = calloc((size_t)p->key_count, sizeof *p->keys);
	if (!p->keys)
		return sj_fail(s, AA_ERR_INTERNAL, "out of memory");
	for (int i = 0; i < p->key_count; i++) {
		const json_t *k = json_array_get(keys, (size_t)i);
		struct aa_camera_key *key = &p->keys[i];
		size_t m2 = sj_push_index(s, (size_t)i);
		/* Each key starts from the previous one (the first from the scene camera), so keys only
		 * write what changes. */
		if (sj_check_keys(s, k, key_keys) || sj_require(s, k, "time") ||
		    sj_number(s, k, "time", SJ_CLOSED(0, 1e6), 0, &key->time) || sj_bool(s, k, "cut", false, &key->cut) ||
		    read_camera_fields(s, k, i ? &p->keys[i - 1].camera : camera, false, &key->camera) ||
		    check_camera(s, &key->camera))
			return -1;
		if (i == 0 && key->cut)
			return sj_fail_key(s, "cut", AA_ERR_INVALID, "the first key cannot be a cut");
		if (i > 0 && !(key->time > p->keys[i - 1].time))
			return sj_fail_key(s, "time", AA_ERR_INVALID, "key times must increase: %g is not after %g",
					   key->time, p->keys[i - 1].time);
		sj_pop(s, m2);
	}
	p->duration = p->keys[p->key_count - 1].time;
	sj_pop(s, mark);
	return 0;
}

static int read_path(struct sj *s, const json_t *o, const struct aa_camera *camera, int index,
		     struct aa_camera_path *p)
{
	static const char *const interp[] = {"centripetal", "uniform", NULL};
	static const char *const keys_of[][7] = {
		{"name", "type", "keys", "interpolation", NULL},
		{"name", "type", "camera", "duration", NULL},
		{"name", "type", "camera", "center", "degrees", "duration", NULL},
		{"name", "type", "camera", "distance", "duration", NULL},
		{"name", "type", "camera", "degrees", "duration", NULL},
	};
	char def_name[32];
	int type, ip;
	snprintf(def_name, sizeof def_name, "path%d", index);
	if (sj_expect_object(s, o) || sj_require(s, o, "type") || sj_enum(s, o, "type", path_types, 0, &type) ||
	    sj_check_keys(s, o, keys_of[type]) || sj_string(s, o, "name", def_name, p->name, sizeof p->name))
		return -1;
	if (!p->name[0] || strcmp(p->name, "default") == 0 || strcmp(p->name, "static") == 0)
		return sj_fail_key(s, "name", AA_ERR_INVALID,
				   "path name '%s' is reserved or empty ('default' and 'static' name paths[0])", p->name);
	p->kind = (enum aa_path_kind)type;
	p->catmull_alpha = 0.5f;
	if (p->kind == AA_PATH_KEYFRAMES) {
		if (sj_require(s, o, "keys") || sj_enum(s, o, "interpolation", interp, 0, &ip) ||
		    read_keys(s, json_object_get(o, "keys"), camera, p))
			return -1;
		p->catmull_alpha = ip == 0 ? 0.5f : 0.0f;
		return 0;
	}
	p->key_count = 1;
	p->keys = calloc(1, sizeof *p->keys);
	if (!p->keys)
		return sj_fail(s, AA_ERR_INTERNAL, "out of memory");
	p->keys[0].camera = *camera;
	const json_t *start = json_object_get(o, "camera");
	if (start) {
		size_t mark = sj_push_key(s, "camera");
		if (aa_camera_from_json(s, start, camera, false, &p->keys[0].camera))
			return -1;
		sj_pop(s, mark);
	}
	double def_duration = p->kind == AA_PATH_STATIC ? 0.0 : p->kind == AA_PATH_ORBIT ? 10.0 : 4.0;
	struct sj_range dr = p->kind == AA_PATH_STATIC ? SJ_CLOSED(0, 1e6) : SJ_CLOSED(1e-3, 1e6);
	const struct aa_camera *c = &p->keys[0].camera;
	double def_center[3] = {c->origin[0] + c->target.x, c->origin[1] + c->target.y, c->origin[2] + c->target.z};
	double center[3];
	if (sj_number(s, o, "duration", dr, def_duration, &p->duration) ||
	    sj_dvec3(s, o, "center", SJ_ANY, def_center, center) ||
	    sj_float(s, o, "degrees", SJ_CLOSED(-36000, 36000), p->kind == AA_PATH_ORBIT ? 360.0f : 30.0f, &p->degrees))
		return -1;
	p->center = v3((float)(center[0] - c->origin[0]), (float)(center[1] - c->origin[1]), (float)(center[2] - c->origin[2]));
	if (p->kind == AA_PATH_DOLLY &&
	    (sj_require(s, o, "distance") || sj_float(s, o, "distance", SJ_CLOSED(-1e5, 1e5), 0, &p->distance)))
		return -1;
	return 0;
}

int aa_paths_from_json(struct sj *s, const json_t *paths, const struct aa_camera *camera, struct aa_scene *scene)
{
	if (!paths) {
		/* No paths: one static path at the scene camera. */
		scene->paths = calloc(1, sizeof *scene->paths);
		if (!scene->paths || !(scene->paths[0].keys = calloc(1, sizeof *scene->paths[0].keys)))
			return sj_fail(s, AA_ERR_INTERNAL, "out of memory");
		scene->path_count = 1;
		snprintf(scene->paths[0].name, sizeof scene->paths[0].name, "main");
		scene->paths[0].kind = AA_PATH_STATIC;
		scene->paths[0].key_count = 1;
		scene->paths[0].keys[0].camera = *camera;
		return 0;
	}
	size_t mark = sj_push_key(s, "paths");
	if (!json_is_array(paths) || json_array_size(paths) < 1 || json_array_size(paths) > AA_SCENE_MAX_PATHS)
		return sj_fail(s, AA_ERR_INVALID, "expected an array of 1 to %d camera paths", AA_SCENE_MAX_PATHS);
	size_t n = json_array_size(paths);
	scene->paths = calloc(n, sizeof *scene->paths);
	if (!scene->paths)
		return sj_fail(s, AA_ERR_INTERNAL, "out of memory");
	for (size_t i = 0; i < n; i++) {
		size_t m2 = sj_push_index(s, i);
		scene->path_count = (int)i + 1; /* so a partly read path is freed */
		if (read_path(s, json_array_get(paths, i), camera, (int)i, &scene->paths[i]))
			return -1;
		for (size_t j = 0; j < i; j++)
			if (strcmp(scene->paths[j].name, scene->paths[i].name) == 0)
				return sj_fail_key(s, "name", AA_ERR_INVALID, "duplicate path name '%s'", scene->paths[i].name);
		sj_pop(s, m2);
	}
	sj_pop(s, mark);
	return 0;
}

/* ---------------------------------------------------------------- evaluation */

const struct aa_camera_path *aa_scene_find_path(const struct aa_scene *scene, const char *name)
{
	if (!scene || scene->path_count < 1)
		return NULL;
	if (!name || !name[0] || strcmp(name, "default") == 0 || strcmp(name, "static") == 0)
		return &scene->paths[0];
	for (int i = 0; i < scene->path_count; i++)
		if (strcmp(scene->paths[i].name, name) == 0)
			return &scene->paths[i];
	return NULL;
}

typedef struct { double x, y, z; } dvec3;

static dvec3 dv(vec3 v) { return (dvec3){v.x, v.y, v.z}; }
static dvec3 dmix(dvec3 a, double wa, dvec3 b, double wb)
{
	return (dvec3){a.x * wa + b.x * wb, a.y * wa + b.y * wb, a.z * wa + b.z * wb};
}

/* Knot spacing |b - a|^alpha (alpha 0.5: centripetal, no cusps or self-intersections; 0: uniform), with a
 * floor so coincident keys (a camera that holds still while its target moves) never divide by zero. */
static double knot(dvec3 a, dvec3 b, double alpha)
{
	double d = sqrt((b.x - a.x) * (b.x - a.x) + (b.y - a.y) * (b.y - a.y) + (b.z - a.z) * (b.z - a.z));
	return fmax(pow(d, alpha), 1e-4);
}

/* Catmull-Rom between p1 and p2 at u in [0,1] (Barry-Goldman pyramid). */
static vec3 catmull_rom(vec3 q0, vec3 q1, vec3 q2, vec3 q3, double alpha, double u)
{
	dvec3 p0 = dv(q0), p1 = dv(q1), p2 = dv(q2), p3 = dv(q3);
	double t0 = 0, t1 = t0 + knot(p0, p1, alpha), t2 = t1 + knot(p1, p2, alpha), t3 = t2 + knot(p2, p3, alpha);
	double t = t1 + (t2 - t1) * u;
	dvec3 a1 = dmix(p0, (t1 - t) / (t1 - t0), p1, (t - t0) / (t1 - t0));
	dvec3 a2 = dmix(p1, (t2 - t) / (t2 - t1), p2, (t - t1) / (t2 - t1));
	dvec3 a3 = dmix(p2, (t3 - t) / (t3 - t2), p3, (t - t2) / (t3 - t2));
	dvec3 b1 = dmix(a1, (t2 - t) / (t2 - t0), a2, (t - t0) / (t2 - t0));
	dvec3 b2 = dmix(a2, (t3 - t) / (t3 - t1), a3, (t - t1) / (t3 - t1));
	dvec3 c = dmix(b1, (t2 - t) / (t2 - t1), b2, (t - t1) / (t2 - t1));
	return v3((float)c.x, (float)c.y, (float)c.z);
}

static float lerpf(float a, float b, float u) { return a + (b - a) * u; }

static void eval_keyframes(const struct aa_camera_path *p, double t, struct aa_camera *out)
{
	const struct aa_camera_key *k = p->keys;
	int n = p->key_count, i = 0;
	if (t <= k[0].time || n == 1) {
		*out = k[0].camera;
		return;
	}
	if (t >= k[n - 1].time) {
		*out = k[n - 1].camera;
		return;
	}
	while (i + 1 < n && k[i + 1].time <= t)
		i++;
	/* Before a cut the camera holds its last key; then it jumps. */
	if (k[i + 1].cut) {
		*out = k[i].camera;
		return;
	}
	const struct aa_camera *c1 = &k[i].camera, *c2 = &k[i + 1].camera;
	/* Neighbours across a cut or past the ends are mirrored, which clamps the curve to the end key. */
	bool has0 = i > 0 && !k[i].cut, has3 = i + 2 < n && !k[i + 2].cut;
	const struct aa_camera *c0 = has0 ? &k[i - 1].camera : NULL, *c3 = has3 ? &k[i + 2].camera : NULL;
	float u = (float)((t - k[i].time) / (k[i + 1].time - k[i].time));
	vec3 pos[4], tgt[4];
	pos[1] = c1->position, pos[2] = c2->position, tgt[1] = c1->target, tgt[2] = c2->target;
	pos[0] = c0 ? c0->position : v3_sub(v3_scale(pos[1], 2), pos[2]);
	tgt[0] = c0 ? c0->target : v3_sub(v3_scale(tgt[1], 2), tgt[2]);
	pos[3] = c3 ? c3->position : v3_sub(v3_scale(pos[2], 2), pos[1]);
	tgt[3] = c3 ? c3->target : v3_sub(v3_scale(tgt[2], 2), tgt[1]);
	*out = *c1;
	out->position = catmull_rom(pos[0], pos[1], pos[2], pos[3], p->catmull_alpha, u);
	out->target = catmull_rom(tgt[0], tgt[1], tgt[2], tgt[3], p->catmull_alpha, u);
	out->up = v3_normalize(v3_lerp(c1->up, c2->up, u));
	out->fov_y_degrees = lerpf(c1->fov_y_degrees, c2->fov_y_degrees, u);
	out->ortho_height = lerpf(c1->ortho_height, c2->ortho_height, u);
	out->near_plane = lerpf(c1->near_plane, c2->near_plane, u);
	out->far_plane = lerpf(c1->far_plane, c2->far_plane, u);
}

static vec3 rotate_about(vec3 p, vec3 center, vec3 axis, double radians)
{
	return v3_add(center, mat4_transform_dir(mat4_rotate(axis, (float)radians), v3_sub(p, center)));
}

/* Keeps a camera usable for mat4_look_at whatever the path did (target on the eye, up along the view). */
static void sanitize(struct aa_camera *c)
{
	vec3 f = v3_sub(c->target, c->position);
	if (!(v3_length(f) > 1e-6f))
		c->target = v3_add(c->position, v3(0, 0, -1)), f = v3(0, 0, -1);
	if (!(v3_length(v3_cross(v3_normalize(f), c->up)) > 1e-4f))
		c->up = fabsf(v3_normalize(f).y) < 0.9f ? v3(0, 1, 0) : v3(0, 0, -1);
}

void aa_camera_path_eval(const struct aa_camera_path *path, bool hold_first, double t_prev, double t,
			 struct aa_camera *out, bool *cut)
{
	if (cut)
		*cut = false;
	if (!path || path->key_count < 1) {
		*out = (struct aa_camera){.position = v3(0, 0, 1), .up = v3(0, 1, 0), .fov_y_degrees = 50.0f,
					  .ortho_height = 2.0f, .near_plane = 0.1f, .far_plane = 100.0f};
		return;
	}
	if (!isfinite(t) || t < 0)
		t = 0;
	*out = path->keys[0].camera;
	if (hold_first)
		return;
	double s = path->duration > 0 ? fmin(t / path->duration, 1.0) : 1.0;
	switch (path->kind) {
	case AA_PATH_KEYFRAMES:
		eval_keyframes(path, t, out);
		if (cut && t_prev >= 0 && isfinite(t_prev))
			for (int i = 1; i < path->key_count; i++)
				if (path->keys[i].cut && path->keys[i].time > t_prev && path->keys[i].time <= t)
					*cut = true;
		break;
	case AA_PATH_STATIC:
		break;
	case AA_PATH_ORBIT: {
		/* Keeps turning past `duration` (a full-circle orbit loops seamlessly). */
		double a = path->duration > 0 ? fmod(path->degrees * (t / path->duration), 360.0) * DEG2RAD : 0.0;
		out->position = rotate_about(out->position, path->center, v3(0, 1, 0), a);
		out->target = rotate_about(out->target, path->center, v3(0, 1, 0), a);
		break;
	}
	case AA_PATH_DOLLY: {
		vec3 f = v3_normalize(v3_sub(out->target, out->position));
		vec3 d = v3_scale(f, (float)(path->distance * s));
		out->position = v3_add(out->position, d);
		out->target = v3_add(out->target, d);
		break;
	}
	case AA_PATH_PAN:
		out->target = rotate_about(out->target, out->position, out->up, path->degrees * s * DEG2RAD);
		break;
	}
	sanitize(out);
}
