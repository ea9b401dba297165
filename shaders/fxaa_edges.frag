#version 450
#extension GL_GOOGLE_include_directive : require
// FXAA edge mask (pixel shader variant): the depth of pixels FXAA leaves alone is set to 1, edge pixels
// keep the cleared 0. The resolve pass then runs behind an early depth test, so llvmpipe shades only the
// blocks that hold an edge: a branch cannot skip work there, since every branch runs under a mask.
#include "fxaa_common.glsl"

layout(set = 0, binding = 0) uniform sampler2D luma_tex; // sRGB colour + luma
FXAA_PUSH_BLOCK;

void main()
{
	ivec2 p = ivec2(gl_FragCoord.xy);
	if (fxaa_is_edge(luma_tex, p, textureSize(luma_tex, 0), push.edge_threshold, push.edge_threshold_min))
		discard;
	gl_FragDepth = 1.0;
}
