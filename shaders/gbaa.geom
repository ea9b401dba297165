#version 450
#extension GL_GOOGLE_include_directive : require
// GBAA (Persson 2011, seed 000 section 3.3): for each triangle, the screen-space distance from each vertex
// to each of the three edges, measured along the edge's major axis (vertical distance for a mostly
// horizontal edge, horizontal for a mostly vertical one). Interpolated without perspective these give,
// at every pixel, the signed offset to each edge.
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
layout(location = 3) noperspective out vec3 out_edge_distance;
layout(location = 4) flat out vec3 out_edge_vertical; // 1: distance is along y (edge mostly horizontal)

void main()
{
	vec2 p[3];
	bool behind = false;
	for (int i = 0; i < 3; i++) {
		vec4 c = gl_in[i].gl_Position;
		behind = behind || c.w <= 1e-6;
		p[i] = (c.xy / max(c.w, 1e-6) * 0.5 + 0.5) * frame.frame_size.xy;
	}
	vec3 vertical;
	float dist[3][3]; // dist[vertex][edge]; edge e joins vertices e+1 and e+2 (opposite vertex e)
	for (int e = 0; e < 3; e++) {
		vec2 a = p[(e + 1) % 3], b = p[(e + 2) % 3], d = b - a;
		bool horizontal = abs(d.x) >= abs(d.y);
		vertical[e] = horizontal ? 1.0 : 0.0;
		for (int v = 0; v < 3; v++) {
			float value;
			if (behind || max(abs(d.x), abs(d.y)) < 1e-6)
				value = 1e3; // no usable edge: never blends
			else if (horizontal)
				value = a.y + d.y * (p[v].x - a.x) / d.x - p[v].y;
			else
				value = a.x + d.x * (p[v].y - a.y) / d.y - p[v].x;
			dist[v][e] = value;
		}
	}
	for (int v = 0; v < 3; v++) {
		gl_Position = gl_in[v].gl_Position;
		out_world = in_world[v];
		out_normal = in_normal[v];
		out_uv = in_uv[v];
		out_tangent = in_tangent[v];
		out_color = in_color[v];
		out_shadow = in_shadow[v];
		out_edge_distance = vec3(dist[v][0], dist[v][1], dist[v][2]);
		out_edge_vertical = vertical;
		EmitVertex();
	}
	EndPrimitive();
}
