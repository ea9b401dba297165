#version 450
#extension GL_GOOGLE_include_directive : require
// SMAA, after pass 1: appends every pixel with an edge to the queue that pass 2 runs over. One invocation
// per 8x8 tile (a per-pixel compute pass costs several times a fragment pass on lavapipe): it collects
// its tile's edge pixels, reserves their places with one atomic add and grows the indirect dispatch.
#define SMAA_QUEUE_BINDING 1
#include "smaa_queue.glsl"

#define TILE 8
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2D edges_tex; // RG8 from pass 1, texel reads

void main()
{
	ivec2 size = textureSize(edges_tex, 0);
	ivec2 origin = ivec2(gl_GlobalInvocationID.xy) * TILE;
	if (any(greaterThanEqual(origin, size)))
		return;
	ivec2 extent = min(size - origin, ivec2(TILE));
	uint rows[TILE]; // bit x of rows[y]: pixel origin + (x, y) has an edge
	uint n = 0u;
	for (int y = 0; y < TILE; y++) {
		rows[y] = 0u;
		for (int x = 0; x < TILE; x++) {
			vec2 e = x < extent.x && y < extent.y ? texelFetch(edges_tex, origin + ivec2(x, y), 0).rg
							      : vec2(0.0);
			if (e.r + e.g > 0.0)
				rows[y] |= 1u << x;
		}
		n += uint(bitCount(rows[y]));
	}
	if (n == 0u)
		return;
	uint at = atomicAdd(queue.count, n);
	atomicMax(queue.args.x, (at + n + SMAA_QUEUE_LOCAL_SIZE - 1u) / SMAA_QUEUE_LOCAL_SIZE);
	for (int y = 0; y < TILE; y++)
		for (uint bits = rows[y]; bits != 0u; bits &= bits - 1u) {
			int x = findLSB(bits);
			queue.items[at++] = uint(origin.x + x) | (uint(origin.y + y) << 16);
		}
}
