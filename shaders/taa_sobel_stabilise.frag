#version 450
#extension GL_GOOGLE_include_directive : require
// The Sobel image stabilised by a simplified TAA (seed 001, 4.3.3): the reprojected previous value is
// clamped (not clipped: the values are one-dimensional) to the 3x3 range and blended; no sharpening.
#include "taa_common.glsl"

layout(set = 0, binding = 0) uniform sampler2D edges;    // this frame's Sobel image
layout(set = 0, binding = 1) uniform sampler2D history;  // stabilised Sobel of the previous frame
layout(set = 0, binding = 2) uniform sampler2D velocity;
layout(push_constant) uniform Push {
	float feedback_min, feedback_max;
	int history_valid;
	float history_frames;
} push;
layout(location = 0) out float out_sobel;

void main()
{
	ivec2 p = ivec2(gl_FragCoord.xy);
	ivec2 last = textureSize(edges, 0) - 1;
	float mn = 1e30, mx = -1e30;
	for (int y = -1; y <= 1; y++)
		for (int x = -1; x <= 1; x++) {
			float e = texelFetch(edges, clamp(p + ivec2(x, y), ivec2(0), last), 0).r;
			mn = min(mn, e);
			mx = max(mx, e);
		}
	float cur = texelFetch(edges, p, 0).r;
	vec2 uv;
	vec2 v = texelFetch(velocity, p, 0).xy;
	if (push.history_valid == 0 || !history_position(gl_FragCoord.xy, v, vec2(textureSize(edges, 0)), uv)) {
		out_sobel = cur;
		return;
	}
	float h = clamp(texture(history, uv).r, mn, mx);
	out_sobel = mix(cur, h, feedback(cur, h, push.feedback_min, push.feedback_max));
}
