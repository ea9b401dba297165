#version 450
#extension GL_GOOGLE_include_directive : require
// T2MSAA resolve (seed 000, section 4.4.2, Listings 4.14-4.19): the mean of this frame's two samples is
// blended with the previous frame, fetched bilinearly at centre - velocity, by luminance-weighted
// exponential smoothing; a = max(1/(N+1), blur threshold). On a miss (rejection rules of the thesis) the
// frame is the current 2x image and N = 1. Unlike the thesis, N is capped (max_samples), and history is
// RGBA32F, so a static scene converges instead of stalling.
#include "asaa_t2msaa.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2D sample0;      // virtual sample 0 (G-buffer target)
layout(set = 0, binding = 1) uniform sampler2D sample1;      // virtual sample 1
layout(set = 0, binding = 2) uniform sampler2D velocity;     // RG16F, pixels, current - previous
layout(set = 0, binding = 3) uniform sampler2D surface;      // RG32F: unlit luma, linear depth
layout(set = 0, binding = 4) uniform sampler2D history;      // previous frame (bilinear)
layout(set = 0, binding = 5) uniform sampler2D state;        // previous: log2 linear depth, samples N, still
layout(set = 0, binding = 6, rgba32f) uniform writeonly image2D history_out;
layout(set = 0, binding = 7, rgba16f) uniform writeonly image2D state_out;

layout(push_constant) uniform Push {
	ivec2 size;
	float max_samples;
	int history_valid; // 0 on the first frame after a reset: nothing to reproject
	int blur_uv;       // blur threshold from |velocity| in UV units (the thesis's code), not pixel fractions
} pc;

// Listing 4.19. pc.blur_uv 0: with the fractional part of the velocity in pixels, Eq. 3.31's meaning
// (the blur bilinear resampling adds depends on where the previous position falls between texels, not
// on how many whole pixels it moved). pc.blur_uv 1: as the thesis's code, |velocity| in UV units, which
// for a motion under a pixel is 1/width (1/height) of the pixel fraction: its threshold stays near
// sigma^2 = 0.25 at any speed the view can show.
float blur_threshold(float a, vec2 v)
{
	vec2 f = pc.blur_uv != 0 ? min(abs(v) / vec2(pc.size), vec2(1.0)) : fract(abs(v));
	float spread = (f.x * (1.0 - f.x) + f.y * (1.0 - f.y)) * 0.5;
	return clamp(0.5 * 0.5 + ((1.0 - a) / a) * spread, 0.0, 1.0);
}

void main()
{
	ivec2 p = ivec2(gl_GlobalInvocationID.xy);
	if (any(greaterThanEqual(p, pc.size)))
		return;
	vec2 size = vec2(pc.size);
	vec3 current = 0.5 * (finite_sample(sample0, p, pc.size) + finite_sample(sample1, p, pc.size));
	float depth = surface_depth(surface, p);
	vec2 v = texelFetch(velocity, p, 0).xy;
	vec2 q = vec2(p) + 0.5 - v;

	bool hit = pc.history_valid != 0 && velocity_valid(v) && on_screen(q, size) &&
		   !magnified(q, footprint_radius(velocity, p, pc.size));
	vec3 previous = vec3(0.0);
	float samples = 1.0, still_before = 0.0;
	bool moving = any(notEqual(v, vec2(0.0)));
	if (hit) {
		vec2 uv = q / size;
		previous = textureLod(history, uv, 0.0).rgb;
		float previous_depth = depth_decode(textureLod(state, uv, 0.0).x);
		// the count where the pixel came from (Eq. 3.29 reprojects it too), nearest texel
		vec4 st = texelFetch(state, clamp(ivec2(floor(q)), ivec2(0), pc.size - 1), 0);
		samples = st.y;
		still_before = finite1(st.z) ? st.z : 0.0;
		// disocclusion needs motion: a still pixel that was still last frame cannot have been uncovered,
		// and the two frames' samples may see different sub-pixel geometry without any disocclusion
		bool depth_test = moving || still_before < 1.0;
		hit = all_finite(previous) && !(depth_test && disoccluded(depth, previous_depth)) && finite1(samples);
	}
	vec3 frame = current;
	if (hit) {
		samples = clamp(samples, 1.0, pc.max_samples);
		float a = 1.0 / (samples + 1.0);
		float tb = moving ? blur_threshold(a, v) : 0.0;
		a = max(a, tb);
		previous = clamp(previous, vec3(0.0), vec3(65504.0));
		float wc = a / (1.0 + luma(current));
		float wp = (1.0 - a) / (1.0 + luma(previous));
		frame = (wc * current + wp * previous) / (wc + wp); // wc > 0: a >= 1/(max_samples + 1)
		if (a > tb)
			samples = min(samples + 1.0, pc.max_samples);
	} else {
		samples = 1.0;
	}
	imageStore(history_out, p, vec4(frame, 1.0));
	float still_now = hit && !moving ? min(still_before + 1.0, 8.0) : 0.0;
	imageStore(state_out, p, vec4(depth_encode(depth), samples, still_now, 0.0));
}
