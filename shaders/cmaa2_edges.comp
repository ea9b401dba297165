#version 450
#extension GL_GOOGLE_include_directive : require
// CMAA2 pass 1, edge detection: for each pixel the edges towards its right and bottom neighbours. The
// contrast across an edge is the Rec. 601 luma-weighted sum of the per-channel differences of the
// gamma-encoded colours (CMAA2's colour path); an edge is kept when it reaches the preset's threshold
// and, local contrast adaptation, when no edge touching either of its two pixels has more than
// lca_factor times its contrast (a soft step beside a hard silhouette forms no line of its own).
#include "cmaa2_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2D scene; // linear RGBA16F, texel reads
layout(set = 0, binding = 1, r8ui) uniform writeonly uimage2D edges_out;
layout(push_constant) uniform Push {
	float threshold;
	float lca_factor;
} push;

ivec2 last;

// CMAA2's gamma for edge detection: the sRGB curve approximated by a square root (a pow per channel and
// fetch would be most of this pass's cost)
vec3 encoded(ivec2 p)
{
	return sqrt(clamp(texelFetch(scene, clamp(p, ivec2(0), last), 0).rgb, 0.0, 1.0));
}

// CMAA2's colour contrast: the per-channel differences weighted as Rec. 601 luma
float contrast(vec3 a, vec3 b)
{
	return dot(abs(a - b), vec3(0.299, 0.587, 0.114));
}

void main()
{
	ivec2 p = ivec2(gl_GlobalInvocationID.xy);
	ivec2 size = textureSize(scene, 0);
	if (any(greaterThanEqual(p, size)))
		return;
	last = size - 1;
	// the pixel, its four neighbours and the pixels beyond its right and bottom neighbours
	vec3 c = encoded(p), l = encoded(p + ivec2(-1, 0)), t = encoded(p + ivec2(0, -1));
	vec3 r = encoded(p + ivec2(1, 0)), b = encoded(p + ivec2(0, 1));
	float right = p.x < last.x ? contrast(c, r) : 0.0;
	float bottom = p.y < last.y ? contrast(c, b) : 0.0;
	uint bits = 0u;
	if (right >= push.threshold) {
		float around = max(max(contrast(c, l), contrast(c, t)), contrast(c, b));
		around = max(around, contrast(r, encoded(p + ivec2(2, 0))));
		around = max(around, max(contrast(r, encoded(p + ivec2(1, -1))), contrast(r, encoded(p + ivec2(1, 1)))));
		if (push.lca_factor * right >= around)
			bits |= EDGE_RIGHT;
	}
	if (bottom >= push.threshold) {
		float around = max(max(contrast(c, l), contrast(c, t)), contrast(c, r));
		around = max(around, contrast(b, encoded(p + ivec2(0, 2))));
		around = max(around, max(contrast(b, encoded(p + ivec2(-1, 1))), contrast(b, encoded(p + ivec2(1, 1)))));
		if (push.lca_factor * bottom >= around)
			bits |= EDGE_BOTTOM;
	}
	imageStore(edges_out, p, uvec4(bits));
}
