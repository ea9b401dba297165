#version 450
#extension GL_GOOGLE_include_directive : require
// Scene geometry: world-space position and normal; jitter is a translation applied after the projection,
// so every depth moves by the same sub-pixel amount (seed 000 applied it before, which is wrong).
#include "common.glsl"

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;
layout(location = 3) in vec4 in_tangent;
layout(location = 4) in vec4 in_color;

layout(location = 0) out vec3 out_world;
layout(location = 1) out vec3 out_normal;
layout(location = 2) out vec2 out_uv;
layout(location = 3) out vec3 out_barycentric; // virtual_sample.geom writes the real ones
layout(location = 8) out vec4 out_tangent;     // normal maps
layout(location = 9) out vec4 out_color;       // vertex colours
layout(location = 10) out vec4 out_shadow;     // shadow_coordinates(): light space, view depth

void main()
{
	vec4 world = draw.model * vec4(in_position, 1.0);
	mat3 nm = mat3(draw.normal_matrix[0].xyz, draw.normal_matrix[1].xyz, draw.normal_matrix[2].xyz);
	out_world = world.xyz;
	out_shadow = shadow_coordinates(world.xyz);
	out_normal = nm * in_normal;
	out_uv = in_uv;
	out_tangent = vec4(mat3(draw.model) * in_tangent.xyz, in_tangent.w);
	out_color = in_color;
	out_barycentric = vec3(1.0);
	vec4 clip = frame.view_proj * world;
	clip.xy += draw.jitter_ndc * clip.w;
	gl_Position = clip;
}
