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
layout(location = 3) noperspective in vec3 in_edge_distance;
layout(location = 4) flat in vec3 in_edge_vertical;
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
	int nearest = 0;
	for (int e = 1; e < 3; e++)
		if (abs(in_edge_distance[e]) < abs(in_edge_distance[nearest]))
			nearest = e;
	float d = clamp(in_edge_distance[nearest], -2.0, 2.0);
	out_edge_offset = in_edge_vertical[nearest] > 0.5 ? vec2(0.5, d) : vec2(d, 0.5);
}
