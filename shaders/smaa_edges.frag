#version 450
// SMAA pass 1, edge detection (notes/smaa.md §2). Writes (left edge, top edge) as 0 or 1 into an RG8
// target cleared to 0, and the blend mask: the triangle's depth 0 over a mask cleared to 1, where the
// blend pass may read a non-zero weight. It discards the other pixels (no edge, and the blend surely reads
// no weight there: its output is the scene colour, and it need not run there). Luma and colour modes read the sRGB-encoded
// colour with its luma in alpha (shaders/smaa_encode.frag); depth mode reads the scene depth. Reads
// outside the image clamp to the border pixel. A fragment pass, not a compute one: per-pixel compute
// passes cost several times more on lavapipe.
layout(constant_id = 0) const int EDGE_MODE = 0; // 0 luma, 1 colour, 2 depth

layout(set = 0, binding = 0) uniform sampler2D source; // RGBA8 sRGB colour + luma, or D32F depth
layout(push_constant) uniform Push {
	float threshold;        // luma / colour: SMAA_THRESHOLD; depth: SMAA_DEPTH_THRESHOLD
	float contrast_factor;  // local contrast adaptation: SMAA_LOCAL_CONTRAST_ADAPTATION_FACTOR (2.0)
} push;
layout(location = 0) out vec4 out_edges;

ivec2 last_texel;

vec4 fetch(ivec2 p)
{
	return texelFetch(source, clamp(p, ivec2(0), last_texel), 0);
}

vec3 gamma_colour(ivec2 p)
{
	return fetch(p).rgb;
}

float luma(ivec2 p)
{
	return fetch(p).a; // Rec. 709 weights on the encoded values
}

// Luma (alpha) of the 2x2 texels around pixel corner c: x (c.x-1, c.y), y (c.x, c.y), z (c.x, c.y-1),
// w (c.x-1, c.y-1). The clamp-to-edge sampler clamps them as fetch() does; one gather costs about one
// texel read on lavapipe.
vec4 gather_luma(ivec2 c)
{
	return textureGather(source, vec2(c) / vec2(last_texel + 1), 3);
}

float colour_delta(vec3 a, vec3 b)
{
	vec3 t = abs(a - b);
	return max(max(t.r, t.g), t.b);
}

// The blend at p reads the weights of p's own edges and those of the left edge of p's right neighbour and
// the top edge of p's bottom neighbour (smaa_blend.frag); the weight pass writes weights only across an
// edge the edge pass found. Those two neighbour edges are the deltas to the right and bottom measured
// here (the same values: |a - b| = |b - a|), before the contrast adaptation that can only drop them, so
// blend_may_run is false only where every weight the blend reads is 0.
bool blend_may_run;

vec2 detect(ivec2 p)
{
	vec2 edges;
	if (EDGE_MODE == 2) {
		float d = fetch(p).r;
		vec2 delta = abs(d - vec2(fetch(p + ivec2(-1, 0)).r, fetch(p + ivec2(0, -1)).r));
		vec2 delta_rb = abs(d - vec2(fetch(p + ivec2(1, 0)).r, fetch(p + ivec2(0, 1)).r));
		edges = step(vec2(push.threshold), delta); // no contrast adaptation on depth
		blend_may_run = edges.x + edges.y > 0.0 || any(greaterThanEqual(delta_rb, vec2(push.threshold)));
		return edges;
	}
	// Left and top deltas decide whether there is an edge at all; most pixels stop here.
	vec2 delta_lt, delta_rb, delta_far;
	if (EDGE_MODE == 0) {
		vec4 left_centre_top = gather_luma(p);          // x left, y centre, z top
		vec4 bottom_right = gather_luma(p + ivec2(1));  // x bottom, z right
		float l = left_centre_top.y, l_left = left_centre_top.x, l_top = left_centre_top.z;
		delta_lt = abs(l - vec2(l_left, l_top));
		delta_rb = abs(l - bottom_right.zx);
		edges = step(vec2(push.threshold), delta_lt);
		blend_may_run = any(greaterThanEqual(delta_rb, vec2(push.threshold)));
		if (edges.x + edges.y == 0.0)
			return edges;
		// the second ring is measured against the neighbour, not the centre
		delta_far = abs(vec2(l_left, l_top) - vec2(luma(p + ivec2(-2, 0)), luma(p + ivec2(0, -2))));
	} else {
		vec3 c = gamma_colour(p);
		delta_lt = vec2(colour_delta(c, gamma_colour(p + ivec2(-1, 0))),
				colour_delta(c, gamma_colour(p + ivec2(0, -1))));
		delta_rb = vec2(colour_delta(c, gamma_colour(p + ivec2(1, 0))),
				colour_delta(c, gamma_colour(p + ivec2(0, 1))));
		edges = step(vec2(push.threshold), delta_lt);
		blend_may_run = any(greaterThanEqual(delta_rb, vec2(push.threshold)));
		if (edges.x + edges.y == 0.0)
			return edges;
		// in colour mode the second ring is measured against the centre
		delta_far = vec2(colour_delta(c, gamma_colour(p + ivec2(-2, 0))),
				 colour_delta(c, gamma_colour(p + ivec2(0, -2))));
	}
	// Local contrast adaptation: an edge next to a much stronger one (in any direction) is dropped, which
	// keeps a soft shading step beside a hard silhouette from forming its own line.
	vec2 max_delta = max(max(delta_lt, delta_rb), delta_far);
	float final_delta = max(max_delta.x, max_delta.y);
	return edges * step(vec2(final_delta), push.contrast_factor * delta_lt);
}

void main()
{
	ivec2 p = ivec2(gl_FragCoord.xy);
	last_texel = textureSize(source, 0) - 1;
	vec2 edges = detect(p);
	if (!blend_may_run && edges.x + edges.y == 0.0)
		discard;
	out_edges = vec4(edges, 0.0, 0.0);
}
