#version 450
#extension GL_GOOGLE_include_directive : require
// CMAA2 pass 2, shape handling, one invocation per pixel; most find nothing to do and stop after one edge
// read. Two kinds of shape:
//  - lines: a pixel that starts a run of bottom edges (or right edges, the same turned) walks along it up
//    to max_line pixels, to the first pixel without the edge or with a crossing edge at its corner. The
//    crossing edges at the two ends say which way the line steps: only a Z shape (steps to opposite
//    sides, a staircase) is revectorised, as one line from the middle of one step to the middle of the
//    other; L and U shapes (corners, bumps: often texture or text detail) and straight runs are left as
//    they are, the conservative choice CMAA2 makes. For each pixel on either side, the area between the
//    edge and that line on its side is how much of the other side's colour it takes;
//  - simple shapes: a pixel with edges on three or four sides (a lone pixel, the tip of a thin line) is
//    blended towards the neighbours across those edges by simple_blur each.
// Deferred blending: the line's starting pixel writes the blended colour of every pixel it changes into
// that pixel's slot of the accumulation buffer (fixed point, atomically); the apply pass averages what each
// pixel received, so pixels where shapes overlap get the mean of their blends.
#include "cmaa2_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2D scene;  // linear RGBA16F
layout(set = 0, binding = 1) uniform usampler2D edges; // R8UI from pass 1
layout(std430, set = 0, binding = 2) buffer Accumulation {
	uvec4 slot[]; // per pixel: R, G, B sums in 1/FIXED_ONE units, and the count of blends
} acc;
layout(push_constant) uniform Push {
	int max_line;      // longest run walked, in pixels
	float simple_blur; // simple shapes: share taken from each neighbour across an edge
} push;

const float FIXED_ONE = 4096.0;
const float FIXED_MAX = 64.0;  // linear colours above this are clamped in the sums
const float MIN_BLEND = 1.0 / 255.0;

ivec2 size;

uint edge_bits(ivec2 q)
{
	if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size)))
		return 0u;
	return texelFetch(edges, q, 0).r;
}

vec3 colour(ivec2 q)
{
	return texelFetch(scene, q, 0).rgb;
}

void deposit(ivec2 q, vec3 c)
{
	uvec3 fixed_c = uvec3(clamp(c, 0.0, FIXED_MAX) * FIXED_ONE + 0.5);
	uint i = uint(q.y * size.x + q.x);
	atomicAdd(acc.slot[i].x, fixed_c.x);
	atomicAdd(acc.slot[i].y, fixed_c.y);
	atomicAdd(acc.slot[i].z, fixed_c.z);
	atomicAdd(acc.slot[i].w, 1u);
}

// The area of the positive and negative parts of a line going from height ha to hb over a width w.
vec2 split_area(float ha, float hb, float w)
{
	if (ha >= 0.0 && hb >= 0.0)
		return vec2(0.5 * (ha + hb) * w, 0.0);
	if (ha <= 0.0 && hb <= 0.0)
		return vec2(0.0, -0.5 * (ha + hb) * w);
	float xc = w * ha / (ha - hb); // where it crosses 0
	vec2 tri = vec2(0.5 * ha * xc, 0.5 * hb * (w - xc));
	return ha > 0.0 ? vec2(tri.x, -tri.y) : vec2(tri.y, -tri.x);
}

// The revectorised line of a run: x in [x0, x1] going from height h0 to h1.
struct Piece { float x0, x1, h0, h1; };

vec2 column_area(Piece piece, float a, float b)
{
	float lo = max(a, piece.x0), hi = min(b, piece.x1);
	if (hi <= lo)
		return vec2(0.0);
	float slope = (piece.h1 - piece.h0) / (piece.x1 - piece.x0);
	return split_area(piece.h0 + slope * (lo - piece.x0), piece.h0 + slope * (hi - piece.x0), hi - lo);
}

// One run along `along`, its edge between each pixel and the pixel at + across. `up` is the side of the
// run's own pixels (positive heights), `down` the other. step(q): the crossing edges at the corner before
// pixel q of the run, on its own side (x) and the other (y).
bvec2 crossing(ivec2 q, ivec2 along, ivec2 across, uint cross_bit)
{
	ivec2 before = q - along; // the crossing edges lie between before and q, in both rows
	// a crossing edge at that corner is the `cross_bit` edge of `before` (right edge for horizontal runs,
	// bottom edge for vertical runs), in the run's own row and in the row across
	return bvec2((edge_bits(before) & cross_bit) != 0u, (edge_bits(before + across) & cross_bit) != 0u);
}

float step_side(bvec2 c)
{
	return c.x && !c.y ? 1.0 : c.y && !c.x ? -1.0 : 0.0;
}

void run_line(ivec2 p, ivec2 along, ivec2 across, uint run_bit, uint cross_bit)
{
	bvec2 start = crossing(p, along, across, cross_bit);
	bool continues = (edge_bits(p - along) & run_bit) != 0u && !start.x && !start.y;
	if (continues)
		return; // not the first pixel of its run
	float sl = step_side(start);
	if (sl == 0.0)
		return; // a Z shape steps at both ends: no need to walk a run that does not step here
	int n = 1;
	bvec2 end = bvec2(false);
	for (; n < push.max_line; n++) {
		ivec2 q = p + n * along;
		end = crossing(q, along, across, cross_bit);
		if ((edge_bits(q) & run_bit) == 0u || end.x || end.y)
			break;
	}
	if (n == push.max_line)
		end = crossing(p + n * along, along, across, cross_bit);
	float sr = step_side(end);
	if (sl * sr >= 0.0)
		return; // not a Z shape
	// one line from the middle of one step to the middle of the other
	Piece line = Piece(0.0, float(n), 0.5 * sl, 0.5 * sr);
	for (int i = 0; i < n; i++) {
		vec2 area = column_area(line, float(i), float(i + 1));
		ivec2 own = p + i * along, other = own + across;
		vec3 c_own = colour(own), c_other = colour(other);
		if (area.x > MIN_BLEND) // the line crosses into the run's own pixel: it takes the other colour
			deposit(own, mix(c_own, c_other, area.x));
		if (area.y > MIN_BLEND)
			deposit(other, mix(c_other, c_own, area.y));
	}
}

void main()
{
	ivec2 p = ivec2(gl_GlobalInvocationID.xy);
	size = textureSize(scene, 0);
	if (any(greaterThanEqual(p, size)))
		return;
	uint e = edge_bits(p);
	uint left = edge_bits(p - ivec2(1, 0)) & EDGE_RIGHT, top = edge_bits(p - ivec2(0, 1)) & EDGE_BOTTOM;
	if (e == 0u && left == 0u && top == 0u)
		return;
	// runs of bottom edges (horizontal lines) and of right edges (vertical lines); for a vertical run the
	// crossing edges are the bottom edges of the pixels above each corner
	if ((e & EDGE_BOTTOM) != 0u)
		run_line(p, ivec2(1, 0), ivec2(0, 1), EDGE_BOTTOM, EDGE_RIGHT);
	if ((e & EDGE_RIGHT) != 0u)
		run_line(p, ivec2(0, 1), ivec2(1, 0), EDGE_RIGHT, EDGE_BOTTOM);
	// simple shapes
	bool sides[4] = bool[4]((e & EDGE_RIGHT) != 0u, (e & EDGE_BOTTOM) != 0u, left != 0u, top != 0u);
	const ivec2 dirs[4] = ivec2[4](ivec2(1, 0), ivec2(0, 1), ivec2(-1, 0), ivec2(0, -1));
	int count = int(sides[0]) + int(sides[1]) + int(sides[2]) + int(sides[3]);
	if (count >= 3) {
		vec3 c = colour(p), sum = vec3(0.0);
		for (int k = 0; k < 4; k++)
			if (sides[k])
				sum += colour(p + dirs[k]) - c;
		deposit(p, c + push.simple_blur * sum);
	}
}
