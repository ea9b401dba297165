// The compute TAA resolves of taa and taa-sobel (docs/methods.md): preset=production (PRODUCTION 1, the
// default: a TAA as engines ship it) and preset=accumulate (PRODUCTION 0: the best case an accumulating
// TAA reaches). What both change from seed 001's resolve (taa_resolve.glsl), each for a measured failure:
// - the current frame is reconstructed at the pixel centre from the jittered 3x3 samples with a Gaussian
//   fit of Blackman-Harris (Karis 2014, UE4; weights from the jitter, taa_impl.c), so it is not shifted
//   by the jitter;
// - the clip box and the clip work on tonemapped colour c / (1 + luma) (Karis's HDR weighting) in YCoCg,
//   inverted afterwards, so a bright sample cannot widen the box to hold any stale history; the blend
//   stays linear, as the reference averages: blended in tonemapped space, a few percent of floor gave a
//   bright ball's pixels the floor's colour (inverting the tonemap multiplies them by 1 + luma);
// - history read under motion with a Catmull-Rom filter (Falcor, HDRP) or bilinearly; clip box from
//   min/max (AABB, seed 001) or Salvi's variance;
// - production: history is clipped every frame and blended with the current colour by an exponential
//   moving average whose current-frame weight is 1/n over the first frames after a reset, n counting
//   them, and current_weight from then on (default HDRP's 0.125; UE4's r.TemporalAACurrentFrameWeight
//   0.04; Falcor's alpha 0.1); it rises toward 1 as the speed nears 40 px/frame (UE4's TemporalAA.usf
//   rises to 0.2), so a fast object keeps more of itself; before that, anti-flicker (Karis 2014, Falcor):
//   the weight is scaled by d / (d + range), d the luma distance of history to the nearer side of the
//   clip box and range the box's luma extent.
//   No special path for still pixels. The rest applies to accumulate only:
// - a pixel that has been still for a whole jitter cycle is settled: its history is the mean of its own
//   jittered samples (each an unbiased sample of the box filter the reference uses) in linear light,
//   taken over whole cycles, so a still image converges instead of following the jitter; a cycle's mean
//   is folded in with weight cycle/(count + cycle), the count growing to max_samples. A settled pixel is
//   not clipped: the 3x3 neighbourhood cannot tell a sub-pixel wire that this frame's samples miss from
//   stale history. It starts over when its own sample differs from the one at the same jitter position a
//   cycle earlier: on a still pixel of a deterministic renderer only a change of the scene does that.
// Included by taa_production.comp, taa_master_production.comp (PRODUCTION 1), taa_converge.comp and
// taa_master_converge.comp (PRODUCTION 0); the master ones (MASTER_TAA 1) use taa-sobel's box.
#ifndef PRODUCTION
#define PRODUCTION 0
#endif
#include "taa_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2D current;  // jittered scene colour (nearest)
layout(set = 0, binding = 1) uniform sampler2D history;  // previous output: linear rgb, a = sample count
layout(set = 0, binding = 2) uniform sampler2D run;      // still pixels: mean of this cycle's own samples,
                                                         // a = frames still (the run's length)
layout(set = 0, binding = 3) uniform sampler2D velocity; // pixels, current - previous (nearest)
layout(set = 0, binding = 4) uniform sampler2D surface;  // unlit luma, linear depth (nearest)
layout(set = 0, binding = 5, rgba32f) uniform writeonly image2D history_out;
layout(set = 0, binding = 6, rgba32f) uniform writeonly image2D run_out;
// still pixels: the tonemapped luma of the own sample at each jitter position, 8 bits each, updated in
// place (each invocation touches its own texel only)
layout(set = 0, binding = 7, rgba32ui) uniform uimage2D positions;
#if MASTER_TAA
layout(set = 0, binding = 8) uniform usampler2D ids;     // model IDs
layout(set = 0, binding = 9) uniform sampler2D sobel;    // this frame's stabilised Sobel image
layout(set = 0, binding = 10) uniform sampler2D past_depth; // linear depth of the previous frame
layout(set = 0, binding = 11, r32f) uniform writeonly image2D depth_out;
#define DISPLAY_BINDING 12
#else
#define DISPLAY_BINDING 8
#endif
// the displayed output (what the sharpen pass overwrites when sharpen is on): history's colour, written
// here so that no copy pass follows the resolve, as engines write it
layout(set = 0, binding = DISPLAY_BINDING, rgba16f) uniform writeonly image2D display_out;

layout(push_constant) uniform Push {
	vec2 jitter;          // this frame's jitter in pixels: the geometry moved by +jitter
	ivec2 size;
	float feedback_min, feedback_max; // history weight bounds (seed 001's feedback law)
	float gamma;          // variance clip: the box is mean +- gamma * sigma (Salvi)
	float max_samples;    // cap on the sample count of settled pixels
	int cycle;            // jitter positions per cycle (8 or 16)
	int jitter_index;     // this frame's position in the cycle
	int history_valid;    // 0 on the first frame after a reset
	int clip_variance;    // 0: AABB (3x3 and cross min/max averaged, as seed 001), 1: variance
	int catmull_rom;      // history read under motion: 0 bilinear, 1 Catmull-Rom
	int clip_linear;      // clip in linear YCoCg instead of tonemapped YCoCg
	int tonemapped_resolve; // Karis' 1/(1 + luma) weight on every colour summed or blended
	float filter_weights[9]; // reconstruction filter weight of each 3x3 sample this frame, row by row
	float current_weight; // production: the current frame's weight once history holds 1/current_weight frames
} pc;

// A settled pixel's own sample differing from the one at the same position a cycle ago by more than
// this many 8-bit steps of tonemapped luma is a change of the scene (rounding gives 1).
const uint CHANGE_STEPS = 4u;
// A cycle mean further than this (tonemapped YCoCg) from history replaces it instead of being folded in.
const float CHANGE = 0.02;
// Below this many pixels of motion a pixel counts as still (rounding of equal matrices gives ~0).
const float STILL_PIXELS = 0.01;
// production: the current frame's weight rises toward MOTION_WEIGHT as the speed nears MOTION_PIXELS per
// frame. UE4's TemporalAA.usf rises to 0.2 at 40 px; here to 1 (0.5 at 20 px/frame): with 0.2 a small
// bright ball crossing at 15-20 px/frame kept under half its pixels (docs/methods.md).
const float MOTION_WEIGHT = 1.0;
const float MOTION_PIXELS = 40.0;
// production: from this speed (pixels per frame) on, the 3x3 reconstruction is linear, below it blends
// toward Karis' weights
const float LINEAR_FILTER_PIXELS = 8.0;
// production: the anti-flicker weight's floor (history of a thousand frames at most)
const float MIN_WEIGHT = 1e-3;

float luma709(vec3 c)
{
	return dot(c, vec3(0.2126, 0.7152, 0.0722));
}

// Karis's tonemap c / (1 + luma) and its inverse: the luma of the result stays below 1, so the inverse
// exists; the floor bounds it at the half-float range the scene colour has.
vec3 tonemap(vec3 c)
{
	return c / (1.0 + luma709(c));
}

vec3 tonemap_inverse(vec3 t)
{
	t = max(t, vec3(0.0));
	return t / max(1.0 - luma709(t), 1.0 / 65504.0);
}

// tonemapped_resolve: Karis' 1/(1 + luma) weight on every colour summed or blended
#define RESOLVE_KARIS (pc.tonemapped_resolve != 0)
#define RESOLVE_LUMA luma709
#include "resolve_weight.glsl"

// The working space of the clip box: tonemapped YCoCg, or linear YCoCg with clip_space=linear.
vec3 to_working(vec3 linear)
{
	return rgb_to_ycocg(pc.clip_linear != 0 ? linear : tonemap(linear));
}

vec3 from_working(vec3 w)
{
	vec3 rgb = ycocg_to_rgb(w);
	return pc.clip_linear != 0 ? clamp(rgb, vec3(0.0), vec3(65504.0)) : min(tonemap_inverse(rgb), vec3(65504.0));
}

// History at pixel position pos (texel units) with the Catmull-Rom filter: the 4x4 texel weights are
// separable, and each axis's two middle weights share one bilinear fetch, so 3x3 bilinear fetches give
// the 16-texel filter exactly. Its negative lobes overshoot at edges, by a tenth of an HDR contrast of
// hundreds: the result is clamped to the range of the four texels around pos (HDRP's anti-ringing).
vec3 history_catmull_rom(vec2 pos)
{
	vec2 size = vec2(pc.size);
	vec2 base = floor(pos - 0.5) + 0.5; // the texel centre at or before pos on each axis
	vec2 f = pos - base;
	vec2 w0 = f * (-0.5 + f * (1.0 - 0.5 * f));
	vec2 w1 = 1.0 + f * f * (-2.5 + 1.5 * f);
	vec2 w2 = f * (0.5 + f * (2.0 - 1.5 * f));
	vec2 w3 = f * f * (-0.5 + 0.5 * f);
	vec2 w12 = w1 + w2;
	vec2 at[3] = vec2[](base - 1.0, base + w2 / w12, base + 2.0);
	vec2 w[3] = vec2[](w0, w12, w3);
	vec3 sum = vec3(0.0);
	float weight = 0.0;
	for (int j = 0; j < 3; j++)
		for (int i = 0; i < 3; i++) {
			float wij = w[i].x * w[j].y;
			sum += wij * textureLod(history, vec2(at[i].x, at[j].y) / size, 0.0).rgb;
			weight += wij;
		}
	ivec2 corner = ivec2(floor(base)), last = pc.size - 1;
	vec3 lo = vec3(1e30), hi = vec3(-1e30);
	for (int j = 0; j < 2; j++)
		for (int i = 0; i < 2; i++) {
			vec3 t = texelFetch(history, clamp(corner + ivec2(i, j), ivec2(0), last), 0).rgb;
			lo = min(lo, t);
			hi = max(hi, t);
		}
	return clamp(sum / weight, lo, hi);
}

// History colour weight under motion: seed 001's luminance feedback, as a cap on the sample count
// (history weight k means the new frame counts at least 1 - k).
float motion_sample_cap(float y_current, float y_history)
{
	float k = feedback(y_current, y_history, pc.feedback_min, pc.feedback_max);
	return 1.0 / max(1.0 - k, 1e-3);
}


// The 3x3 neighbourhood in the working space.
struct Neighbourhood {
	vec3 filtered;               // reconstruction at the pixel centre, linear (Karis-weighted or not)
	vec3 filtered_linear;        // the same without Karis' weights
	vec3 filtered_working;       // the same in the working space
	vec3 box_min, box_max;       // the clip box (3x3 and cross combined, or variance)
	vec3 min3, max3, minx, maxx; // taa-sobel mixes the 3x3 and cross boxes itself
	ivec2 closest_at;            // the pixel of the closest depth (its velocity is used)
	float dsum, dmin, dmax, model_diff;
	bool any_finite;
};

Neighbourhood gather(ivec2 p)
{
	ivec2 last = pc.size - 1;
	Neighbourhood nb;
	vec3 mn3 = vec3(1e30), mx3 = vec3(-1e30), mnx = vec3(1e30), mxx = vec3(-1e30);
	vec3 sum3 = vec3(0.0), sq3 = vec3(0.0), sumx = vec3(0.0), sqx = vec3(0.0), filtered = vec3(0.0);
	vec3 filtered_linear = vec3(0.0);
	float n3 = 0.0, nx = 0.0, filter_weight = 0.0, linear_weight = 0.0, closest = 1e30;
	nb.closest_at = p;
	nb.dsum = 0.0;
	nb.dmin = 1e30;
	nb.dmax = -1e30;
	nb.model_diff = 0.0;
#if MASTER_TAA
	uint id_centre = texelFetch(ids, p, 0).r;
#endif
	for (int y = -1; y <= 1; y++)
		for (int x = -1; x <= 1; x++) {
			ivec2 q = clamp(p + ivec2(x, y), ivec2(0), last);
			float depth = texelFetch(surface, q, 0).y;
			if (depth < closest) {
				closest = depth;
				nb.closest_at = q;
			}
			nb.dsum += depth;
			nb.dmin = min(nb.dmin, depth);
			nb.dmax = max(nb.dmax, depth);
#if MASTER_TAA
			if (texelFetch(ids, q, 0).r != id_centre)
				nb.model_diff += 1.0;
#endif
			vec3 c = texelFetch(current, q, 0).rgb;
			if (!finite3(c)) // non-finite samples are left out: they must not reach history
				continue;
			c = clamp(c, vec3(0.0), vec3(65504.0));
			float w = pc.filter_weights[(y + 1) * 3 + (x + 1)] * resolve_weight(c);
			filtered += w * c;
			filtered_linear += pc.filter_weights[(y + 1) * 3 + (x + 1)] * c;
			linear_weight += pc.filter_weights[(y + 1) * 3 + (x + 1)];
			c = to_working(c);
			filter_weight += w;
			mn3 = min(mn3, c);
			mx3 = max(mx3, c);
			sum3 += c;
			sq3 += c * c;
			n3 += 1.0;
			if (x == 0 || y == 0) {
				mnx = min(mnx, c);
				mxx = max(mxx, c);
				sumx += c;
				sqx += c * c;
				nx += 1.0;
			}
		}
	nb.any_finite = n3 > 0.0;
	if (!nb.any_finite)
		return nb;
	if (nx == 0.0) {
		mnx = mn3;
		mxx = mx3;
		sumx = sum3;
		sqx = sq3;
		nx = n3;
	}
	nb.filtered = filtered / filter_weight;
	nb.filtered_linear = filtered_linear / linear_weight;
	nb.filtered_working = to_working(nb.filtered);
	if (pc.clip_variance != 0) { // Salvi: mean +- gamma sigma
		vec3 mean3 = sum3 / n3, sigma3 = sqrt(max(sq3 / n3 - mean3 * mean3, vec3(0.0)));
		vec3 meanx = sumx / nx, sigmax = sqrt(max(sqx / nx - meanx * meanx, vec3(0.0)));
		nb.min3 = mean3 - pc.gamma * sigma3;
		nb.max3 = mean3 + pc.gamma * sigma3;
		nb.minx = meanx - pc.gamma * sigmax;
		nb.maxx = meanx + pc.gamma * sigmax;
		nb.box_min = nb.min3;
		nb.box_max = nb.max3;
	} else { // seed 001 / INSIDE: 3x3 and cross min/max, averaged
		nb.min3 = mn3;
		nb.max3 = mx3;
		nb.minx = mnx;
		nb.maxx = mxx;
		nb.box_min = 0.5 * (mn3 + mnx);
		nb.box_max = 0.5 * (mx3 + mxx);
	}
	return nb;
}

#if MASTER_TAA
// seed 001's Master TAA: the box chosen between cross and 3x3 and shrunk toward the current colour by
// aliasedValue (model IDs, depth pseudo-variances, the stabilised Sobel image)
void master_box(inout Neighbourhood nb, ivec2 p, float depth, float past_depth, bool valid)
{
	ivec2 last = pc.size - 1;
	float model_average = nb.model_diff / 9.0;
	float davg = nb.dsum / 9.0;
	float aliased = master_aliased_value(sobel, p, last, model_average, depth, past_depth, valid, nb.dmin, nb.dmax,
					      davg);
	nb.box_min = mix(nb.filtered_working, mix(nb.minx, nb.min3, aliased), aliased);
	nb.box_max = mix(nb.filtered_working, mix(nb.maxx, nb.max3, aliased), aliased);
}
#endif

bool finite4(vec4 v)
{
	return !any(isnan(v)) && !any(isinf(v));
}

// The 8-bit tonemapped luma of the own sample at jitter position i (word i / 4, byte i % 4), and its
// update. The word is selected by comparisons: a dynamically indexed vector goes through memory.
uint position_word(uvec4 t, int i)
{
	return i < 8 ? (i < 4 ? t.x : t.y) : (i < 12 ? t.z : t.w);
}

uint position_luma(uvec4 t, int i)
{
	return (position_word(t, i) >> (8 * (i & 3))) & 0xffu;
}

uvec4 with_position_luma(uvec4 t, int i, uint value)
{
	uint shift = 8u * uint(i & 3);
	uint word = (position_word(t, i) & ~(0xffu << shift)) | (value << shift);
	return i < 8 ? (i < 4 ? uvec4(word, t.yzw) : uvec4(t.x, word, t.zw))
		     : (i < 12 ? uvec4(t.xy, word, t.w) : uvec4(t.xyz, word));
}

// The resolve's result: history (colour, and n, the frames it holds) and the displayed image, both
// finite and within half-float range
void store_result(ivec2 p, vec3 h, float n)
{
	h = finite3(h) ? clamp(h, vec3(0.0), vec3(65504.0)) : vec3(0.0);
	imageStore(history_out, p, vec4(h, n));
	imageStore(display_out, p, vec4(h, 1.0));
}

void main()
{
	ivec2 p = ivec2(gl_GlobalInvocationID.xy);
	if (any(greaterThanEqual(p, pc.size)))
		return;
	ivec2 last = pc.size - 1;
	vec2 size = vec2(pc.size);
	vec2 centre = vec2(p) + 0.5;
	float depth = texelFetch(surface, p, 0).y;
#if MASTER_TAA
	imageStore(depth_out, p, vec4(depth));
#endif

	Neighbourhood nb = gather(p);
	if (!nb.any_finite) { // every sample poisoned: write finite black rather than keep any of it
		store_result(p, vec3(0.0), 1.0);
#if !PRODUCTION // production's cycle images are 1x1 and unused
		imageStore(run_out, p, vec4(0.0));
#endif
		return;
	}
	vec3 own = texelFetch(current, p, 0).rgb;
	own = finite3(own) ? clamp(own, vec3(0.0), vec3(65504.0)) : nb.filtered;
	uint own_luma = uint(luma709(tonemap(own)) * 255.0 + 0.5);

	vec2 v = texelFetch(velocity, nb.closest_at, 0).xy;
	vec2 uv;
	bool valid = pc.history_valid != 0 && history_position(centre, v, size, uv);
	bool still = all(lessThan(abs(v), vec2(STILL_PIXELS))); // NaN velocity: not still, not valid
	ivec2 from = clamp(ivec2(floor(centre - v)), ivec2(0), last);
	vec4 past = valid ? texelFetch(history, from, 0) : vec4(0.0);
#if PRODUCTION
	vec4 past_run = vec4(0.0);
#else
	vec4 past_run = valid ? texelFetch(run, from, 0) : vec4(0.0);
#endif
	vec3 h = past.rgb;
	if (valid && !still)
		h = pc.catmull_rom != 0 ? history_catmull_rom(centre - v) : textureLod(history, uv, 0.0).rgb;
	valid = valid && finite3(h) && finite4(past) && past.a >= 1.0 && finite4(past_run);
	h = clamp(h, vec3(0.0), vec3(65504.0));
#if PRODUCTION
	// Karis' weights in the 3x3 filter keep a jittered hit on an HDR speck from spreading over its
	// neighbours, but they also let a few dark neighbours outweigh a small bright object's own sample:
	// a bright ball moving fast, which history cannot hold either, faded to the floor. From
	// LINEAR_FILTER_PIXELS of motion on, the filter is linear.
	nb.filtered = mix(nb.filtered, nb.filtered_linear, clamp(length(v) / LINEAR_FILTER_PIXELS, 0.0, 1.0));
	nb.filtered_working = to_working(nb.filtered);
#endif
#if MASTER_TAA
	master_box(nb, p, depth, valid ? texelFetch(past_depth, from, 0).r : depth, valid);
#endif
	vec3 box_centre = 0.5 * (nb.box_min + nb.box_max);

#if PRODUCTION
	float n = past.a;
	if (!valid) {
		h = nb.filtered;
		n = 1.0;
	} else {
		vec3 hw = to_working(h);
		float weight = pc.current_weight;
		// anti-flicker (Karis 2014, as Falcor): a history near the edge of the box gets less of the
		// current frame, so a sample that only just widens the box does not pull history across it and back
		float d = min(abs(nb.box_min.x - hw.x), abs(nb.box_max.x - hw.x));
		float range = nb.box_max.x - nb.box_min.x;
		weight = clamp(weight * d / max(d + range, 1e-7), MIN_WEIGHT, 1.0);
		weight = mix(weight, max(weight, MOTION_WEIGHT), clamp(length(v) / MOTION_PIXELS, 0.0, 1.0));
		vec3 w = clip_toward(hw, box_centre, nb.box_min, nb.box_max);
		n = min(n + 1.0, 1.0 / weight);
		h = resolve_mix(from_working(w), nb.filtered, 1.0 / n);
	}
	store_result(p, h, n);
#else
	// A still pixel's run: how many frames it has been still, the mean of its own samples since the
	// last whole cycle, and the lumas of its own samples by jitter position (valid once a whole cycle
	// is in them).
	float run_length = valid && still ? past_run.a : 0.0;
	vec3 cycle_mean = run_length > 0.0 ? past_run.rgb : vec3(0.0);
	float cycle = float(pc.cycle);
	uvec4 lumas = still ? imageLoad(positions, p) : uvec4(0u);
	if (run_length >= cycle) {
		uint before = position_luma(lumas, pc.jitter_index);
		if (max(own_luma, before) - min(own_luma, before) > CHANGE_STEPS)
			run_length = 0.0; // the scene changed here: start over, history as one clipped sample
	}
	bool settled = run_length >= cycle;

	float n = past.a;
	if (!valid) {
		h = nb.filtered;
		n = 1.0;
	} else if (!settled) {
		// moving, or still for less than a whole cycle: seed 001's clip and feedback on the filtered
		// current colour; history that had to start over counts as one sample
		vec3 w = clip_toward(to_working(h), box_centre, nb.box_min, nb.box_max);
		if (still && run_length == 0.0 && past_run.a >= cycle)
			n = 1.0;
		n = min(n + 1.0, motion_sample_cap(nb.filtered_working.x, w.x));
		h = resolve_mix(from_working(w), nb.filtered, 1.0 / n);
	}
	if (still) {
		run_length += 1.0;
		float in_cycle = mod(run_length - 1.0, cycle) + 1.0; // this sample's place in its cycle, 1..cycle
		cycle_mean = in_cycle == 1.0 ? own : resolve_mix(cycle_mean, own, 1.0 / in_cycle);
		lumas = with_position_luma(lumas, pc.jitter_index, own_luma);
		if (in_cycle == cycle) {
			// A whole cycle: its mean replaces history when the pixel settles or the mean moved away from
			// history (a change the per-position test missed), and is folded into it otherwise.
			bool replace = run_length == cycle || distance(to_working(cycle_mean), to_working(h)) > CHANGE;
			h = replace ? cycle_mean : resolve_mix(h, cycle_mean, cycle / (n + cycle));
			n = replace ? min(cycle, pc.max_samples) : min(n + cycle, pc.max_samples);
		}
		imageStore(positions, p, lumas);
	}
	// run lengths past two cycles carry no more information
	run_length = run_length >= 2.0 * cycle ? run_length - cycle : run_length;
	store_result(p, h, n);
	imageStore(run_out, p, vec4(cycle_mean, run_length));
#endif
}
