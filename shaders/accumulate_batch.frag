#version 450
// Adds up to seven renders, times a weight, to the running sum (engine/reference/sample_accumulator.c).
// The sum is read from one RGBA32F image and written to the other, and the renders are added one at a
// time in order, so the float result is the same as blending each render into the sum in its own pass.
layout(set = 0, binding = 0) uniform sampler2D previous_sum;
layout(set = 0, binding = 1) uniform sampler2D render0;
layout(set = 0, binding = 2) uniform sampler2D render1;
layout(set = 0, binding = 3) uniform sampler2D render2;
layout(set = 0, binding = 4) uniform sampler2D render3;
layout(set = 0, binding = 5) uniform sampler2D render4;
layout(set = 0, binding = 6) uniform sampler2D render5;
layout(set = 0, binding = 7) uniform sampler2D render6;
// BATCH: the renders bound (1..7), fixed per pipeline; push.count: how many hold a render this time.
// llvmpipe fetches under a mask too, so BATCH keeps a small batch from paying for seven fetches.
layout(constant_id = 0) const int BATCH = 7;
layout(push_constant) uniform Push { float weight; int count; } push;
layout(location = 0) out vec4 out_sum;

void main()
{
	ivec2 p = ivec2(gl_FragCoord.xy);
	vec4 sum = texelFetch(previous_sum, p, 0);
	sum += texelFetch(render0, p, 0) * push.weight;
	if (BATCH > 1 && push.count > 1) sum += texelFetch(render1, p, 0) * push.weight;
	if (BATCH > 2 && push.count > 2) sum += texelFetch(render2, p, 0) * push.weight;
	if (BATCH > 3 && push.count > 3) sum += texelFetch(render3, p, 0) * push.weight;
	if (BATCH > 4 && push.count > 4) sum += texelFetch(render4, p, 0) * push.weight;
	if (BATCH > 5 && push.count > 5) sum += texelFetch(render5, p, 0) * push.weight;
	if (BATCH > 6 && push.count > 6) sum += texelFetch(render6, p, 0) * push.weight;
	out_sum = sum;
}
