/* Fitting the shadow map to the camera's view: AA_SHADOW_CASCADES orthographic maps from the light, each
 * covering one slice of the view frustum (closer slices are smaller, so shadows near the camera get fine
 * texels), sized by the slice's bounding sphere (the same size however the camera turns), centred on a
 * whole texel of a fixed light-space grid (so a camera moving by less than a texel moves nothing in the
 * map: no shimmer made here), and with a depth range that just holds the casters over the slice. Pure
 * maths: the renderer feeds it bounds and gets matrices (docs/architecture.md, "Rendering"). */
#ifndef AA_SHADOW_FIT_H
#define AA_SHADOW_FIT_H

#include <stdbool.h>

#include "util/mat4.h"
#include "scene/scene.h"

#define AA_SHADOW_CASCADES 4

struct aa_box {
	vec3 min, max;
};

struct aa_shadow_fit_input {
	/* Camera-relative (docs/architecture.md): the camera and boxes are relative to eye, the camera's world
	 * position; eye only places the texel grid, which stays fixed in the world as the camera moves. */
	struct aa_camera camera;
	double eye[3];
	float aspect;            /* width / height of the frame */
	vec3 light_direction;    /* where the light travels (normalised) */
	const struct aa_box *boxes; /* boxes of what is drawn (relative to eye): receivers, and casters */
	int box_count;
	int tile_size;           /* texels per side of each cascade's map */
};

struct aa_shadow_cascade {
	vec3 center;             /* light space, on the texel grid */
	float radius;            /* half the side of the map, light-space units */
	float z_near, z_far;     /* light-space z: toward the light is larger */
	float scale[3], offset[3]; /* NDC = light-space position * scale + offset (reversed-Z) */
	float texel;             /* light-space units per texel */
};

struct aa_shadow_fit {
	mat4 light_view;         /* world -> light space (a rotation) */
	int cascade_count;       /* in use: once a cascade holds the whole scene, it covers the rest of the view */
	float splits[AA_SHADOW_CASCADES + 1]; /* view depths: cascade i covers [splits[i], splits[i+1]] */
	struct aa_shadow_cascade cascades[AA_SHADOW_CASCADES];
};

void aa_shadow_fit(const struct aa_shadow_fit_input *in, struct aa_shadow_fit *out);
/* Whether a world box lies (partly) in a cascade's light-space window. */
bool aa_shadow_cascade_sees(const struct aa_shadow_fit *fit, int cascade, const struct aa_box *box);
/* The world box of a local box under a matrix. */
struct aa_box aa_box_transform(mat4 m, const float local_min[3], const float local_max[3]);

#endif
