#version 450
#extension GL_GOOGLE_include_directive : require
// FXAA compute variant, passes 3 and 4 (one pipeline each, HORIZONTAL selects the queue): the end-of-edge
// search and offset fetch for the pixels of one queue, dispatched indirectly with the group count the
// classification wrote. All items of a dispatch share the edge direction, so the search loops of
// neighbouring invocations run in step.
#include "fxaa_common.glsl"
#include "fxaa_cs_queue.glsl"

layout(constant_id = 13) const bool HORIZONTAL = true;

layout(local_size_x = FXAA_QUEUE_LOCAL_SIZE) in;
layout(set = 0, binding = 0) uniform sampler2D luma_tex;
layout(set = 0, binding = 1) uniform sampler2D scene;
layout(set = 0, binding = 2, rgba16f) uniform writeonly image2D result;
FXAA_PUSH_BLOCK;

void main()
{
	uint i = gl_GlobalInvocationID.x;
	ivec2 size = textureSize(luma_tex, 0);
	if (i >= (HORIZONTAL ? queues.count_horizontal : queues.count_vertical))
		return;
	uint item = HORIZONTAL ? queues.items[i] : queues.items[uint(size.x * size.y) - 1u - i];
	ivec2 p = ivec2(item & 0xffffu, item >> 16);
	// The classification is recomputed (nine fetches) rather than stored: the same function on the same
	// texels gives the same values as in fxaa.frag, and the queues stay one word per pixel.
	FxaaPixel px;
	fxaa_classify(luma_tex, p, size, push.edge_threshold, push.edge_threshold_min, px);
	vec3 srgb = fxaa_resolve_edge(luma_tex, p, size, px, push.subpix);
	imageStore(result, p, vec4(fxaa_srgb_to_linear(srgb), texelFetch(scene, p, 0).a));
}
