/* 2D test patterns as scenes: flat unlit polygons seen by an orthographic camera whose image is exactly
 * the pixel grid, so an exact-coverage reference can be compared pixel for pixel. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/mesh_procedural.h"
#include "scene/scene.h"

/* Pixel (x, y), y down, sits at world (x, -y, 0); the camera looks down -z from z = 1 at the image
 * centre with y up, so world -y (pixel y) runs down the image. */
static vec3 pixel_to_world(double x, double y)
{
	return v3((float)x, (float)-y, 0.0f);
}

int aa_scene_from_polygons(const struct aa_polygon2d *polys, int poly_count, int width, int height,
			   const float fg[3], const float bg[3], struct aa_scene **out, struct aa_error *err)
{
	*out = NULL;
	if (width < 1 || height < 1 || width > 16384 || height > 16384)
		return aa_error_set(err, AA_ERR_INVALID, "", "image size %dx%d must be 1 to 16384 on each side", width,
				    height);
	if (poly_count < 1 || poly_count > 4096)
		return aa_error_set(err, AA_ERR_INVALID, "", "need 1 to 4096 polygons, got %d", poly_count);
	uint32_t tris = 0;
	for (int i = 0; i < poly_count; i++) {
		if (polys[i].count < 3 || polys[i].count > 16)
			return aa_error_set(err, AA_ERR_INVALID, "", "polygon %d has %d vertices (3 to 16 allowed)", i,
					    polys[i].count);
		for (int k = 0; k < polys[i].count; k++)
			if (!isfinite(polys[i].xy[k][0]) || !isfinite(polys[i].xy[k][1]))
				return aa_error_set(err, AA_ERR_INVALID, "", "polygon %d has a non-finite vertex", i);
		tris += (uint32_t)polys[i].count - 2;
	}

	struct aa_scene *sc = calloc(1, sizeof *sc);
	if (!sc)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	snprintf(sc->name, sizeof sc->name, "polygons");
	snprintf(sc->description, sizeof sc->description, "%d flat polygons on %dx%d pixels", poly_count, width, height);
	memcpy(sc->background, bg, sizeof sc->background);
	sc->fps = 30.0;
	sc->meshes = calloc(1, sizeof *sc->meshes);
	sc->materials = calloc(1, sizeof *sc->materials);
	sc->objects = calloc(1, sizeof *sc->objects);
	sc->paths = calloc(1, sizeof *sc->paths);
	struct aa_mesh *m = sc->meshes;
	if (sc->meshes) {
		m->vertices = calloc((size_t)tris + 2u * (uint32_t)poly_count, sizeof *m->vertices);
		m->indices = calloc((size_t)tris * 3, sizeof *m->indices);
	}
	if (!sc->materials || !sc->objects || !sc->paths || !sc->meshes || !m->vertices || !m->indices ||
	    !(sc->paths[0].keys = calloc(1, sizeof *sc->paths[0].keys))) {
		if (sc->meshes)
			sc->mesh_count = 1;
		if (sc->paths)
			sc->path_count = 1;
		aa_scene_free(sc);
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	}
	sc->mesh_count = sc->material_count = sc->object_count = sc->path_count = 1;
	m->part_count = 1;
	m->file_material = m->rig = -1;

	/* One mesh: each convex polygon as a fan, turned to face the camera (+z) whichever way it winds. */
	snprintf(m->name, sizeof m->name, "polygons");
	for (int i = 0; i < poly_count; i++) {
		const struct aa_polygon2d *p = &polys[i];
		double area = 0;
		for (int k = 0; k < p->count; k++) {
			const double *a = p->xy[k], *b = p->xy[(k + 1) % p->count];
			area += a[0] * -b[1] - b[0] * -a[1]; /* in world orientation (y flipped) */
		}
		uint32_t first = m->vertex_count;
		for (int k = 0; k < p->count; k++) {
			struct aa_vertex *v = &m->vertices[m->vertex_count++];
			vec3 w = pixel_to_world(p->xy[k][0], p->xy[k][1]);
			v->position[0] = w.x, v->position[1] = w.y, v->position[2] = w.z;
			v->normal[2] = 1.0f;
			v->uv[0] = (float)(p->xy[k][0] / width), v->uv[1] = (float)(p->xy[k][1] / height);
			v->tangent[0] = v->tangent[3] = 1.0f;
			for (int c = 0; c < 4; c++)
				v->color[c] = 1.0f;
		}
		for (int k = 1; k + 1 < p->count; k++) {
			uint32_t b = first + (uint32_t)k, c = first + (uint32_t)k + 1;
			m->indices[m->index_count++] = first;
			m->indices[m->index_count++] = area >= 0 ? b : c;
			m->indices[m->index_count++] = area >= 0 ? c : b;
		}
	}

	aa_mesh_compute_bounds(m);
	struct aa_material *mat = sc->materials;
	aa_material_defaults(mat);
	snprintf(mat->name, sizeof mat->name, "foreground");
	memcpy(mat->base_color, fg, 3 * sizeof(float));
	mat->base_color[3] = 1.0f;
	mat->pattern = AA_PATTERN_NONE;
	mat->texture_index = -1;
	mat->scale[0] = mat->scale[1] = 1.0f;
	mat->stripe_width = 0.5f;
	mat->roughness = 0.5f;
	mat->alpha_cutoff = 0.5f;
	mat->unlit = true;

	struct aa_object *o = sc->objects;
	snprintf(o->name, sizeof o->name, "polygons");
	o->transform = mat4_identity();
	o->model_id = 1;
	o->pose.clip = -1;
	sc->model_count = 1;

	/* Orthographic, ortho_height = height: with a width:height viewport the view spans x in
	 * [-w/2, w/2], y in [-h/2, h/2] around the image centre, which is world [0,w] x [-h,0]. */
	struct aa_camera *cam = &sc->paths[0].keys[0].camera;
	cam->position = v3(0.5f * (float)width, -0.5f * (float)height, 1.0f);
	cam->target = v3(0.5f * (float)width, -0.5f * (float)height, 0.0f);
	cam->up = v3(0, 1, 0);
	cam->projection = AA_PROJECTION_ORTHOGRAPHIC;
	cam->fov_y_degrees = 50.0f;
	cam->ortho_height = (float)height;
	cam->near_plane = 0.5f;
	cam->far_plane = 2.0f;
	snprintf(sc->paths[0].name, sizeof sc->paths[0].name, "main");
	sc->paths[0].kind = AA_PATH_STATIC;
	sc->paths[0].key_count = 1;
	sc->uid = aa_scene_new_uid();
	*out = sc;
	return 0;
}
