#version 450
#extension GL_GOOGLE_include_directive : require
// Master TAA's edge image (seed 001, eq. 4.9-4.10): Sobel magnitudes of the unlit luma u, the lit luma l
// and the linear depth d, mixed as g = clamp01(0.3 u + 0.7 l + d), then sobel = sqrt(g^2 (3 - 2g)).
// With `tonemapped` (preset=converge) the lit luma is L / (1 + L), as the resolve sees colour: on HDR
// values the linear luma's gradient saturates g everywhere a bright light falls, and every pixel would
// count as an edge. Seed 001 rendered LDR and used the lit luma as is (preset=seed001).
#include "taa_common.glsl"

layout(set = 0, binding = 0) uniform sampler2D current; // lit colour
layout(set = 0, binding = 1) uniform sampler2D surface; // unlit luma, linear depth
layout(push_constant) uniform Push { int tonemapped; } push;
layout(location = 0) out float out_sobel;

void main()
{
	ivec2 p = ivec2(gl_FragCoord.xy);
	ivec2 last = textureSize(current, 0) - 1;
	vec3 gx = vec3(0.0), gy = vec3(0.0); // (u, l, d)
	const float kx[9] = float[9](-1, 0, 1, -2, 0, 2, -1, 0, 1);
	const float ky[9] = float[9](1, 2, 1, 0, 0, 0, -1, -2, -1);
	for (int y = -1; y <= 1; y++)
		for (int x = -1; x <= 1; x++) {
			ivec2 q = clamp(p + ivec2(x, y), ivec2(0), last);
			vec3 c = texelFetch(current, q, 0).rgb;
			float lit = finite3(c) ? dot(c, vec3(0.2126, 0.7152, 0.0722)) : 0.0;
			if (push.tonemapped != 0)
				lit = lit / (1.0 + max(lit, 0.0));
			vec2 s = texelFetch(surface, q, 0).xy;
			vec3 v = vec3(s.x, lit, s.y);
			int k = (y + 1) * 3 + (x + 1);
			gx += kx[k] * v;
			gy += ky[k] * v;
		}
	vec3 m = sqrt(gx * gx + gy * gy);
	float g = clamp(0.3 * m.x + 0.7 * m.y + m.z, 0.0, 1.0);
	out_sobel = sqrt(g * g * (3.0 - 2.0 * g));
}
