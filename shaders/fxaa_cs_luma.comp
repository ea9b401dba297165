#version 450
#extension GL_GOOGLE_include_directive : require
// FXAA compute variant, pass 1: the luma texture (sRGB colour + luma in alpha, RGBA8), as fxaa_luma.frag.
#include "fxaa_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2D scene;
layout(set = 0, binding = 1, rgba8) uniform writeonly image2D luma_out;

void main()
{
	ivec2 p = ivec2(gl_GlobalInvocationID.xy);
	if (any(greaterThanEqual(p, imageSize(luma_out))))
		return;
	imageStore(luma_out, p, fxaa_encode(texelFetch(scene, p, 0)));
}
