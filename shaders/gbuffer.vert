#version 450
#extension GL_GOOGLE_include_directive : require
// G-buffer pass geometry: as scene.vert, plus this frame's and the previous frame's unjittered clip
// positions, from which the fragment shader derives screen-space velocity.
#include "common.glsl"

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;

layout(location = 0) out vec3 out_world;
layout(location = 1) out vec3 out_normal;
layout(location = 2) out vec2 out_uv;
layout(location = 3) out vec4 out_clip;
layout(location = 4) out vec4 out_prev_clip;
layout(location = 5) out vec3 out_barycentric; // virtual_sample_gbuffer.geom writes the real ones

void main()
{
	vec4 world = draw.model * vec4(in_position, 1.0);
	mat3 nm = mat3(draw.normal_matrix[0].xyz, draw.normal_matrix[1].xyz, draw.normal_matrix[2].xyz);
	out_world = world.xyz;
	out_normal = nm * in_normal;
	out_uv = in_uv;
	out_barycentric = vec3(1.0);
	vec4 clip = frame.view_proj * world;
	out_clip = clip;
	out_prev_clip = frame.prev_view_proj * (prev_models[draw.object_id - 1u] * vec4(in_position, 1.0));
	clip.xy += draw.jitter_ndc * clip.w;
	gl_Position = clip;
}
