#version 450
#extension GL_GOOGLE_include_directive : require
// FXAA edge mask (pixel shader variant): edge pixels get the triangle's depth 0 over the mask's clear to
// 1; the pixels FXAA leaves alone are discarded and keep the 1. The resolve pass then runs behind an early depth test, so llvmpipe shades only the
// blocks that hold an edge: a branch cannot skip work there, since every branch runs under a mask.
#include "fxaa_common.glsl"

layout(set = 0, binding = 0) uniform sampler2D luma_tex; // sRGB colour + luma
FXAA_PUSH_BLOCK;

void main()
{
	ivec2 p = ivec2(gl_FragCoord.xy);
	if (!fxaa_is_edge(luma_tex, p, textureSize(luma_tex, 0), push.edge_threshold, push.edge_threshold_min))
		discard;
}
