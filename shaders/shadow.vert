#version 450
#extension GL_GOOGLE_include_directive : require
// Shadow map: depth from the shadow-casting directional light (orthographic, reversed-Z).
#include "common.glsl"

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;
layout(location = 4) in vec4 in_color;

layout(location = 0) out vec2 out_uv;
layout(location = 1) out float out_alpha; // vertex colour alpha (glTF multiplies the base colour by it)

// One draw per cascade, its index as the instance (firstInstance): the cascade's viewport is its quarter
// of the atlas, and its orthographic box clips the rest.
void main()
{
	out_uv = in_uv;
	out_alpha = in_color.a;
	int cascade = gl_InstanceIndex;
	vec3 light = (frame.shadow_light_view * (draw.model * vec4(in_position, 1.0))).xyz;
	gl_Position = vec4(light * frame.shadow_cascade_scale[cascade].xyz + frame.shadow_cascade_offset[cascade].xyz, 1.0);
}
