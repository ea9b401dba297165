#version 450
#extension GL_GOOGLE_include_directive : require
// FXAA 3.11 (quality path) as a pixel shader, on edge pixels only: it draws into the scene colour, behind
// the edge mask's early depth test (fxaa_edges.frag), so every other pixel keeps the scene colour. Edge
// pixels get FXAA's offset fetch from the luma texture, decoded back to linear.
#include "fxaa_common.glsl"

layout(set = 0, binding = 0) uniform sampler2D luma_tex; // sRGB colour + luma, bilinear clamp
FXAA_PUSH_BLOCK;
layout(location = 0) out vec4 out_color;

void main()
{
	ivec2 p = ivec2(gl_FragCoord.xy);
	ivec2 size = textureSize(luma_tex, 0);
	FxaaPixel px;
	fxaa_classify(luma_tex, p, size, push.edge_threshold, push.edge_threshold_min, px); // true: an edge
	// alpha as the scene pass writes it everywhere (scene.frag): 1
	out_color = vec4(fxaa_srgb_to_linear(fxaa_resolve_edge(luma_tex, p, size, px, push.subpix)), 1.0);
}
