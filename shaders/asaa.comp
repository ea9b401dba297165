#version 450
#extension GL_GOOGLE_include_directive : require
// ASAA resolve (seed 000, sections 3.8 and 4.4.1): four sub-pixel buffers, buffer k holding samples of
// pixel quadrant phi_k. Each frame one buffer (index) receives a new sample s: it is blended with the
// tent-weighted reconstruction of all four buffers around the quadrant's position (Eq. 3.21-3.26,
// radius r_b), and the frame is the reconstruction around the pixel centre (radius r_f = 2 r_b) blended
// with s by a/4 (Eq. 3.28). Each 2x2 tent is one bilinear fetch (Eq. 3.24-3.25).
//
// Reprojection differs from the thesis, which reprojected static geometry by depth and matrices: here the
// velocity buffer moves everything, objects included. Buffers are up to four frames old and velocity
// spans one frame, so the displacement from each pixel to each buffer's content is chained: this frame's
// displacement to a buffer of age a+1 is last frame's displacement to it (age a, read at centre -
// velocity) minus velocity. The three displacements still needed next frame are written out with the
// sample count N (motion_a/motion_b, ping-ponged); 65000 marks "no valid history".
#include "asaa_t2msaa.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2D current;      // this frame's sample (jittered render)
layout(set = 0, binding = 1) uniform sampler2D velocity;     // RG16F, pixels, current - previous
layout(set = 0, binding = 2) uniform sampler2D surface;      // RG32F: unlit luma, linear depth
layout(set = 0, binding = 3) uniform sampler2D buffers[4];   // rgb, log2 linear depth of the sample (bilinear)
layout(set = 0, binding = 4) uniform sampler2D motion_a;     // displacement to buffers of age 1 (xy), 2 (zw)
layout(set = 0, binding = 5) uniform sampler2D motion_b;     // age 3 (xy), samples N (z), still frames (w)
layout(set = 0, binding = 6, rgba16f) uniform writeonly image2D updated;   // new contents of buffer index
layout(set = 0, binding = 7, rgba16f) uniform writeonly image2D frame_out;
layout(set = 0, binding = 8, rgba16f) uniform writeonly image2D motion_a_out;
layout(set = 0, binding = 9, rgba16f) uniform writeonly image2D motion_b_out;

layout(push_constant) uniform Push {
	vec4 quadrant[4];     // xy: phi_k, the sub-pixel offset of buffer k's samples, pixels
	ivec2 size;
	int index;            // the buffer this frame updates
	int valid_ages;       // buffers written since the last reset (0..4); older ones are empty
	float max_samples;    // cap on N (the thesis leaves it unbounded on static pixels)
	float motion_samples; // cap on N while the pixel moves (thesis: 4, Listing 4.11)
	float final_radius;   // tent radius of the frame reconstruction in footprints (thesis: 2 x 0.5)
	int still;            // priming after a cut: every buffer shows this frame, ignore velocity
	int tonemapped_resolve; // Karis' 1/(1 + luma) weight on every colour summed or blended
} pc;

// tonemapped_resolve: each tap (a bilinear fetch of 2x2 texels), the new sample and the history count
// 1/(1 + luma) times their usual weight (Karis 2014, as t2msaa's blend), so a jittered hit on an HDR
// emitter cannot spread it over the pixel and its neighbours for frames.
#define RESOLVE_KARIS (pc.tonemapped_resolve != 0)
#define RESOLVE_LUMA luma
#include "resolve_weight.glsl"

const float NO_HISTORY = 65000.0;

// Tent-weighted mean of the 2x2 texels around pos (texel space, centres at i + 0.5), radius r per axis:
// the separable weights become one bilinear fetch at base + w1 / (w0 + w1), times their total.
vec4 tent_fetch(int k, vec2 pos, vec2 r, out float weight)
{
	vec2 base = floor(pos - 0.5) + 0.5;
	vec2 t = pos - base;
	vec2 w0 = clamp(1.0 - t / r, 0.0, 1.0);
	vec2 w1 = clamp(1.0 - (1.0 - t) / r, 0.0, 1.0);
	vec2 sum = w0 + w1;
	weight = sum.x * sum.y;
	if (!(weight > 0.0))
		return vec4(0.0);
	vec2 uv = (base + w1 / sum) / vec2(pc.size);
	// constant indices: dynamic indexing of sampler arrays is an optional device feature
	if (k == 0)
		return textureLod(buffers[0], uv, 0.0);
	if (k == 1)
		return textureLod(buffers[1], uv, 0.0);
	if (k == 2)
		return textureLod(buffers[2], uv, 0.0);
	return textureLod(buffers[3], uv, 0.0);
}

bool stored_valid(vec2 d)
{
	return finite1(d.x) && finite1(d.y) && all(lessThan(abs(d), vec2(NO_MOTION_LIMIT)));
}

void main()
{
	ivec2 p = ivec2(gl_GlobalInvocationID.xy);
	if (any(greaterThanEqual(p, pc.size)))
		return;
	vec2 size = vec2(pc.size);
	vec2 c = vec2(p) + 0.5;
	vec3 s = finite_sample(current, p, pc.size);
	float depth = surface_depth(surface, p);
	vec2 v = pc.still != 0 ? vec2(0.0) : texelFetch(velocity, p, 0).xy;
	vec2 q = c - v;
	vec2 radius = pc.still != 0 ? vec2(1.0) : footprint_radius(velocity, p, pc.size);
	bool reprojected = pc.valid_ages > 0 && velocity_valid(v) && on_screen(q, size) && !magnified(q, radius);

	// last frame's displacements and count where this pixel was, nearest texel (no mixing across edges)
	ivec2 qp = clamp(ivec2(floor(q)), ivec2(0), pc.size - 1);
	vec4 ma = reprojected ? texelFetch(motion_a, qp, 0) : vec4(NO_HISTORY);
	vec4 mb = reprojected ? texelFetch(motion_b, qp, 0) : vec4(NO_HISTORY, NO_HISTORY, 0.0, 0.0);
	vec2 displacement[4] = vec2[](-v, ma.xy - v, ma.zw - v, mb.xy - v);
	bool valid[4] = bool[](reprojected, stored_valid(ma.xy), stored_valid(ma.zw), stored_valid(mb.xy));

	// tent radii from the footprint (Listing 4.5), kept to what a 2x2 fetch can represent
	// Disocclusion needs motion: a pixel that showed a still surface through the buffers' lifetime (the
	// last four frames) and is still now cannot have been uncovered. Skipping the depth test there keeps
	// sub-pixel geometry, which one quadrant's sample hits and another's misses (a depth difference
	// without any disocclusion), from being rejected over and over on a still camera.
	bool moving = any(notEqual(v, vec2(0.0)));
	float still_before = reprojected && finite1(mb.w) ? mb.w : 0.0;
	bool depth_test = moving || still_before < 4.0;
	float still_now = moving || !reprojected ? 0.0 : min(still_before + 1.0, 8.0);

	vec2 r = clamp(radius, vec2(0.5), vec2(1.0));
	vec2 rb = 0.5 * r, rf = pc.final_radius * r;
	vec2 phi_i = pc.quadrant[pc.index].xy;
	vec3 cb = vec3(0.0), cf = vec3(0.0);
	float wb_sum = 0.0, wf_sum = 0.0; // tent coverage: how much of the footprint the buffers hold
	float kb_sum = 0.0, kf_sum = 0.0; // the weights cb and cf are sums of (tent x resolve_weight)
	for (int age = 0; age < 4; age++) {
		if (!(reprojected && valid[age] && age < pc.valid_ages))
			continue;
		int k = (pc.index + 3 - age) & 3; // the buffer written age + 1 frames ago
		vec2 phi_k = pc.quadrant[k].xy;
		vec2 previous = c + displacement[age];
		float wb, wf;
		vec4 b = tent_fetch(k, previous + phi_i - phi_k, rb, wb);  // Eq. 3.23
		vec4 f = tent_fetch(k, previous - phi_k, rf, wf);          // Eq. 3.27
		if (wb > 0.0 && all_finite(b.rgb) && !(depth_test && disoccluded(depth, depth_decode(b.w)))) {
			float k = wb * resolve_weight(b.rgb);
			cb += k * b.rgb;
			kb_sum += k;
			wb_sum += wb;
		}
		if (wf > 0.0 && all_finite(f.rgb) && !(depth_test && disoccluded(depth, depth_decode(f.w)))) {
			float k = wf * resolve_weight(f.rgb);
			cf += k * f.rgb;
			kf_sum += k;
			wf_sum += wf;
		}
	}

	// N counts the pixel's samples over all four buffers; the updated buffer holds floor(N/4) of them, and
	// a = 1/(floor(N/4) + 1) makes each buffer the running mean of its own samples up to the cap (the
	// thesis's 1/(N+1) gives a buffer's first samples too much weight: 4x slower to converge). The caps
	// are per buffer: max_samples on still pixels, 4 under motion (Listing 4.11: a >= 1/5).
	float n = reprojected && finite1(mb.z) ? clamp(mb.z, 0.0, 4.0 * pc.max_samples + 3.0) : 0.0;
	if (moving)
		n = min(n, 4.0 * pc.motion_samples + 3.0);
	if (!(wb_sum > 1e-3))
		n = 0.0; // nothing of this quadrant survived: full weight to the new sample
	float a = 1.0 / (floor(n * 0.25) + 1.0);
	vec3 buffer_value = a < 1.0 ? resolve_mix(cb / kb_sum, s, a) : s;                // Eq. 3.26
	vec3 frame = s;
	if (a < 1.0 && wf_sum > 1e-3)
		frame = resolve_mix(cf / kf_sum, s, 0.25 * a); // Eq. 3.28
	else if (wf_sum > 1e-3)                            // own quadrant empty: s stands in for its buffer
		frame = (cf + resolve_weight(s) * s) / (kf_sum + resolve_weight(s));

	float n_next = min(n + 1.0, 4.0 * pc.max_samples + 3.0);

	imageStore(updated, p, vec4(clamp(buffer_value, vec3(0.0), vec3(65504.0)), depth_encode(depth)));
	imageStore(frame_out, p, vec4(clamp(frame, vec3(0.0), vec3(65504.0)), 1.0));
	// next frame's ages 2, 3, 4 are this frame's 1, 2, 3
	vec2 d0 = valid[0] ? displacement[0] : vec2(NO_HISTORY);
	vec2 d1 = reprojected && valid[1] && pc.valid_ages > 1 ? displacement[1] : vec2(NO_HISTORY);
	vec2 d2 = reprojected && valid[2] && pc.valid_ages > 2 ? displacement[2] : vec2(NO_HISTORY);
	imageStore(motion_a_out, p, vec4(d0, d1));
	imageStore(motion_b_out, p, vec4(d2, n_next, still_now));
}
