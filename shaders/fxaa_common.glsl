// FXAA 3.11, quality path, written out for this project. Shared by the pixel shader variant (fxaa.frag)
// and the compute variant (fxaa_cs_*.comp): both run these functions on the same inputs, so their pixels
// agree. The input ("luma texture") holds sRGB-encoded colour with luma in alpha, as FXAA expects, in an
// RGBA8 UNORM image read through a bilinear clamp-to-edge sampler.
//
// Coordinates are in pixels (pixel centres at +0.5) and are turned into texture coordinates only at a
// fetch; FXAA's reference works in texture coordinates, which changes only rounding.

// The quality preset's end-of-edge search, as specialization constants set by engine/methods/fxaa.c:
// FXAA_STEP_COUNT steps (FXAA_QUALITY__PS), of sizes FXAA_STEP_0.. in pixels (FXAA_QUALITY__P0..).
layout(constant_id = 0) const int FXAA_STEP_COUNT = 5;
layout(constant_id = 1) const float FXAA_STEP_0 = 1.0;
layout(constant_id = 2) const float FXAA_STEP_1 = 1.5;
layout(constant_id = 3) const float FXAA_STEP_2 = 2.0;
layout(constant_id = 4) const float FXAA_STEP_3 = 4.0;
layout(constant_id = 5) const float FXAA_STEP_4 = 12.0;
layout(constant_id = 6) const float FXAA_STEP_5 = 0.0;
layout(constant_id = 7) const float FXAA_STEP_6 = 0.0;
layout(constant_id = 8) const float FXAA_STEP_7 = 0.0;
layout(constant_id = 9) const float FXAA_STEP_8 = 0.0;
layout(constant_id = 10) const float FXAA_STEP_9 = 0.0;
layout(constant_id = 11) const float FXAA_STEP_10 = 0.0;
layout(constant_id = 12) const float FXAA_STEP_11 = 0.0;

// Push constants of the passes that run FXAA (struct aa_fxaa_push in engine/methods/fxaa.h).
#define FXAA_PUSH_BLOCK \
	layout(push_constant) uniform FxaaPush { \
		float subpix; \
		float edge_threshold; \
		float edge_threshold_min; \
		float unused; \
	} push

float fxaa_step(int i)
{
	switch (i) {
	case 0: return FXAA_STEP_0;
	case 1: return FXAA_STEP_1;
	case 2: return FXAA_STEP_2;
	case 3: return FXAA_STEP_3;
	case 4: return FXAA_STEP_4;
	case 5: return FXAA_STEP_5;
	case 6: return FXAA_STEP_6;
	case 7: return FXAA_STEP_7;
	case 8: return FXAA_STEP_8;
	case 9: return FXAA_STEP_9;
	case 10: return FXAA_STEP_10;
	default: return FXAA_STEP_11;
	}
}

// ---------------------------------------------------------------- colour encoding (the luma passes)

float fxaa_linear_to_srgb(float v)
{
	// NaN and negatives go to 0 ("not >= 0" catches NaN); HDR values above 1 clip, as the display would.
	v = v >= 0.0 ? min(v, 1.0) : 0.0;
	return v <= 0.0031308 ? v * 12.92 : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}

vec3 fxaa_srgb_to_linear(vec3 c)
{
	vec3 lo = c / 12.92;
	vec3 hi = pow((c + 0.055) / 1.055, vec3(2.4));
	return mix(hi, lo, lessThanEqual(c, vec3(0.04045)));
}

// Linear scene colour -> the luma texture's texel: sRGB colour, luma (Rec. 601 weights on the encoded
// values, FXAA's recommendation) in alpha. Values are rounded to the 8-bit grid here, so that a colour
// attachment and a storage image store exactly the same bytes whatever rounding their conversion uses.
vec4 fxaa_encode(vec4 linear)
{
	vec3 c = vec3(fxaa_linear_to_srgb(linear.r), fxaa_linear_to_srgb(linear.g), fxaa_linear_to_srgb(linear.b));
	float luma = dot(c, vec3(0.299, 0.587, 0.114));
	return round(vec4(c, luma) * 255.0) / 255.0;
}

// ---------------------------------------------------------------- FXAA

// What the local contrast test and the edge direction found at one pixel.
struct FxaaPixel {
	float lumaM;
	float lumaN, lumaS;  // the two neighbours across the edge: north/south (horizontal edge) or west/east
	bool horizontal;     // the edge runs horizontally: blend vertically
	float subpix;        // the subpixel term before the `subpix` parameter scales it (subpixG)
};

// Luma around a pixel by textureGather at pixel corners: a gather at corner c (integer pixel
// coordinates) returns the alphas of texels (c.x-1, c.y), (c.x, c.y), (c.x, c.y-1), (c.x-1, c.y-1) in x, y,
// z, w; the clamp-to-edge sampler clamps them as texel reads clamped to the image would. One gather costs
// about a texel read on lavapipe, so four replace nine reads.
vec4 fxaa_gather_luma(sampler2D tex, ivec2 corner, vec2 rcp_size)
{
	return textureGather(tex, vec2(corner) * rcp_size, 3);
}

// FXAA's early exit: the local contrast of the pixel and its four neighbours (lumas M, N, S, W, E) is
// below the thresholds. A zero range is never an edge (also keeps 1/range finite when both thresholds
// are 0).
bool fxaa_contrast_is_edge(vec4 lumaNSWE, float lumaM, float edge_threshold, float edge_threshold_min,
			   out float range)
{
	float rangeMax = max(max(max(lumaNSWE.x, lumaNSWE.z), max(lumaNSWE.w, lumaNSWE.y)), lumaM);
	float rangeMin = min(min(min(lumaNSWE.x, lumaNSWE.z), min(lumaNSWE.w, lumaNSWE.y)), lumaM);
	range = rangeMax - rangeMin;
	return !(range < max(edge_threshold_min, rangeMax * edge_threshold) || range <= 0.0);
}

// The early exit alone (fxaa_classify's result, from two gathers instead of four): the edge pass of the
// pixel shader variant marks the pixels the resolve pass runs on.
bool fxaa_is_edge(sampler2D tex, ivec2 p, ivec2 size, float edge_threshold, float edge_threshold_min)
{
	vec2 rcp_size = 1.0 / vec2(size);
	vec4 wmn = fxaa_gather_luma(tex, p, rcp_size);     // x W, y M, z N, w NW
	vec4 sem = fxaa_gather_luma(tex, p + 1, rcp_size); // x S, y SE, z E, w M
	float range;
	return fxaa_contrast_is_edge(vec4(wmn.z, sem.x, wmn.x, sem.z), wmn.y, edge_threshold, edge_threshold_min,
				     range);
}

// Early exit (local contrast below the thresholds: not an edge) and, for edge pixels, the edge direction
// and the subpixel term. Returns false for pixels FXAA leaves alone.
bool fxaa_classify(sampler2D tex, ivec2 p, ivec2 size, float edge_threshold, float edge_threshold_min,
		   out FxaaPixel px)
{
	vec2 rcp_size = 1.0 / vec2(size);
	vec4 wmn = fxaa_gather_luma(tex, p, rcp_size);                  // x W, y M, z N, w NW
	vec4 sem = fxaa_gather_luma(tex, p + 1, rcp_size);              // x S, y SE, z E, w M
	vec4 mene = fxaa_gather_luma(tex, ivec2(p.x + 1, p.y), rcp_size); // x M, y E, z NE, w N
	vec4 swsm = fxaa_gather_luma(tex, ivec2(p.x, p.y + 1), rcp_size); // x SW, y S, z M, w W
	float lumaM = wmn.y;
	float lumaN = wmn.z, lumaS = sem.x, lumaW = wmn.x, lumaE = sem.z;
	vec4 nswe = vec4(lumaN, lumaS, lumaW, lumaE);
	float range;
	bool edge = fxaa_contrast_is_edge(nswe, lumaM, edge_threshold, edge_threshold_min, range);
	px.lumaM = lumaM;
	px.lumaN = lumaN;
	px.lumaS = lumaS;
	px.horizontal = false;
	px.subpix = 0.0;
	if (!edge)
		return false;

	float lumaNW = wmn.w, lumaNE = mene.z, lumaSW = swsm.x, lumaSE = sem.y;

	// Edge direction: second differences across rows (horizontal) and across columns (vertical), the
	// centre row/column weighted twice.
	float edgeHorz = abs(-2.0 * lumaW + lumaNW + lumaSW) + 2.0 * abs(-2.0 * lumaM + lumaN + lumaS) +
			 abs(-2.0 * lumaE + lumaNE + lumaSE);
	float edgeVert = abs(-2.0 * lumaN + lumaNW + lumaNE) + 2.0 * abs(-2.0 * lumaM + lumaW + lumaE) +
			 abs(-2.0 * lumaS + lumaSW + lumaSE);
	px.horizontal = edgeHorz >= edgeVert;
	if (!px.horizontal) {
		px.lumaN = lumaW;
		px.lumaS = lumaE;
	}

	// Subpixel aliasing: how far the 3x3 low-pass (edges weighted 2, corners 1) is from the centre,
	// relative to the local range; shaped by a smoothstep and squared.
	float lowpass = (2.0 * (lumaN + lumaS + lumaW + lumaE) + (lumaNW + lumaNE + lumaSW + lumaSE)) * (1.0 / 12.0);
	float subpixC = clamp(abs(lowpass - lumaM) * (1.0 / range), 0.0, 1.0);
	float subpixF = (-2.0 * subpixC + 3.0) * (subpixC * subpixC);
	px.subpix = subpixF * subpixF;
	return true;
}

float fxaa_fetch_luma(sampler2D tex, vec2 pos_px, vec2 rcp_size)
{
	return textureLod(tex, pos_px * rcp_size, 0.0).a;
}

// For an edge pixel: pair with the neighbour of the larger gradient across the edge, search along the
// edge both ways for its ends (the preset's steps; an end is where the pair's average luma changes by a
// quarter of the gradient), and offset the fetch towards the pair by the distance to the nearer end
// when that end is a "good span" (the luma change there has the opposite sign to the centre's), or by
// the subpixel term if larger. Returns the sRGB colour fetched at the offset position.
vec3 fxaa_resolve_edge(sampler2D tex, ivec2 p, ivec2 size, FxaaPixel px, float subpix)
{
	vec2 rcp_size = 1.0 / vec2(size);
	vec2 posM = vec2(p) + 0.5;
	float gradientN = px.lumaN - px.lumaM;
	float gradientS = px.lumaS - px.lumaM;
	bool pairN = abs(gradientN) >= abs(gradientS);
	float gradient = max(abs(gradientN), abs(gradientS));
	float lengthSign = pairN ? -1.0 : 1.0;                       // towards the pair, in pixels
	float lumaPairHalf = ((pairN ? px.lumaN : px.lumaS) + px.lumaM) * 0.5; // the pair's average
	vec2 along = px.horizontal ? vec2(1.0, 0.0) : vec2(0.0, 1.0);
	vec2 across = px.horizontal ? vec2(0.0, 1.0) : vec2(1.0, 0.0);
	vec2 posB = posM + across * (0.5 * lengthSign);              // on the boundary between the pair
	float gradientScaled = gradient * 0.25;
	bool lumaMLTZero = px.lumaM - lumaPairHalf < 0.0;

	vec2 posN = posB - along * fxaa_step(0);
	vec2 posP = posB + along * fxaa_step(0);
	float lumaEndN = fxaa_fetch_luma(tex, posN, rcp_size) - lumaPairHalf;
	float lumaEndP = fxaa_fetch_luma(tex, posP, rcp_size) - lumaPairHalf;
	bool doneN = abs(lumaEndN) >= gradientScaled;
	bool doneP = abs(lumaEndP) >= gradientScaled;
	// Each further step moves the sides not yet done; the last step moves without a fetch after it.
	for (int i = 1; i < FXAA_STEP_COUNT; i++) {
		if (doneN && doneP)
			break;
		if (!doneN)
			posN -= along * fxaa_step(i);
		if (!doneP)
			posP += along * fxaa_step(i);
		if (i == FXAA_STEP_COUNT - 1)
			break;
		if (!doneN)
			lumaEndN = fxaa_fetch_luma(tex, posN, rcp_size) - lumaPairHalf;
		if (!doneP)
			lumaEndP = fxaa_fetch_luma(tex, posP, rcp_size) - lumaPairHalf;
		doneN = abs(lumaEndN) >= gradientScaled;
		doneP = abs(lumaEndP) >= gradientScaled;
	}

	float dstN = dot(posM - posN, along);
	float dstP = dot(posP - posM, along);
	bool directionN = dstN < dstP;
	float dst = min(dstN, dstP);
	bool goodSpan = directionN ? ((lumaEndN < 0.0) != lumaMLTZero) : ((lumaEndP < 0.0) != lumaMLTZero);
	float pixelOffset = goodSpan ? 0.5 - dst / (dstN + dstP) : 0.0; // dstN, dstP >= 1: no zero division
	float offset = max(pixelOffset, px.subpix * subpix);
	return textureLod(tex, (posM + across * (offset * lengthSign)) * rcp_size, 0.0).rgb;
}
