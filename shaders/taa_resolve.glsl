// TAA resolve (seed 001). Baseline ("Uncharted TAA"): colour box from the 3x3 and cross min/max, averaged;
// velocity of the closest-depth pixel in 3x3; history clipped toward the box centre in YCoCg;
// luminance-difference feedback. MASTER (the thesis's "Master TAA"): the box is chosen and shrunk per
// pixel by aliasedValue, from model IDs, depth pseudo-variances and the stabilised Sobel image.
// Writes the new history: linear colour (alpha: linear depth, for the next frame's MASTER test), and the
// same colour as the displayed image (location 1; dropped when a sharpen pass writes that instead).
// Included by taa_resolve.frag (MASTER_TAA 0) and taa_master_resolve.frag (MASTER_TAA 1).
#include "taa_common.glsl"

const bool MASTER = MASTER_TAA != 0;

layout(set = 0, binding = 0) uniform sampler2D current;   // jittered scene colour, nearest
layout(set = 0, binding = 1) uniform sampler2D history;   // previous output, bilinear
layout(set = 0, binding = 2) uniform sampler2D velocity;  // pixels, nearest
layout(set = 0, binding = 3) uniform sampler2D surface;   // unlit luma, linear depth; nearest
#if MASTER_TAA
layout(set = 0, binding = 4) uniform usampler2D ids;      // model IDs
layout(set = 0, binding = 5) uniform sampler2D sobel;     // stabilised Sobel image
#endif

layout(push_constant) uniform Push {
	float feedback_min, feedback_max;
	int history_valid;
	float history_frames; // frames accumulated since the last reset
} push;

layout(location = 0) out vec4 out_history;
layout(location = 1) out vec4 out_display;

void main()
{
	ivec2 p = ivec2(gl_FragCoord.xy);
	ivec2 last = textureSize(current, 0) - 1;
	vec2 size = vec2(textureSize(current, 0));

	// neighbourhood in YCoCg; non-finite samples are left out (they must not reach history)
	vec3 mn3 = vec3(1e30), mx3 = vec3(-1e30), sum3 = vec3(0.0), mnx = vec3(1e30), mxx = vec3(-1e30),
	     sumx = vec3(0.0);
	float n3 = 0.0, nx = 0.0, closest = 1e30, dsum = 0.0, dmin = 1e30, dmax = -1e30;
	ivec2 closest_at = p;
#if MASTER_TAA
	uint id_centre = texelFetch(ids, p, 0).r;
#endif
	float model_diff = 0.0;
	for (int y = -1; y <= 1; y++)
		for (int x = -1; x <= 1; x++) {
			ivec2 q = clamp(p + ivec2(x, y), ivec2(0), last);
			float depth = texelFetch(surface, q, 0).y;
			if (depth < closest) {
				closest = depth;
				closest_at = q;
			}
			dsum += depth;
			dmin = min(dmin, depth);
			dmax = max(dmax, depth);
#if MASTER_TAA
			if (texelFetch(ids, q, 0).r != id_centre)
				model_diff += 1.0;
#endif
			vec3 c = texelFetch(current, q, 0).rgb;
			if (!finite3(c))
				continue;
			c = rgb_to_ycocg(c);
			mn3 = min(mn3, c);
			mx3 = max(mx3, c);
			sum3 += c;
			n3 += 1.0;
			if (x == 0 || y == 0) {
				mnx = min(mnx, c);
				mxx = max(mxx, c);
				sumx += c;
				nx += 1.0;
			}
		}
	vec3 centre = texelFetch(current, p, 0).rgb;
	bool centre_ok = finite3(centre);
	if (n3 == 0.0) { // every sample poisoned: write finite black rather than keep any of it
		out_history = vec4(0.0, 0.0, 0.0, texelFetch(surface, p, 0).y);
		return;
	}
	vec3 cur = centre_ok ? rgb_to_ycocg(centre) : sum3 / n3;
	if (nx == 0.0) {
		mnx = mn3;
		mxx = mx3;
		sumx = sum3;
		nx = n3;
	}
	vec3 box_min = 0.5 * (mn3 + mnx), box_max = 0.5 * (mx3 + mxx);

	vec2 uv;
	vec2 v = texelFetch(velocity, closest_at, 0).xy;
	bool valid = push.history_valid != 0 && history_position(gl_FragCoord.xy, v, size, uv);
	vec4 hist = valid ? texture(history, uv) : vec4(0.0);
	valid = valid && finite3(hist.rgb);

#if MASTER_TAA
	{
		float model_average = model_diff / 9.0;
		float davg = dsum / 9.0, depth = texelFetch(surface, p, 0).y;
		float aliased = master_aliased_value(sobel, p, last, model_average, depth, hist.a, valid, dmin, dmax, davg);
		vec3 color_min = mix(mnx, mn3, aliased), color_max = mix(mxx, mx3, aliased);
		box_min = mix(cur, color_min, aliased);
		box_max = mix(cur, color_max, aliased);
	}
#endif

	vec3 result = cur;
	if (valid) {
		// toward the box centre, as INSIDE does: clipping toward the current colour instead pulled thin
		// sub-pixel detail out of history (measured on thin-wires: 2.6 dB lower after 16 frames)
		vec3 h = clip_toward(rgb_to_ycocg(hist.rgb), 0.5 * (box_min + box_max), box_min, box_max);
		// a running average until the history holds enough frames: without the ramp the first frame
		// would keep a weight of feedback^n for many frames (0.97^15 = 0.63)
		float n = push.history_frames;
		float k = min(feedback(cur.x, h.x, push.feedback_min, push.feedback_max), n / (n + 1.0));
		result = mix(cur, h, k);
	}
	vec3 rgb = max(ycocg_to_rgb(result), vec3(0.0));
	vec3 shown = finite3(rgb) ? rgb : vec3(0.0);
	out_history = vec4(shown, texelFetch(surface, p, 0).y);
	out_display = vec4(shown, 1.0);
}
