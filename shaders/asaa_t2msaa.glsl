// Shared by the temporal methods of seed 000 (asaa.comp, t2msaa.comp): sanitising the new samples,
// validating velocities and the history rejection rules of the thesis (Listings 3.9, 4.3, 4.16).

// Velocity images hold 65000 where a pixel has no previous position; anything this large is invalid.
const float NO_MOTION_LIMIT = 30000.0;

// NaN or Inf in any channel, tested on the bits so no compiler can fold it away.
bool all_finite(vec3 c)
{
	uvec3 e = floatBitsToUint(c) & 0x7f800000u;
	return all(notEqual(e, uvec3(0x7f800000u)));
}

bool finite1(float x)
{
	return (floatBitsToUint(x) & 0x7f800000u) != 0x7f800000u;
}

bool velocity_valid(vec2 v)
{
	return finite1(v.x) && finite1(v.y) && all(lessThan(abs(v), vec2(NO_MOTION_LIMIT)));
}

// The thesis's luma (section 2.2.5) for the luminance-weighted blend.
float luma(vec3 c)
{
	return dot(c, vec3(0.299, 0.587, 0.114));
}

// A new sample that is not finite (stability tests poison sparse pixels) is replaced by the mean of its
// finite 4-neighbours, or black: nothing non-finite may reach history or output. Colours are clamped to
// the half-float range, so +Inf can never come back through a later multiplication.
vec3 finite_sample(sampler2D img, ivec2 p, ivec2 size)
{
	vec3 c = texelFetch(img, p, 0).rgb;
	if (all_finite(c))
		return clamp(c, vec3(0.0), vec3(65504.0));
	vec3 sum = vec3(0.0);
	float n = 0.0;
	ivec2 offsets[4] = ivec2[](ivec2(-1, 0), ivec2(1, 0), ivec2(0, -1), ivec2(0, 1));
	for (int i = 0; i < 4; i++) {
		ivec2 q = p + offsets[i];
		if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size)))
			continue;
		vec3 d = texelFetch(img, q, 0).rgb;
		if (all_finite(d)) {
			sum += clamp(d, vec3(0.0), vec3(65504.0));
			n += 1.0;
		}
	}
	return n > 0.0 ? sum / n : vec3(0.0);
}

// Depth kept in half-float history as log2(depth): half floats end at 65504, and a clamp there made
// every surface beyond it fail the disocclusion test against the clamped value (nothing past ~70,000
// units accumulated). In log2 the half float's 11-bit mantissa keeps depth to 0.5% up to 2^32 units,
// far inside the 8% the test allows; bilinear reads interpolate it geometrically, which the test does
// not notice either.
float depth_encode(float depth)
{
	return log2(max(depth, 1e-30));
}

float depth_decode(float stored)
{
	return exp2(stored);
}

// Linear view depth of the G-buffer's surface target (.y); non-finite or non-positive depths become the
// largest finite value, which no depth test accepts as "nearer".
float surface_depth(sampler2D surface, ivec2 p)
{
	float d = texelFetch(surface, p, 0).y;
	return finite1(d) && d > 0.0 ? d : 3.0e38;
}

// The footprint of this pixel in the previous frame: max(|d prev/dx|, |d prev/dy|) per axis, where
// prev = centre - velocity (the thesis's pixelRadius from ddx/ddy, Listing 4.3), by finite differences
// with the right and lower neighbour (left/upper at the border). Neighbours without a valid velocity
// count as moving like this pixel.
vec2 footprint_radius(sampler2D velocity, ivec2 p, ivec2 size)
{
	int sx = p.x + 1 < size.x ? 1 : -1, sy = p.y + 1 < size.y ? 1 : -1;
	vec2 v = texelFetch(velocity, p, 0).xy;
	vec2 vx = texelFetch(velocity, p + ivec2(sx, 0), 0).xy;
	vec2 vy = texelFetch(velocity, p + ivec2(0, sy), 0).xy;
	if (!velocity_valid(v))
		return vec2(1.0);
	if (!velocity_valid(vx))
		vx = v;
	if (!velocity_valid(vy))
		vy = v;
	vec2 dx = vec2(1.0, 0.0) - (vx - v) * float(sx);
	vec2 dy = vec2(0.0, 1.0) - (vy - v) * float(sy);
	return max(abs(dx), abs(dy));
}

// Border rejection (Listing 3.9): the previous position must lie on the image. A velocity pointing
// off-screen is a miss, never a clamped lookup.
bool on_screen(vec2 q, vec2 size)
{
	return all(greaterThanEqual(q, vec2(0.0))) && all(lessThanEqual(q, size));
}

// Magnification rejection (Listing 4.3, the thesis's version without the 0.5 scale): a miss when the
// previous position is further from the nearest previous pixel centre than the footprint radius.
bool magnified(vec2 q, vec2 radius)
{
	vec2 d = abs(q - (floor(q) + 0.5));
	return any(greaterThan(d, radius));
}

// Disocclusion rejection (Listing 4.3): a miss when this surface lies further than 8% (of its depth)
// behind what the history saw there. One-sided, as in the thesis: nearer surfaces are accepted.
bool disoccluded(float depth, float history_depth)
{
	return !finite1(history_depth) || depth - history_depth > 0.08 * depth;
}
