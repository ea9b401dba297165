#version 450
#extension GL_GOOGLE_include_directive : require
// FXAA compute variant, pass 2: FXAA's early exit and edge direction for every pixel. Pixels FXAA leaves
// alone are copied to the output here; edge pixels are appended to the horizontal or vertical queue, and
// the queue's indirect dispatch size grows by one group every FXAA_QUEUE_LOCAL_SIZE items.
#include "fxaa_common.glsl"
#include "fxaa_cs_queue.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2D luma_tex;
layout(set = 0, binding = 1) uniform sampler2D scene;
layout(set = 0, binding = 2, rgba16f) uniform writeonly image2D result;
FXAA_PUSH_BLOCK;

void main()
{
	ivec2 p = ivec2(gl_GlobalInvocationID.xy);
	ivec2 size = textureSize(luma_tex, 0);
	if (any(greaterThanEqual(p, size)))
		return;
	FxaaPixel px;
	if (!fxaa_classify(luma_tex, p, size, push.edge_threshold, push.edge_threshold_min, px)) {
		imageStore(result, p, texelFetch(scene, p, 0));
		return;
	}
	uint item = uint(p.x) | (uint(p.y) << 16);
	if (px.horizontal) {
		uint i = atomicAdd(queues.count_horizontal, 1u);
		if (i % FXAA_QUEUE_LOCAL_SIZE == 0u)
			atomicAdd(queues.args_horizontal.x, 1u);
		queues.items[i] = item;
	} else {
		uint i = atomicAdd(queues.count_vertical, 1u);
		if (i % FXAA_QUEUE_LOCAL_SIZE == 0u)
			atomicAdd(queues.args_vertical.x, 1u);
		queues.items[uint(size.x * size.y) - 1u - i] = item;
	}
}
