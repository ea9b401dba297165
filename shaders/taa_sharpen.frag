#version 450
// Sharpening of the TAA result for display (history keeps the unsharpened colour, so sharpening never
// accumulates). ORIGINAL: Xu's [0 -1 0; -1 5 -1; 0 -1 0]; otherwise the thesis's normalised
// [0 -0.25 0; -0.25 2 -0.25; 0 -0.25 0], which avoids bright peaks next to dark pixels. strength 0: off.
layout(set = 0, binding = 0) uniform sampler2D resolved;
layout(push_constant) uniform Push { int kind; } push; // 0 off, 1 original, 2 normalized
layout(location = 0) out vec4 out_color;

void main()
{
	ivec2 p = ivec2(gl_FragCoord.xy);
	ivec2 last = textureSize(resolved, 0) - 1;
	vec3 c = texelFetch(resolved, p, 0).rgb;
	if (push.kind == 0) {
		out_color = vec4(c, 1.0);
		return;
	}
	vec3 n = texelFetch(resolved, clamp(p + ivec2(0, -1), ivec2(0), last), 0).rgb +
		 texelFetch(resolved, clamp(p + ivec2(0, 1), ivec2(0), last), 0).rgb +
		 texelFetch(resolved, clamp(p + ivec2(-1, 0), ivec2(0), last), 0).rgb +
		 texelFetch(resolved, clamp(p + ivec2(1, 0), ivec2(0), last), 0).rgb;
	vec3 s = push.kind == 1 ? 5.0 * c - n : 2.0 * c - 0.25 * n;
	out_color = vec4(max(s, vec3(0.0)), 1.0);
}
