// Where a fragment of an MSAA-style pass is shaded and alpha-tested, the same on every path and device
// (docs/methods.md, "Shading point and alpha"). MSAA shades once per pixel and triangle; at the pixel centre
// when the triangle covers every sample, otherwise at a sample it covers (centroid interpolation: Vulkan
// lets the device choose; aalab fixes the choice to the first covered sample in the pattern's order, as
// lavapipe does), so that no partly covered pixel takes a value extrapolated from outside its triangle.
// Hardware samples know their coverage from gl_SampleMaskIn; virtual samples (one rasterisation per
// sample position, geometry jittered so that the position lands on the pixel centre) from the triangle's
// barycentric coordinates, which virtual_sample*.geom add. Needs common.glsl included first.

layout(constant_id = 3) const int SHADING_POINT_MODE = 0; // 0 the fragment itself, 1 hardware, 2 virtual
layout(constant_id = 4) const int PATTERN_SAMPLES = 1;    // N of the sample pattern (1, 2, 4 or 8)
layout(constant_id = 5) const bool ALPHA_TO_COVERAGE = false;
// the pattern: the Vulkan standard sample positions for N, in pixel units (engine/gpu/sample_positions.c)
layout(constant_id = 6) const float PATTERN_X0 = 0.5;
layout(constant_id = 7) const float PATTERN_Y0 = 0.5;
layout(constant_id = 8) const float PATTERN_X1 = 0.5;
layout(constant_id = 9) const float PATTERN_Y1 = 0.5;
layout(constant_id = 10) const float PATTERN_X2 = 0.5;
layout(constant_id = 11) const float PATTERN_Y2 = 0.5;
layout(constant_id = 12) const float PATTERN_X3 = 0.5;
layout(constant_id = 13) const float PATTERN_Y3 = 0.5;
layout(constant_id = 14) const float PATTERN_X4 = 0.5;
layout(constant_id = 15) const float PATTERN_Y4 = 0.5;
layout(constant_id = 16) const float PATTERN_X5 = 0.5;
layout(constant_id = 17) const float PATTERN_Y5 = 0.5;
layout(constant_id = 18) const float PATTERN_X6 = 0.5;
layout(constant_id = 19) const float PATTERN_Y6 = 0.5;
layout(constant_id = 20) const float PATTERN_X7 = 0.5;
layout(constant_id = 21) const float PATTERN_Y7 = 0.5;

#define SHADING_POINT_FRAGMENT 0
#define SHADING_POINT_HARDWARE 1
#define SHADING_POINT_VIRTUAL 2

vec2 pattern_position(int i)
{
	vec2 p[8] = vec2[8](vec2(PATTERN_X0, PATTERN_Y0), vec2(PATTERN_X1, PATTERN_Y1), vec2(PATTERN_X2, PATTERN_Y2),
			    vec2(PATTERN_X3, PATTERN_Y3), vec2(PATTERN_X4, PATTERN_Y4), vec2(PATTERN_X5, PATTERN_Y5),
			    vec2(PATTERN_X6, PATTERN_Y6), vec2(PATTERN_X7, PATTERN_Y7));
	return p[clamp(i, 0, 7)];
}

struct ShadingPoint {
	vec2 offset;    // pixels from where this fragment was interpolated to where it is shaded
	vec2 centre;    // pixels from there to the pixel's centre
	uint coverage;  // pattern samples this triangle covers in the pixel (bit i: sample i)
	int own_sample; // virtual: the sample this rasterisation stands for; -1 otherwise
};

// The sample a virtual rasterisation stands for: its geometry was moved by `jitter` (pixels), so the pixel
// centre shows the pattern point nearest (0.5, 0.5) - jitter. A temporal shift of the whole pattern (t2msaa)
// moves that point off the pattern, but never closer to another of its samples (engine/renderer.c checks).
int virtual_sample_index(vec2 jitter)
{
	vec2 here = vec2(0.5) - jitter;
	int best = 0;
	for (int i = 1; i < PATTERN_SAMPLES; i++)
		if (distance(pattern_position(i), here) < distance(pattern_position(best), here))
			best = i;
	return best;
}

// barycentric: this fragment's barycentric coordinates in its triangle (virtual only), interpolated with
// perspective like any attribute (so that clipping keeps them right).
ShadingPoint shading_point(vec3 barycentric)
{
	ShadingPoint sp = ShadingPoint(vec2(0.0), vec2(0.0), 1u, -1);
	uint all_samples = (1u << PATTERN_SAMPLES) - 1u;
	vec2 centre = vec2(0.0); // offset from this fragment to the pixel's centre
	vec2 here = vec2(0.5);   // where this fragment sits in its pixel
	if (SHADING_POINT_MODE == SHADING_POINT_HARDWARE) {
		sp.coverage = uint(gl_SampleMaskIn[0]) & all_samples;
	} else if (SHADING_POINT_MODE == SHADING_POINT_VIRTUAL) {
		centre = draw.jitter_ndc * frame.frame_size.xy * 0.5;
		sp.own_sample = virtual_sample_index(centre);
		here = pattern_position(sp.own_sample);
		// barycentric / w is affine on screen (the triangle's edge functions, up to scale), and 1/w > 0 in
		// front of the eye, so its sign at another sample says whether the triangle covers it
		vec3 edge = barycentric * gl_FragCoord.w, ex = dFdxFine(edge), ey = dFdyFine(edge);
		sp.coverage = 1u << sp.own_sample; // this rasterisation exists: its own sample is covered
		for (int i = 0; i < PATTERN_SAMPLES; i++) {
			vec2 d = pattern_position(i) - here;
			if (all(greaterThanEqual(edge + ex * d.x + ey * d.y, vec3(0.0))))
				sp.coverage |= 1u << i;
		}
	}
	sp.centre = centre;
	if (SHADING_POINT_MODE == SHADING_POINT_FRAGMENT || sp.coverage == all_samples || sp.coverage == 0u)
		sp.offset = centre;
	else
		sp.offset = pattern_position(findLSB(sp.coverage)) - here;
	return sp;
}

// An attribute at `offset` pixels from this fragment, perspective-correct: a/w and 1/w are affine on
// screen, so their screen derivatives carry them exactly (first-order extrapolation of `a` itself drifts at
// grazing angles, where hardware and virtual samples then disagreed).
#define AT_SHADING_POINT(T) T at_shading_point(T v, vec2 offset) \
	{ \
		float q = gl_FragCoord.w; \
		T vq = v * q; \
		float q_at = q + dFdxFine(q) * offset.x + dFdyFine(q) * offset.y; \
		return (vq + dFdxFine(vq) * offset.x + dFdyFine(vq) * offset.y) / max(q_at, 1e-12); \
	}
AT_SHADING_POINT(vec2)
AT_SHADING_POINT(vec3)
AT_SHADING_POINT(vec4)

// The screen gradients of uv at `offset` pixels from this fragment, exact by the quotient rule on uv/w and
// 1/w. MSAA paths take them at the pixel centre: the texture LOD is then the same whichever sample a
// virtual rasterisation stands for (finite differences taken there differ with the sample's position).
void uv_gradients_at(vec2 uv, vec2 offset, out vec2 uv_dx, out vec2 uv_dy)
{
	float q = gl_FragCoord.w, q_x = dFdxFine(q), q_y = dFdyFine(q);
	vec2 uq = uv * q, uq_x = dFdxFine(uq), uq_y = dFdyFine(uq);
	float q_at = max(q + q_x * offset.x + q_y * offset.y, 1e-12);
	vec2 uq_at = uq + uq_x * offset.x + uq_y * offset.y;
	uv_dx = (uq_x * q_at - uq_at * q_x) / (q_at * q_at);
	uv_dy = (uq_y * q_at - uq_at * q_y) / (q_at * q_at);
}

// Alpha to coverage keeps the glTF cut (docs/methods.md, "Alpha to coverage"): a sample survives iff the
// surface's alpha at that sample reaches the cutoff, while colour is still shaded once. A hardware
// fragment is interpolated at the pixel centre, so sample i lies this many pixels from it; a virtual
// rasterisation (and a one-sample fragment) already lies on its own sample.
vec2 hardware_sample_offset(int i)
{
	return pattern_position(i) - vec2(0.5);
}
