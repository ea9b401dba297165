/* Sums of jittered scene renders, a batch of renders per summing pass (sample_accumulator.h). */
#include <string.h>

#include "reference/sample_accumulator.h"

int aa_sample_accumulator_create(struct aa_renderer *r, const struct aa_scene_target_desc *desc, int batch,
				 float weight, const char *name, struct aa_method_result *info,
				 struct aa_sample_accumulator *acc, struct aa_error *err)
{
	memset(acc, 0, sizeof *acc);
	acc->r = r;
	acc->weight = weight;
	acc->batch = batch < 1 ? 1 : batch > AA_ACCUMULATE_BATCH ? AA_ACCUMULATE_BATCH : batch;
	for (int i = 0; i < acc->batch; i++) {
		if (aa_scene_target_create_desc(r, &acc->targets[i], r->width, r->height, desc, name, info, err))
			return -1;
		acc->memory_bytes += acc->targets[i].color.bytes + acc->targets[i].depth.bytes;
	}
	for (int i = 0; i < 2; i++) {
		if (aa_renderer_image_create(r, &acc->sums[i], r->width, r->height, VK_FORMAT_R32G32B32A32_SFLOAT,
					     VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
					     VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
					     "running sum (RGBA32F)", info, err))
			return -1;
		acc->memory_bytes += acc->sums[i].bytes;
	}
	/* A partial batch leaves some bound targets unrendered: give them a readable layout from the start. */
	VkCommandBuffer cmd;
	if (aa_gpu_begin(r->gpu, &cmd, err))
		return -1;
	for (int i = 0; i < acc->batch; i++)
		aa_gpu_image_barrier(cmd, acc->targets[i].output, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
	if (aa_gpu_submit_wait(r->gpu, cmd, err))
		return -1;
	int32_t batch_constant = acc->batch;
	VkSpecializationMapEntry entry = {0, 0, sizeof batch_constant};
	VkSpecializationInfo spec = {1, &entry, sizeof batch_constant, &batch_constant};
	for (int i = 0; i < 2; i++) {
		/* every binding gets an image; the shader reads only the first `batch` renders */
		/* keep: the pass writes every pixel, so loading (free on lavapipe) beats clearing first */
		struct aa_fullscreen_desc d = {.frag = "accumulate_batch.frag", .source_count = 1 + AA_ACCUMULATE_BATCH,
					       .sources = {&acc->sums[1 - i]}, .target = &acc->sums[i], .keep = true,
					       .push_size = sizeof(float) + sizeof(int32_t), .specialization = &spec};
		for (int k = 0; k < AA_ACCUMULATE_BATCH; k++)
			d.sources[1 + k] = acc->targets[k < acc->batch ? k : 0].output;
		if (aa_fullscreen_pass_create(r, &acc->add[i], &d, err))
			return -1;
	}
	return 0;
}

void aa_sample_accumulator_destroy(struct aa_sample_accumulator *acc)
{
	if (!acc->r)
		return;
	for (int i = 0; i < 2; i++) {
		aa_fullscreen_pass_destroy(acc->r, &acc->add[i]);
		aa_gpu_image_destroy(acc->r->gpu, &acc->sums[i]);
	}
	for (int i = 0; i < acc->batch; i++)
		aa_scene_target_destroy(acc->r, &acc->targets[i]);
	memset(acc, 0, sizeof *acc);
}

void aa_sample_accumulator_clear(struct aa_sample_accumulator *acc, VkCommandBuffer cmd)
{
	struct aa_gpu_image *sum = &acc->sums[acc->current];
	aa_gpu_image_barrier(cmd, sum, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
	VkClearColorValue zero = {.float32 = {0, 0, 0, 0}};
	VkImageSubresourceRange range = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
	vkCmdClearColorImage(cmd, sum->image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero, 1, &range);
	aa_gpu_image_barrier(cmd, sum, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
	acc->pending = 0;
}

int aa_sample_accumulator_load(struct aa_sample_accumulator *acc, const float *sum, struct aa_error *err)
{
	const uint8_t *level = (const uint8_t *)sum;
	acc->pending = 0;
	return aa_gpu_image_upload_rgba8(acc->r->gpu, &acc->sums[acc->current], &level, err);
}

static void add_pending(struct aa_sample_accumulator *acc, VkCommandBuffer cmd)
{
	if (acc->pending == 0)
		return;
	int next = 1 - acc->current;
	struct { float weight; int32_t count; } push = {acc->weight, acc->pending};
	if (acc->sums[acc->current].layout != VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
		aa_gpu_image_barrier(cmd, &acc->sums[acc->current], VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
	aa_fullscreen_pass_record(acc->r, cmd, &acc->add[next], &push, sizeof push);
	acc->current = next;
	acc->pending = 0;
}

void aa_sample_accumulator_render(struct aa_sample_accumulator *acc, VkCommandBuffer cmd, float jx, float jy)
{
	aa_renderer_draw_scene(acc->r, cmd, &acc->targets[acc->pending++], jx, jy);
	if (acc->pending == acc->batch)
		add_pending(acc, cmd);
}

struct aa_gpu_image *aa_sample_accumulator_sum(struct aa_sample_accumulator *acc, VkCommandBuffer cmd)
{
	add_pending(acc, cmd);
	struct aa_gpu_image *sum = &acc->sums[acc->current];
	if (sum->layout != VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
		aa_gpu_image_barrier(cmd, sum, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
	return sum;
}
