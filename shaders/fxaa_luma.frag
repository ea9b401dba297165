#version 450
#extension GL_GOOGLE_include_directive : require
// FXAA luma pass: linear scene colour -> sRGB-encoded colour with luma in alpha (RGBA8), the input
// FXAA 3.11 expects.
#include "fxaa_common.glsl"

layout(set = 0, binding = 0) uniform sampler2D scene;
layout(location = 0) out vec4 out_color;

void main()
{
	out_color = fxaa_encode(texelFetch(scene, ivec2(gl_FragCoord.xy), 0));
}
