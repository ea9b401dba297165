#version 450
// SMAA pass 3, neighbourhood blending (notes/smaa.md §4). Each pixel gathers the four weights that touch
// it (its own top and left edges, its right and bottom neighbours' edges), keeps the stronger direction
// and mixes in the neighbours on that axis. The reference does this with two bilinear reads at
// fractional offsets; on one axis those are exactly lerps between two texels, done here from texel reads
// (cheaper on lavapipe). The colour is the linear scene colour, so the blend happens in linear light
// (what SMAA's sRGB view achieves) and the output is linear again. It runs behind an early depth test
// against the edge pass's blend mask, into a copy of the scene colour: lavapipe shades only the blocks
// that hold a pixel whose weights may be non-zero (a branch cannot skip work there). With REPROJECT (T2x,
// 4x) the velocity is blended with the colour's weights and its length packed in alpha, as the reference
// does for its temporal resolve: sqrt(5 |velocity in UV units|).
layout(constant_id = 0) const bool REPROJECT = false;
layout(early_fragment_tests) in;
layout(set = 0, binding = 0) uniform sampler2D colour_tex;  // linear RGBA16F
layout(set = 0, binding = 1) uniform sampler2D weights_tex; // RGBA8 from pass 2
layout(set = 0, binding = 2) uniform sampler2D velocity_tex; // REPROJECT: RG16F, pixels
layout(location = 0) out vec4 out_colour;

void main()
{
	ivec2 p = ivec2(gl_FragCoord.xy);
	ivec2 last = textureSize(weights_tex, 0) - 1;
	vec4 here = texelFetch(weights_tex, p, 0);
	// x: right neighbour's left edge, y: bottom neighbour's top edge (their "other side" weights);
	// z: this pixel's left edge, w: its top edge
	vec4 a = vec4(texelFetch(weights_tex, min(p + ivec2(1, 0), last), 0).a,
		      texelFetch(weights_tex, min(p + ivec2(0, 1), last), 0).g, here.b, here.r);
	vec4 c = texelFetch(colour_tex, p, 0);
	vec2 rcp = 1.0 / vec2(last + 1);
	if (dot(a, vec4(1.0)) < 1e-5) {
		out_colour = c;
		if (REPROJECT)
			out_colour.a = sqrt(5.0 * length(texelFetch(velocity_tex, p, 0).rg * rcp));
		return;
	}
	bool horizontal = max(a.x, a.z) > max(a.y, a.w); // ties go vertical
	ivec2 axis = horizontal ? ivec2(1, 0) : ivec2(0, 1);
	vec2 amount = horizontal ? a.xz : a.yw; // towards +axis, towards -axis
	vec4 plus = texelFetch(colour_tex, min(p + axis, last), 0);
	vec4 minus = texelFetch(colour_tex, max(p - axis, ivec2(0)), 0);
	vec2 weights = amount / (amount.x + amount.y);
	out_colour = weights.x * mix(c, plus, amount.x) + weights.y * mix(c, minus, amount.y);
	if (REPROJECT) {
		vec2 v = texelFetch(velocity_tex, p, 0).rg;
		vec2 v_plus = texelFetch(velocity_tex, min(p + axis, last), 0).rg;
		vec2 v_minus = texelFetch(velocity_tex, max(p - axis, ivec2(0)), 0).rg;
		vec2 blended = weights.x * mix(v, v_plus, amount.x) + weights.y * mix(v, v_minus, amount.y);
		out_colour.a = sqrt(5.0 * length(blended * rcp));
	}
}
