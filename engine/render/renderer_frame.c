/* The renderer's state for one frame (aa_renderer_set_frame): the camera's matrices, skinned meshes posed
 * at the frame's time, blended objects sorted back to front, and the shadow cascades fitted to the view,
 * all written to the frame's uniform buffer before any pass of the frame is recorded (renderer.c). */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render/renderer.h"

static mat4 camera_projection(const struct aa_camera *c, int width, int height)
{
	float aspect = (float)width / (float)height;
	if (c->projection == AA_PROJECTION_ORTHOGRAPHIC)
		return mat4_ortho_reversed_z(c->ortho_height * aspect, c->ortho_height, c->near_plane, c->far_plane);
	return mat4_perspective_reversed_z(c->fov_y_degrees * (float)M_PI / 180.0f, aspect, c->near_plane,
					   c->far_plane);
}

/* Poses the skinned parts for time t into this frame's vertices and, for prev_t, into the previous
 * positions the G-buffer reads for velocity (no previous frame: the same positions, no motion). Each
 * object's world box comes from its posed vertices. */
static void pose_skinned(struct aa_renderer *r, double t, bool has_prev, double prev_t)
{
	const struct aa_scene *s = r->scene;
	struct aa_vertex *current = r->skinned_vertices.mapped;
	float *previous = r->skinned_previous.mapped;
	for (int o = 0; o < s->object_count; o++) {
		if (r->skin_offset[o] < 0)
			continue;
		const struct aa_object *obj = &s->objects[o];
		const struct aa_mesh *m = &s->meshes[obj->mesh_index];
		const struct aa_rig *rig = &s->rigs[m->rig];
		struct aa_vertex *out = current + r->skin_offset[o];
		aa_rig_pose(rig, &obj->pose, t, r->joint_matrices);
		aa_mesh_skin(m, r->joint_matrices, out);
		float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
		for (uint32_t v = 0; v < m->vertex_count; v++)
			for (int k = 0; k < 3; k++)
				lo[k] = fminf(lo[k], out[v].position[k]), hi[k] = fmaxf(hi[k], out[v].position[k]);
		if (m->vertex_count)
			r->bounds[o] = aa_box_transform(r->models[o], lo, hi);
		const struct aa_vertex *before = out;
		if (has_prev) {
			aa_rig_pose(rig, &obj->pose, prev_t, r->joint_matrices);
			aa_mesh_skin(m, r->joint_matrices, r->skin_scratch);
			before = r->skin_scratch;
		}
		for (uint32_t v = 0; v < m->vertex_count; v++) {
			float *p = previous + 4 * ((size_t)r->skin_offset[o] + v);
			p[0] = before[v].position[0], p[1] = before[v].position[1], p[2] = before[v].position[2], p[3] = 1.0f;
		}
	}
}

/* Draw orders sort object indices by a key per object, smallest first and the scene's order on ties, so
 * that the order is the same on every run (qsort alone is not stable). */
static int compare_key(const void *a, const void *b, void *user)
{
	const float *key = user;
	float ka = key[*(const int *)a], kb = key[*(const int *)b];
	return ka < kb ? -1 : ka > kb ? 1 : *(const int *)a - *(const int *)b;
}

/* The distance from p to the farthest point of box b. */
static float farthest_distance(const struct aa_box *b, vec3 p)
{
	vec3 lo = v3_sub(b->min, p), hi = v3_sub(b->max, p);
	vec3 d = v3(fmaxf(fabsf(lo.x), fabsf(hi.x)), fmaxf(fabsf(lo.y), fabsf(hi.y)), fmaxf(fabsf(lo.z), fabsf(hi.z)));
	return sqrtf(v3_dot(d, d));
}

int aa_draw_order_front_to_back(const struct aa_box *bounds, int count, vec3 eye, int *order)
{
	float *reach = malloc((size_t)(count > 0 ? count : 1) * sizeof *reach);
	if (!reach)
		return -1;
	for (int o = 0; o < count; o++)
		reach[o] = farthest_distance(&bounds[o], eye);
	qsort_r(order, (size_t)count, sizeof *order, compare_key, reach);
	free(reach);
	return 0;
}

/* This frame's draw orders. Blended objects: back to front, as blending needs. Opaque and cut-out ones:
 * front to back by where their boxes end (aa_draw_order_front_to_back), so that llvmpipe's early depth
 * test rejects the hidden fragments of a floor or wall before they are shaded (docs/architecture.md,
 * "Rendering"). The order can only change which of two exactly equal depths wins, and every method
 * and the reference draw through it. Without memory for the keys the scene's order stands. */
static void sort_draws(struct aa_renderer *r, const struct aa_camera *camera)
{
	const struct aa_scene *s = r->scene;
	vec3 forward = v3_normalize(v3_sub(camera->target, camera->position));
	float *depth = malloc((size_t)(s->object_count ? s->object_count : 1) * sizeof *depth);
	r->blend_count = 0;
	for (int o = 0; o < s->object_count; o++) {
		r->opaque_order[o] = o;
		if (!s->materials[s->objects[o].material_index].blend)
			continue;
		vec3 c = v3_scale(v3_add(r->bounds[o].min, r->bounds[o].max), 0.5f);
		if (depth) /* farthest first: the smallest key */
			depth[o] = -v3_dot(v3_sub(c, camera->position), forward);
		r->blend_order[r->blend_count++] = o;
	}
	if (depth)
		qsort_r(r->blend_order, (size_t)r->blend_count, sizeof *r->blend_order, compare_key, depth);
	free(depth);
	aa_draw_order_front_to_back(r->bounds, s->object_count, camera->position, r->opaque_order);
}

/* The shadow cascades for this camera (shadow_fit.c) into the frame uniforms. */
static void fit_shadow(struct aa_renderer *r, const struct aa_camera *camera, const double eye[3], int light,
		       struct aa_frame_uniforms *u)
{
	const struct aa_scene *s = r->scene;
	const float *d = s->lights[light].direction;
	struct aa_shadow_fit_input in = {
		.camera = *camera, .eye = {eye[0], eye[1], eye[2]}, .aspect = (float)r->width / (float)r->height,
		.light_direction = v3(d[0], d[1], d[2]), .boxes = r->bounds, .box_count = s->object_count,
		.tile_size = AA_SHADOW_TILE_SIZE,
	};
	aa_shadow_fit(&in, &r->shadow_fit);
	const struct aa_shadow_fit *f = &r->shadow_fit;
	memcpy(u->shadow_light_view, f->light_view.m, sizeof u->shadow_light_view);
	for (int i = 0; i < AA_SHADOW_CASCADES; i++) {
		const struct aa_shadow_cascade *c = &f->cascades[i];
		for (int k = 0; k < 3; k++) {
			u->shadow_cascade_scale[i][k] = c->scale[k];
			u->shadow_cascade_offset[i][k] = c->offset[k];
		}
		u->shadow_cascade_scale[i][3] = 0.5f / AA_SHADOW_TILE_SIZE;
		u->shadow_cascade_offset[i][3] = c->texel * c->scale[2];
		if (i + 1 < AA_SHADOW_CASCADES) /* beyond the cascades in use: never reached */
			u->shadow_splits[i] = isfinite(f->splits[i + 1]) ? f->splits[i + 1] : 3.0e38f;
	}
	u->shadow_splits[3] = isfinite(f->splits[AA_SHADOW_CASCADES]) ? f->splits[AA_SHADOW_CASCADES] : 3.0e38f;
	/* the first cascade as one matrix, for anything that reads the old single map's field */
	const struct aa_shadow_cascade *c0 = &f->cascades[0];
	mat4 fit = mat4_identity();
	fit.m[0] = c0->scale[0], fit.m[5] = c0->scale[1], fit.m[10] = c0->scale[2];
	fit.m[12] = c0->offset[0], fit.m[13] = c0->offset[1], fit.m[14] = c0->offset[2];
	r->shadow_view_proj = mat4_mul(fit, f->light_view);
	memcpy(u->shadow_view_proj, r->shadow_view_proj.m, sizeof u->shadow_view_proj);
}

/* The camera moved to the origin of camera-relative space: world position eye, its target relative to it. */
static struct aa_camera relative_camera(const struct aa_camera *camera, double eye[3])
{
	struct aa_camera c = *camera;
	aa_camera_eye(camera, eye);
	c.origin[0] = c.origin[1] = c.origin[2] = 0.0;
	c.target = v3_sub(camera->target, camera->position); /* both relative to the same origin: exact enough */
	c.position = v3(0, 0, 0);
	return c;
}

/* Camera-relative rendering (docs/architecture.md): what the GPU sees is relative to this frame's eye, with
 * the subtraction done in double on the CPU (model translations, point lights); the view matrix is a
 * rotation. The previous frame's model matrices are relative to the previous eye and its view_proj has
 * no translation either, so velocity compares the two frames without a world-sized number in between. */
void aa_renderer_set_frame(struct aa_renderer *r, const struct aa_camera *camera, double t,
			   const struct aa_camera *prev_camera, double prev_t, struct aa_frame_ctx *ctx)
{
	const struct aa_scene *s = r->scene;
	double eye[3], prev_eye[3];
	struct aa_camera rel = relative_camera(camera, eye);
	ctx->camera = rel;
	ctx->time = t;
	ctx->width = r->width;
	ctx->height = r->height;
	ctx->view = mat4_look_at(rel.position, rel.target, rel.up);
	ctx->proj = camera_projection(&rel, r->width, r->height);
	ctx->view_proj = mat4_mul(ctx->proj, ctx->view);
	ctx->prev_view_proj = ctx->view_proj;
	memcpy(prev_eye, eye, sizeof prev_eye);
	if (prev_camera) {
		struct aa_camera prev_rel = relative_camera(prev_camera, prev_eye);
		ctx->prev_view_proj = mat4_mul(camera_projection(&prev_rel, r->width, r->height),
					       mat4_look_at(prev_rel.position, prev_rel.target, prev_rel.up));
	}
	mat4 *prev = r->prev_models.mapped; /* by model_id: every part of an object moves as the object */
	for (int o = 0; o < s->object_count; o++) {
		const struct aa_object *obj = &s->objects[o];
		const struct aa_mesh *m = &s->meshes[obj->mesh_index];
		r->models[o] = aa_object_model_relative(obj, t, eye);
		prev[obj->model_id - 1] = aa_object_model_relative(obj, prev_camera ? prev_t : t, prev_eye);
		r->bounds[o] = aa_box_transform(r->models[o], m->bounds_min, m->bounds_max);
	}
	pose_skinned(r, t, prev_camera != NULL, prev_t);
	sort_draws(r, &rel);

	struct aa_frame_uniforms *u = &r->uniforms;
	memset(u, 0, sizeof *u);
	memcpy(u->view_proj, ctx->view_proj.m, sizeof u->view_proj);
	memcpy(u->prev_view_proj, ctx->prev_view_proj.m, sizeof u->prev_view_proj);
	u->camera_planes[0] = camera->near_plane;
	u->camera_planes[1] = camera->far_plane;
	u->camera_planes[2] = camera->projection == AA_PROJECTION_ORTHOGRAPHIC ? 1.0f : 0.0f;
	/* the shaders' world positions are relative to the eye: the frame carries no camera position */
	vec3 forward = v3_normalize(rel.target);
	u->camera_forward[0] = forward.x, u->camera_forward[1] = forward.y, u->camera_forward[2] = forward.z;
	memcpy(u->ambient, s->ambient, 3 * sizeof(float));
	u->frame_size[0] = (float)r->width;
	u->frame_size[1] = (float)r->height;
	int shadow_light = -1;
	for (int i = 0; i < s->light_count && i < AA_MAX_LIGHTS; i++) {
		const struct aa_light *l = &s->lights[i];
		bool point = l->type == AA_LIGHT_POINT;
		for (int k = 0; k < 3; k++) {
			u->lights[i].position_type[k] = point ? (float)(l->position[k] - eye[k]) : l->direction[k];
			u->lights[i].color_range[k] = l->color[k] * l->intensity;
		}
		u->lights[i].position_type[3] = point ? 1.0f : 0.0f;
		u->lights[i].color_range[3] = l->range;
		if (i == r->shadow_light) {
			shadow_light = i;
			u->lights[i].shadow[0] = 1.0f;
		}
		u->counts[0] = i + 1;
	}
	u->counts[1] = shadow_light >= 0;
	u->counts[2] = r->inject_nonfinite;
	if (shadow_light >= 0)
		fit_shadow(r, &rel, eye, shadow_light, u);
	memcpy(r->frame_ubo.mapped, u, sizeof *u);
}
