/* GPU timestamps around passes, scaled by timestampPeriod. */
#include <string.h>
#include <stdio.h>

#include "gpu/gpu.h"

int aa_gpu_timer_create(struct aa_gpu *gpu, struct aa_gpu_timer *t, struct aa_error *err)
{
	memset(t, 0, sizeof *t);
	VkQueryPoolCreateInfo ci = {
		.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO,
		.queryType = VK_QUERY_TYPE_TIMESTAMP,
		.queryCount = AA_GPU_TIMER_MAX,
	};
	if (vkCreateQueryPool(gpu->device, &ci, NULL, &t->pool) != VK_SUCCESS)
		return aa_error_set(err, AA_ERR_GPU, "", "vkCreateQueryPool failed");
	return 0;
}

void aa_gpu_timer_destroy(struct aa_gpu *gpu, struct aa_gpu_timer *t)
{
	if (gpu->device && t->pool)
		vkDestroyQueryPool(gpu->device, t->pool, NULL);
	memset(t, 0, sizeof *t);
}

void aa_gpu_timer_reset(VkCommandBuffer cmd, struct aa_gpu_timer *t)
{
	vkCmdResetQueryPool(cmd, t->pool, 0, AA_GPU_TIMER_MAX);
	t->used = 0;
	t->span_count = 0;
}

int aa_gpu_timer_begin(VkCommandBuffer cmd, struct aa_gpu_timer *t, const char *name)
{
	if (t->used + 2 > AA_GPU_TIMER_MAX)
		return -1;
	int s = t->span_count++;
	snprintf(t->spans[s].name, sizeof t->spans[s].name, "%s", name);
	t->spans[s].begin = t->used++;
	t->spans[s].end = t->used++;
	/* BOTTOM_OF_PIPE + execution barrier: lavapipe flushes its queued work for this stamp, so the
	 * span measures only the pass that follows (lavapipe-costs.md, trap 1). */
	vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, t->pool, t->spans[s].begin);
	vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0,
			     NULL, 0, NULL, 0, NULL);
	return s;
}

void aa_gpu_timer_end(VkCommandBuffer cmd, struct aa_gpu_timer *t, int span)
{
	if (span < 0)
		return;
	vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, t->pool, t->spans[span].end);
}

int aa_gpu_timer_read(struct aa_gpu *gpu, struct aa_gpu_timer *t, double *ms, struct aa_error *err)
{
	if (t->used == 0)
		return 0;
	uint64_t stamps[AA_GPU_TIMER_MAX];
	VkResult vr = vkGetQueryPoolResults(gpu->device, t->pool, 0, t->used, sizeof stamps, stamps,
					    sizeof stamps[0], VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT);
	if (vr != VK_SUCCESS)
		return aa_error_set(err, AA_ERR_GPU, "", "reading timestamps failed (VkResult %d)", vr);
	uint64_t mask = gpu->timestamp_valid_bits >= 64 ? ~0ull : ((1ull << gpu->timestamp_valid_bits) - 1);
	for (int s = 0; s < t->span_count; s++) {
		uint64_t a = stamps[t->spans[s].begin] & mask, b = stamps[t->spans[s].end] & mask;
		uint64_t ticks = (b - a) & mask; /* wraps correctly within the valid bits */
		ms[s] = ticks * gpu->timestamp_period_ns * 1e-6;
	}
	return 0;
}
