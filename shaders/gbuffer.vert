#version 450
#extension GL_GOOGLE_include_directive : require
// G-buffer pass geometry: as scene.vert, plus this frame's and the previous frame's unjittered clip
// positions, from which the fragment shader derives screen-space velocity.
#include "common.glsl"

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;
layout(location = 3) in vec4 in_tangent;
layout(location = 4) in vec4 in_color;

layout(location = 0) out vec3 out_world;
layout(location = 1) out vec3 out_normal;
layout(location = 2) out vec2 out_uv;
layout(location = 3) out vec4 out_clip;
layout(location = 4) out vec4 out_prev_clip;
layout(location = 5) out vec3 out_barycentric; // virtual_sample_gbuffer.geom writes the real ones
layout(location = 8) out vec4 out_tangent;
layout(location = 9) out vec4 out_color;
layout(location = 10) out vec4 out_shadow; // shadow_coordinates(): light space, view depth

// Skinned parts (posed on the CPU each frame): their previous positions, at the same index as this frame's
// vertices, so that velocity follows the joints (engine/renderer.c).
layout(constant_id = 36) const bool SKINNED = false;
layout(std430, set = 0, binding = 9) readonly buffer PreviousSkinned {
	vec4 prev_skinned[];
};

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
	out_clip = clip;
	vec3 prev_position = SKINNED ? prev_skinned[gl_VertexIndex].xyz : in_position;
	out_prev_clip = frame.prev_view_proj * (prev_models[draw.object_id - 1u] * vec4(prev_position, 1.0));
	clip.xy += draw.jitter_ndc * clip.w;
	gl_Position = clip;
}
