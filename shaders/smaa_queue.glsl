// The queue of SMAA edge pixels (one storage buffer; struct smaa_queue_header in engine/methods/smaa.c):
// the indirect dispatch size of the blending-weight pass, the number of items, then one item per edge
// pixel. The edge pass appends, the weight pass runs one invocation per item.
#define SMAA_QUEUE_LOCAL_SIZE 64

layout(std430, set = 0, binding = SMAA_QUEUE_BINDING) buffer SmaaQueue {
	uvec3 args;     // VkDispatchIndirectCommand: groups of SMAA_QUEUE_LOCAL_SIZE items
	uint count;
	uint items[];   // x | y << 16
} queue;
