// The work queues of the FXAA compute variant (one storage buffer, struct layout in engine/methods/fxaa_cs.c):
// indirect dispatch arguments and counts for the horizontal and vertical edge queues, then one item per
// pixel at most. A pixel is in at most one queue, so both share the item array: horizontal items from
// the front, vertical items from the back.
#define FXAA_QUEUE_LOCAL_SIZE 64

layout(std430, set = 0, binding = 3) buffer FxaaQueues {
	uvec3 args_horizontal; // VkDispatchIndirectCommand: x counts groups of FXAA_QUEUE_LOCAL_SIZE items
	uint count_horizontal;
	uvec3 args_vertical;
	uint count_vertical;
	uint items[];          // x | y << 16
} queues;
