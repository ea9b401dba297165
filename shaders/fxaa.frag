#version 450
#extension GL_GOOGLE_include_directive : require
// FXAA 3.11 (quality path) as a pixel shader: pixels below the local contrast threshold keep the scene
// colour; edge pixels get FXAA's offset fetch from the luma texture, decoded back to linear.
#include "fxaa_common.glsl"

layout(set = 0, binding = 0) uniform sampler2D luma_tex; // sRGB colour + luma, bilinear clamp
layout(set = 0, binding = 1) uniform sampler2D scene;    // linear scene colour, nearest
FXAA_PUSH_BLOCK;
layout(location = 0) out vec4 out_color;

void main()
{
	ivec2 p = ivec2(gl_FragCoord.xy);
	ivec2 size = textureSize(luma_tex, 0);
	vec4 original = texelFetch(scene, p, 0);
	FxaaPixel px;
	if (!fxaa_classify(luma_tex, p, size, push.edge_threshold, push.edge_threshold_min, px)) {
		out_color = original;
		return;
	}
	out_color = vec4(fxaa_srgb_to_linear(fxaa_resolve_edge(luma_tex, p, size, px, push.subpix)), original.a);
}
