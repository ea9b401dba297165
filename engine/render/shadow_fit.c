/* Shadow cascades fitted to the view (shadow_fit.h). */
#include "render/shadow_fit.h"

#include <math.h>
#include <string.h>

/* How the splits lean between uniform (0) and logarithmic (1) spacing. Logarithmic: each cascade is the
 * same factor deeper than the last, so a shadow texel covers about as many pixels in every cascade. */
#define SPLIT_LAMBDA 1.0f

struct aa_box aa_box_transform(mat4 m, const float lo[3], const float hi[3])
{
	struct aa_box b = {v3(INFINITY, INFINITY, INFINITY), v3(-INFINITY, -INFINITY, -INFINITY)};
	for (int c = 0; c < 8; c++) {
		vec3 p = mat4_transform_point(m, v3(c & 1 ? hi[0] : lo[0], c & 2 ? hi[1] : lo[1], c & 4 ? hi[2] : lo[2]));
		b.min = v3(fminf(b.min.x, p.x), fminf(b.min.y, p.y), fminf(b.min.z, p.z));
		b.max = v3(fmaxf(b.max.x, p.x), fmaxf(b.max.y, p.y), fmaxf(b.max.z, p.z));
	}
	return b;
}

static struct aa_box light_box(mat4 light_view, const struct aa_box *world)
{
	float lo[3] = {world->min.x, world->min.y, world->min.z}, hi[3] = {world->max.x, world->max.y, world->max.z};
	return aa_box_transform(light_view, lo, hi);
}

/* Rounded to a grid of 2^(1/4) steps, down or up: a range that moves a little with the camera keeps
 * its splits (and so every cascade's size) until it moves by a step. */
static float quantize(float x, bool up)
{
	float e = log2f(fmaxf(x, 1e-6f)) * 4.0f;
	return exp2f((up ? ceilf(e) : floorf(e)) / 4.0f);
}

/* The view depths of the part of a box the camera sees: the box's faces clipped by the view frustum
 * (Sutherland-Hodgman against its side planes and near/far). False when none of it is in view. */
static bool visible_depths(const struct aa_box *box, const struct aa_camera *cam, vec3 right, vec3 up, vec3 forward,
			   float tan_x, float tan_y, float half_w, float half_h, float *lo, float *hi)
{
	static const int faces[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
	bool ortho = cam->projection == AA_PROJECTION_ORTHOGRAPHIC, any = false;
	vec3 corner[8];
	for (int c = 0; c < 8; c++) {
		vec3 p = v3_sub(v3(c & 1 ? box->max.x : box->min.x, c & 2 ? box->max.y : box->min.y,
				   c & 4 ? box->max.z : box->min.z), cam->position);
		corner[c] = v3(v3_dot(p, right), v3_dot(p, up), v3_dot(p, forward)); /* view space, z = depth */
	}
	for (int f = 0; f < 6; f++) {
		vec3 poly[16], next[16];
		int n = 4;
		for (int k = 0; k < 4; k++)
			poly[k] = corner[faces[f][k]];
		for (int plane = 0; plane < 6 && n > 0; plane++) {
			int m = 0;
			for (int k = 0; k < n; k++) {
				vec3 a = poly[k], b = poly[(k + 1) % n];
				float ga, gb; /* >= 0 inside */
#define SIDE(p) (plane == 0 ? (ortho ? half_w : (p).z * tan_x) - (p).x : plane == 1 ? (ortho ? half_w : (p).z * tan_x) + (p).x 		 : plane == 2 ? (ortho ? half_h : (p).z * tan_y) - (p).y : plane == 3 ? (ortho ? half_h : (p).z * tan_y) + (p).y 		 : plane == 4 ? (p).z - cam->near_plane : cam->far_plane - (p).z)
				ga = SIDE(a), gb = SIDE(b);
#undef SIDE
				if (ga >= 0 && m < 16)
					next[m++] = a;
				if ((ga >= 0) != (gb >= 0) && m < 16)
					next[m++] = v3_lerp(a, b, ga / (ga - gb));
			}
			n = m;
			for (int k = 0; k < n; k++)
				poly[k] = next[k];
		}
		for (int k = 0; k < n; k++) {
			*lo = fminf(*lo, poly[k].z), *hi = fmaxf(*hi, poly[k].z);
			any = true;
		}
	}
	return any;
}

bool aa_shadow_cascade_sees(const struct aa_shadow_fit *fit, int i, const struct aa_box *box)
{
	const struct aa_shadow_cascade *c = &fit->cascades[i];
	struct aa_box l = light_box(fit->light_view, box);
	return l.max.x >= c->center.x - c->radius && l.min.x <= c->center.x + c->radius &&
	       l.max.y >= c->center.y - c->radius && l.min.y <= c->center.y + c->radius;
}

void aa_shadow_fit(const struct aa_shadow_fit_input *in, struct aa_shadow_fit *out)
{
	memset(out, 0, sizeof *out);
	const struct aa_camera *cam = &in->camera;
	/* light space: z toward the light, x and y across it; a fixed basis, so a fixed texel grid */
	vec3 z = v3_normalize(v3_scale(in->light_direction, -1.0f));
	vec3 up = fabsf(z.y) < 0.99f ? v3(0, 1, 0) : v3(1, 0, 0);
	vec3 x = v3_normalize(v3_cross(up, z)), y = v3_cross(z, x);
	mat4 lv = mat4_identity();
	lv.m[0] = x.x, lv.m[4] = x.y, lv.m[8] = x.z;
	lv.m[1] = y.x, lv.m[5] = y.y, lv.m[9] = y.z;
	lv.m[2] = z.x, lv.m[6] = z.y, lv.m[10] = z.z;
	out->light_view = lv;

	/* the view depths where something in view can receive a shadow */
	vec3 forward = v3_normalize(v3_sub(cam->target, cam->position));
	vec3 right = v3_normalize(v3_cross(forward, cam->up)), up_view = v3_cross(right, forward);
	float tan_y = tanf(cam->fov_y_degrees * 3.14159265f / 360.0f), tan_x = tan_y * in->aspect;
	float half_h = 0.5f * cam->ortho_height, half_w = half_h * in->aspect;
	float d_lo = INFINITY, d_hi = -INFINITY;
	struct aa_box everything = {v3(INFINITY, INFINITY, INFINITY), v3(-INFINITY, -INFINITY, -INFINITY)};
	for (int k = 0; k < in->box_count; k++) {
		const struct aa_box *b = &in->boxes[k];
		visible_depths(b, cam, right, up_view, forward, tan_x, tan_y, half_w, half_h, &d_lo, &d_hi);
		everything.min = v3(fminf(everything.min.x, b->min.x), fminf(everything.min.y, b->min.y),
				    fminf(everything.min.z, b->min.z));
		everything.max = v3(fmaxf(everything.max.x, b->max.x), fmaxf(everything.max.y, b->max.y),
				    fmaxf(everything.max.z, b->max.z));
	}
	if (!(d_hi >= d_lo)) /* nothing in view */
		d_lo = cam->near_plane, d_hi = 2.0f * cam->near_plane;
	float n = fmaxf(cam->near_plane, quantize(fmaxf(d_lo, cam->near_plane), false));
	float f = fminf(cam->far_plane, quantize(fmaxf(d_hi, n * 1.01f), true));
	if (!(f > n))
		f = n * 2.0f;
	for (int i = 0; i <= AA_SHADOW_CASCADES; i++) {
		float s = (float)i / AA_SHADOW_CASCADES;
		out->splits[i] = SPLIT_LAMBDA * n * powf(f / n, s) + (1.0f - SPLIT_LAMBDA) * (n + (f - n) * s);
	}
	out->splits[0] = n, out->splits[AA_SHADOW_CASCADES] = f;

	/* the scene's own extent across the light: a cascade never needs more */
	struct aa_box scene = light_box(lv, &everything);
	float scene_radius = quantize(0.5f * fmaxf(scene.max.x - scene.min.x, scene.max.y - scene.min.y), true);
	vec3 scene_center = v3_scale(v3_add(scene.min, scene.max), 0.5f);
	float k2 = tan_x * tan_x + tan_y * tan_y;
	out->cascade_count = AA_SHADOW_CASCADES;
	for (int i = 0; i < out->cascade_count; i++) {
		struct aa_shadow_cascade *c = &out->cascades[i];
		float a = out->splits[i], b = out->splits[i + 1], along, radius;
		if (cam->projection == AA_PROJECTION_ORTHOGRAPHIC) {
			float hy = 0.5f * cam->ortho_height, hx = hy * in->aspect;
			along = 0.5f * (a + b);
			radius = sqrtf(0.25f * (b - a) * (b - a) + hx * hx + hy * hy);
		} else {
			/* the sphere through the slice's corners, centred on the view axis: its size depends only
			 * on the slice, not on where the camera turns */
			along = fminf(0.5f * (a + b) * (1.0f + k2), b);
			radius = sqrtf((along - b) * (along - b) + b * b * k2);
		}
		vec3 center = mat4_transform_point(lv, v3_add(cam->position, v3_scale(forward, along)));
		if (scene_radius < radius) { /* the whole scene is smaller: its box, fixed while nothing moves */
			radius = scene_radius;
			center = scene_center;
			out->cascade_count = i + 1; /* and later cascades would only repeat it */
			for (int k = i + 1; k <= AA_SHADOW_CASCADES; k++)
				out->splits[k] = INFINITY;
		}
		radius = fmaxf(radius, 1e-3f);
		c->texel = 2.0f * radius / (float)in->tile_size;
		/* snapped in world light space (eye's light-space position added in double), returned relative */
		double eye_x = (double)x.x * in->eye[0] + (double)x.y * in->eye[1] + (double)x.z * in->eye[2];
		double eye_y = (double)y.x * in->eye[0] + (double)y.y * in->eye[1] + (double)y.z * in->eye[2];
		c->center = v3((float)(round((center.x + eye_x) / c->texel) * c->texel - eye_x),
			       (float)(round((center.y + eye_y) / c->texel) * c->texel - eye_y), center.z);
		c->radius = radius;
		/* depth: just the casters over this window */
		float zn = -INFINITY, zf = INFINITY;
		for (int k = 0; k < in->box_count; k++) {
			struct aa_box l = light_box(lv, &in->boxes[k]);
			if (l.max.x < c->center.x - radius || l.min.x > c->center.x + radius || l.max.y < c->center.y - radius ||
			    l.min.y > c->center.y + radius)
				continue;
			zn = fmaxf(zn, l.max.z), zf = fminf(zf, l.min.z);
		}
		if (!(zn > zf)) { /* nothing casts here (or one flat caster): any range will do */
			zn = isfinite(zn) ? zn + radius : center.z + radius;
			zf = isfinite(zf) ? zf - radius : center.z - radius;
		}
		float margin = 1e-3f * (zn - zf) + 1e-4f;
		c->z_near = zn + margin, c->z_far = zf - margin;
		c->scale[0] = c->scale[1] = 1.0f / radius;
		c->scale[2] = 1.0f / (c->z_near - c->z_far);
		c->offset[0] = -c->center.x / radius, c->offset[1] = -c->center.y / radius;
		c->offset[2] = -c->z_far / (c->z_near - c->z_far);
	}
}
