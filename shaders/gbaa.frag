#version 450
#extension GL_GOOGLE_include_directive : require
// GBAA geometry pass: the shaded colour, and in a second target the signed offset to the nearest triangle
// edge along its major axis (x or y); the other channel holds 0.5, "no edge this way".
#include "common.glsl"
#include "shading.glsl"

layout(constant_id = 0) const bool ALPHA_TEST = false;

layout(location = 0) in vec3 in_world;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;
layout(location = 3) flat in vec3 in_edge_line[3]; // gbaa.geom: a x + b y + c = 0 in pixels
layout(location = 8) in vec4 in_tangent;
layout(location = 9) in vec4 in_color;
layout(location = 10) in vec4 in_shadow; // shadow_coordinates(): light space, view depth

layout(location = 0) out vec4 out_color;
layout(location = 1) out vec2 out_edge_offset;

void main()
{
	Material m = material;
	vec2 uv_dx = dFdx(in_uv), uv_dy = dFdy(in_uv);
	vec4 base = surface_color_vertex(m, in_uv, uv_dx, uv_dy, in_color);
	if (ALPHA_TEST && base.a < m.shading.z)
		discard;
	Surface s = Surface(in_world, in_shadow, in_normal, in_tangent, in_uv, uv_dx, uv_dy, gl_FrontFacing);
	out_color = vec4(shade(m, base, s), MATERIAL_BLEND ? base.a : 1.0);
	// the offset from this pixel's centre to each edge along its major axis: for a mostly horizontal edge
	// (|b| >= |a|) the y where the line crosses this column, minus ours; an edge seen end-on has no axis
	float nearest = 1e3;
	bool vertical = true;
	for (int e = 0; e < 3; e++) {
		vec3 l = in_edge_line[e];
		float along = dot(l, vec3(gl_FragCoord.xy, 1.0));
		bool horizontal = abs(l.y) >= abs(l.x);
		float axis = horizontal ? l.y : l.x;
		float d = abs(axis) > 0.0 ? -along / axis : 1e3;
		if (abs(d) < abs(nearest)) {
			nearest = d;
			vertical = horizontal;
		}
	}
	float d = clamp(nearest, -2.0, 2.0);
	out_edge_offset = vertical ? vec2(0.5, d) : vec2(d, 0.5);
}
