#version 450
#extension GL_GOOGLE_include_directive : require
// GBAA (Persson 2011, seed 000 section 3.3): for each triangle, its three edges as lines in homogeneous
// pixel coordinates (the cross product of two vertices' (x, y, w) in pixels times w), passed flat; the
// fragment shader evaluates them at its pixel centre for the signed offset to each edge along the edge's
// major axis (vertical distance for a mostly horizontal edge, horizontal for a mostly vertical one).
// The seed's form, distances computed at the projected vertices and interpolated without perspective,
// divides by w: a vertex near or behind the eye plane gave huge or meaningless values (such triangles had
// to be left without edges), and the clipper's new vertices carried whatever it interpolated. A line
// through two homogeneous points is exact wherever they lie, and a flat value is never interpolated.
#include "common.glsl"

layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;

layout(location = 0) in vec3 in_world[];
layout(location = 1) in vec3 in_normal[];
layout(location = 2) in vec2 in_uv[];
layout(location = 8) in vec4 in_tangent[];
layout(location = 9) in vec4 in_color[];
layout(location = 10) in vec4 in_shadow[];

layout(location = 0) out vec3 out_world;
layout(location = 1) out vec3 out_normal;
layout(location = 2) out vec2 out_uv;
layout(location = 8) out vec4 out_tangent; // passed through: normal maps, vertex colours
layout(location = 9) out vec4 out_color;
layout(location = 10) out vec4 out_shadow;
layout(location = 3) flat out vec3 out_edge_line[3]; // edge e (opposite vertex e): a x + b y + c = 0 in pixels

void main()
{
	vec3 p[3];
	for (int i = 0; i < 3; i++) {
		vec4 c = gl_in[i].gl_Position;
		p[i] = vec3((c.xy * 0.5 + 0.5 * c.w) * frame.frame_size.xy, c.w);
	}
	vec3 line[3];
	for (int e = 0; e < 3; e++)
		line[e] = cross(p[(e + 1) % 3], p[(e + 2) % 3]);
	for (int v = 0; v < 3; v++) {
		gl_Position = gl_in[v].gl_Position;
		out_world = in_world[v];
		out_normal = in_normal[v];
		out_uv = in_uv[v];
		out_tangent = in_tangent[v];
		out_color = in_color[v];
		out_shadow = in_shadow[v];
		out_edge_line = line;
		EmitVertex();
	}
	EndPrimitive();
}
