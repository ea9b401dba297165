#version 450
#extension GL_GOOGLE_include_directive : require
// SMAA pass 2, blending weights (notes/smaa.md §3), one invocation per queued edge pixel. Find the line
// the pixel's edges belong to (diagonal staircases first, then the horizontal line through its top edge
// and the vertical line through its left edge), the crossing edges at both ends, and look the coverage
// up in the area texture. Output: R, G = weights across the top edge (this pixel's side, the
// neighbour's side); B, A = the same for the left edge. Other pixels keep the weights' clear to 0.
#define SMAA_QUEUE_BINDING 3
#include "smaa_queue.glsl"

layout(local_size_x = SMAA_QUEUE_LOCAL_SIZE) in;
layout(set = 0, binding = 0) uniform sampler2D edges_tex;  // RG8, bilinear: searches decode 2x2 blocks
layout(set = 0, binding = 1) uniform sampler2D area_tex;   // RG8 160x560, bilinear (sqrt distances)
layout(set = 0, binding = 2) uniform sampler2D search_tex; // R8 64x16, nearest: reads hit texel centres
layout(set = 0, binding = 4, rgba8) uniform writeonly image2D weights_out;
layout(push_constant) uniform Push {
	int search_steps;      // SMAA_MAX_SEARCH_STEPS: 2 pixels per step
	int diag_steps;        // SMAA_MAX_SEARCH_STEPS_DIAG: 1 pixel per step; 0 = no diagonal detection
	float corner_keep;     // 1 - SMAA_CORNER_ROUNDING / 100; negative = no corner detection
	int pad;
	// subsample indices (notes/smaa.md §3.9): the area texture slot of each line kind for this sample's
	// position in the pixel: x vertical lines, y horizontal lines, z "/" diagonals, w "\" diagonals;
	// all 0 for SMAA 1x
	ivec4 subsample;
} push;

const float AREA_BLOCK = 16.0;             // orthogonal block of the area texture, per crossing pattern
const vec2 AREA_SIZE = vec2(160.0, 560.0);
const float AREA_SLOT = 80.0;              // rows per subsample slot (7 orthogonal, 5 diagonal)
const float SEARCH_RESCALE = 255.0 / 127.0; // stored 0, 127, 254 -> 0, 1, 2 pixels
const float SEARCH_END_BIAS = 3.25;         // +0.25 start offset, +1 search bias, +2 for the last step

vec2 size, rcp, pixcoord; // pixcoord: the pixel centre in pixels
ivec2 last_texel;

vec2 edge_at(ivec2 q)
{
	return texelFetch(edges_tex, clamp(q, ivec2(0), last_texel), 0).rg;
}

// ------------------------------------------------------------------ orthogonal lines (§3.3-§3.6)

// The last search fetch e mixed a 2x2 block (far/near pixel x line row/outer row); the search texture
// says how many of its pixels still belong to the line. offset 0: left/up table, 0.5: right/down table.
float search_length(vec2 e, float offset)
{
	vec2 texel = vec2(32.0 * e.x + 66.0 * offset + 0.5, 32.5 - 32.0 * e.y);
	return textureLod(search_tex, texel / vec2(64.0, 16.0), 0.0).r;
}

// Each step reads two pixels of the line row (weights 0.75 near, 0.25 far) mixed 7:1 with the row
// above/left; it goes on while both have the line's edge (> 0.8281) and none has a crossing edge.
float search_left(vec2 t)
{
	vec2 e = vec2(0.0, 1.0);
	for (int i = 0; i < push.search_steps && e.g > 0.8281 && e.r == 0.0; i++) {
		e = textureLod(edges_tex, t, 0.0).rg;
		t.x -= 2.0 * rcp.x;
	}
	return t.x + (SEARCH_END_BIAS - SEARCH_RESCALE * search_length(e, 0.0)) * rcp.x;
}

float search_right(vec2 t)
{
	vec2 e = vec2(0.0, 1.0);
	for (int i = 0; i < push.search_steps && e.g > 0.8281 && e.r == 0.0; i++) {
		e = textureLod(edges_tex, t, 0.0).rg;
		t.x += 2.0 * rcp.x;
	}
	return t.x - (SEARCH_END_BIAS - SEARCH_RESCALE * search_length(e, 0.5)) * rcp.x;
}

float search_up(vec2 t)
{
	vec2 e = vec2(1.0, 0.0);
	for (int i = 0; i < push.search_steps && e.r > 0.8281 && e.g == 0.0; i++) {
		e = textureLod(edges_tex, t, 0.0).rg;
		t.y -= 2.0 * rcp.y;
	}
	return t.y + (SEARCH_END_BIAS - SEARCH_RESCALE * search_length(e.gr, 0.0)) * rcp.y;
}

float search_down(vec2 t)
{
	vec2 e = vec2(1.0, 0.0);
	for (int i = 0; i < push.search_steps && e.r > 0.8281 && e.g == 0.0; i++) {
		e = textureLod(edges_tex, t, 0.0).rg;
		t.y += 2.0 * rcp.y;
	}
	return t.y - (SEARCH_END_BIAS - SEARCH_RESCALE * search_length(e.gr, 0.5)) * rcp.y;
}

// Coverage for integer distances d to both ends and the crossing edges read there: round(4 e) is
// 0 (none), 1 (on the far side of the line), 3 (on this pixel's side) or 4 (both), which is the block
// index; distances are stored as sqrt (16 texels reach 225 pixels), so this read is bilinear.
vec2 area_ortho(vec2 d, float e1, float e2, int slot)
{
	vec2 texel = AREA_BLOCK * round(4.0 * vec2(e1, e2)) + sqrt(d) + vec2(0.0, AREA_SLOT * float(slot));
	return textureLod(area_tex, (texel + 0.5) / AREA_SIZE, 0.0).rg;
}

// Which end rounds a corner: the nearer one (both, halved, when equal).
vec2 corner_share(vec2 d)
{
	vec2 ends = step(d.xy, d.yx);
	return push.corner_keep * ends / (ends.x + ends.y);
}

// The horizontal line through this pixel's top edge.
vec2 horizontal_weights(ivec2 p, vec2 uv)
{
	// Start a quarter pixel left (1.25 right) and an eighth up, so each fetch mixes as described above.
	float xl = search_left(uv + vec2(-0.25, -0.125) * rcp);
	float xr = search_right(uv + vec2(1.25, -0.125) * rcp);
	vec2 d = abs(round(vec2(xl, xr) * size.x - pixcoord.x));
	// Crossing edges at the ends, read a quarter pixel up: 0.75 this row, 0.25 the row above.
	float y = uv.y - 0.25 * rcp.y;
	float e1 = textureLod(edges_tex, vec2(xl, y), 0.0).r;
	float e2 = textureLodOffset(edges_tex, vec2(xr, y), 0.0, ivec2(1, 0)).r;
	vec2 w = area_ortho(d, e1, e2, push.subsample.y);
	if (push.corner_keep >= 0.0) {
		// A crossing edge that goes on two pixels beyond the line marks a real corner: blend less.
		vec2 r = corner_share(d);
		int left = p.x - int(d.x), right = p.x + int(d.y) + 1;
		vec2 f = vec2(1.0);
		f.x -= r.x * edge_at(ivec2(left, p.y + 1)).r + r.y * edge_at(ivec2(right, p.y + 1)).r;
		f.y -= r.x * edge_at(ivec2(left, p.y - 2)).r + r.y * edge_at(ivec2(right, p.y - 2)).r;
		w *= clamp(f, 0.0, 1.0);
	}
	return w;
}

// The vertical line through this pixel's left edge: the same with the axes swapped.
vec2 vertical_weights(ivec2 p, vec2 uv)
{
	float yt = search_up(uv + vec2(-0.125, -0.25) * rcp);
	float yb = search_down(uv + vec2(-0.125, 1.25) * rcp);
	vec2 d = abs(round(vec2(yt, yb) * size.y - pixcoord.y));
	float x = uv.x - 0.25 * rcp.x;
	float e1 = textureLod(edges_tex, vec2(x, yt), 0.0).g;
	float e2 = textureLodOffset(edges_tex, vec2(x, yb), 0.0, ivec2(0, 1)).g;
	vec2 w = area_ortho(d, e1, e2, push.subsample.x);
	if (push.corner_keep >= 0.0) {
		vec2 r = corner_share(d);
		int top = p.y - int(d.x), bottom = p.y + int(d.y) + 1;
		vec2 f = vec2(1.0);
		f.x -= r.x * edge_at(ivec2(p.x + 1, top)).g + r.y * edge_at(ivec2(p.x + 1, bottom)).g;
		f.y -= r.x * edge_at(ivec2(p.x - 2, top)).g + r.y * edge_at(ivec2(p.x - 2, bottom)).g;
		w *= clamp(f, 0.0, 1.0);
	}
	return w;
}

// ------------------------------------------------------------------ diagonal lines (§3.7-§3.8)

// Walks from p along dir while each pixel has both edges of a staircase step: its left and top edges
// ("/"), or its top edge and its right neighbour's left edge ("\"). Returns (pixels that passed,
// 1 if the walk hit the step cap without finding the end, the last pixel's top edge).
vec3 diagonal_walk(ivec2 p, ivec2 dir, bool backslash)
{
	int n = -1;
	float both = 1.0, top = 0.0;
	while (n < push.diag_steps - 1 && both > 0.9) {
		n++;
		ivec2 q = p + (n + 1) * dir;
		vec2 e = edge_at(q);
		if (backslash)
			e.r = edge_at(q + ivec2(1, 0)).r;
		both = (e.r + e.g) * 0.5;
		top = e.g;
	}
	return vec3(float(n), both, top);
}

// Diagonal area: distances and crossing codes are integers, so this is a texel read.
vec2 area_diag(float dl, float dr, float c1, float c2, int slot)
{
	return texelFetch(area_tex, ivec2(80 + 20 * int(c1) + int(dl), 80 * slot + 20 * int(c2) + int(dr)), 0).rg;
}

vec2 diagonal_weights(ivec2 p, vec2 e)
{
	vec2 w = vec2(0.0);
	// "/": the down-left arm needs this pixel's left edge; an end pixel with a top edge adds one
	vec3 l = vec3(0.0);
	if (e.r > 0.0) {
		l = diagonal_walk(p, ivec2(-1, 1), false);
		l.x += step(0.9, l.z);
	}
	vec3 r = diagonal_walk(p, ivec2(1, -1), false);
	if (l.x + r.x > 2.0) { // longer than 3 pixels
		ivec2 pl = p + ivec2(-1, 1) * int(l.x), pr = p + ivec2(1, -1) * int(r.x);
		float c1 = 2.0 * edge_at(pl + ivec2(-1, 0)).g + edge_at(pl).r;
		float c2 = 2.0 * edge_at(pr + ivec2(1, 0)).g + edge_at(pr + ivec2(1, -1)).r;
		c1 = l.y >= 0.9 ? 0.0 : c1; // an end not found has no known crossing
		c2 = r.y >= 0.9 ? 0.0 : c2;
		w += area_diag(l.x, r.x, c1, c2, push.subsample.z);
	}
	// "\": the down-right arm needs the right neighbour's left edge
	l = diagonal_walk(p, ivec2(-1, -1), true);
	r = vec3(0.0);
	if (edge_at(p + ivec2(1, 0)).r > 0.0) {
		r = diagonal_walk(p, ivec2(1, 1), true);
		r.x += step(0.9, r.z);
	}
	if (l.x + r.x > 2.0) {
		ivec2 pl = p - ivec2(int(l.x)), pr = p + ivec2(int(r.x));
		float c1 = 2.0 * edge_at(pl + ivec2(-1, 0)).g + edge_at(pl + ivec2(0, -1)).r;
		float c2 = 2.0 * edge_at(pr + ivec2(1, 0)).g + edge_at(pr + ivec2(1, 0)).r;
		c1 = l.y >= 0.9 ? 0.0 : c1;
		c2 = r.y >= 0.9 ? 0.0 : c2;
		w += area_diag(l.x, r.x, c1, c2, push.subsample.w).gr; // mirrored pattern: the sides swap
	}
	return w;
}

void main()
{
	if (gl_GlobalInvocationID.x >= queue.count)
		return;
	uint item = queue.items[gl_GlobalInvocationID.x];
	ivec2 p = ivec2(item & 0xffffu, item >> 16);
	ivec2 isize = textureSize(edges_tex, 0);
	vec2 e = texelFetch(edges_tex, p, 0).rg;
	size = vec2(isize);
	rcp = 1.0 / size;
	last_texel = isize - 1;
	pixcoord = vec2(p) + 0.5;
	vec2 uv = pixcoord * rcp;
	vec4 w = vec4(0.0);
	bool diagonal = false;
	if (e.g > 0.0) {
		if (push.diag_steps > 0) {
			w.rg = diagonal_weights(p, e);
			diagonal = w.r + w.g != 0.0; // a diagonal replaces both orthogonal lines
		}
		if (!diagonal)
			w.rg = horizontal_weights(p, uv);
	}
	if (e.r > 0.0 && !diagonal)
		w.ba = vertical_weights(p, uv);
	imageStore(weights_out, p, w);
}
