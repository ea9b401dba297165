/* The registry of intermediate images behind job option debug_targets, and their readback. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render/debug_targets.h"

/* Channels of the float formats a method's intermediate can have; 0: not checked. */
static int float_channels(VkFormat format, bool *half)
{
	*half = false;
	switch (format) {
	case VK_FORMAT_R16_SFLOAT: *half = true; return 1;
	case VK_FORMAT_R16G16_SFLOAT: *half = true; return 2;
	case VK_FORMAT_R16G16B16A16_SFLOAT: *half = true; return 4;
	case VK_FORMAT_R32_SFLOAT:
	case VK_FORMAT_D32_SFLOAT: return 1;
	case VK_FORMAT_R32G32_SFLOAT: return 2;
	case VK_FORMAT_R32G32B32A32_SFLOAT: return 4;
	default: return 0;
	}
}

bool aa_debug_targets_wants(VkFormat format, VkImageUsageFlags usage, uint32_t samples)
{
	bool half;
	if (samples > 1 || float_channels(format, &half) == 0)
		return false;
	/* a depth attachment that is not sampled is not stored (DONT_CARE): its contents mean nothing */
	return format != VK_FORMAT_D32_SFLOAT || (usage & VK_IMAGE_USAGE_SAMPLED_BIT);
}

VkImageUsageFlags aa_debug_targets_usage(const struct aa_debug_targets *d, VkFormat format, VkImageUsageFlags usage,
					 uint32_t samples)
{
	if (d && d->owner >= 0 && aa_debug_targets_wants(format, usage, samples))
		return usage | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
	return usage;
}

static void forget(void *user, const struct aa_gpu_image *img)
{
	struct aa_debug_targets *d = user;
	for (int i = 0; i < d->count; i++)
		if (d->targets[i].img == img) {
			d->targets[i] = d->targets[--d->count];
			i--;
		}
}

int aa_debug_targets_create(struct aa_gpu *gpu, struct aa_debug_targets **out, struct aa_error *err)
{
	struct aa_debug_targets *d = calloc(1, sizeof *d);
	if (!d)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	d->gpu = gpu;
	d->owner = -1;
	gpu->image_destroyed = forget;
	gpu->image_destroyed_user = d;
	*out = d;
	return 0;
}

void aa_debug_targets_destroy(struct aa_debug_targets *d)
{
	if (!d)
		return;
	if (d->gpu->image_destroyed_user == d) {
		d->gpu->image_destroyed = NULL;
		d->gpu->image_destroyed_user = NULL;
	}
	aa_gpu_buffer_destroy(d->gpu, &d->readback);
	free(d->targets);
	free(d);
}

int aa_debug_targets_add(struct aa_debug_targets *d, struct aa_gpu_image *img, VkImageUsageFlags usage,
			 const char *name, struct aa_error *err)
{
	if (!d || d->owner < 0 || !aa_debug_targets_wants(img->format, usage, img->samples))
		return 0;
	if (d->count == d->capacity) {
		int capacity = d->capacity ? 2 * d->capacity : 32;
		struct aa_debug_target *t = realloc(d->targets, (size_t)capacity * sizeof *t);
		if (!t)
			return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
		d->targets = t;
		d->capacity = capacity;
	}
	struct aa_debug_target *t = &d->targets[d->count++];
	*t = (struct aa_debug_target){.img = img, .image = img->image, .owner = d->owner};
	snprintf(t->name, sizeof t->name, "%s", name);
	return 0;
}

static bool half_nonfinite(uint16_t h)
{
	return (h & 0x7c00u) == 0x7c00u;
}

static bool float_invalid(float f, bool depth)
{
	/* reversed-Z depth lies in [0, 1] (the viewport clamps it): anything else was never written by a draw */
	return !isfinite(f) || (depth && (f < 0.0f || f > 1.0f));
}

long aa_debug_targets_count_invalid(const void *data, VkFormat format, int width, int height)
{
	bool half;
	const int channels = float_channels(format, &half);
	const bool depth = format == VK_FORMAT_D32_SFLOAT;
	const size_t texels = (size_t)width * height;
	long n = 0;
	for (size_t i = 0; i < texels; i++) {
		bool bad = false;
		for (int c = 0; c < channels; c++) {
			if (half) {
				bad |= half_nonfinite(((const uint16_t *)data)[i * channels + c]);
			} else {
				float f;
				memcpy(&f, (const char *)data + (i * channels + c) * sizeof f, sizeof f);
				bad |= float_invalid(f, depth);
			}
		}
		n += bad;
	}
	return n;
}

/* An image's bytes in the readback buffer, padded so that the next one starts at a 4-byte offset. */
static VkDeviceSize readback_bytes(const struct aa_gpu_image *img)
{
	return ((VkDeviceSize)img->width * img->height * aa_gpu_format_bytes(img->format) + 3) & ~(VkDeviceSize)3;
}

/* Whether entry t is read back for method owner: still the image it was entered as, and written by the
 * method (an image still UNDEFINED holds nothing yet). */
static bool to_read(const struct aa_debug_target *t, int owner)
{
	return t->owner == owner && t->img->image == t->image && t->img->layout != VK_IMAGE_LAYOUT_UNDEFINED;
}

int aa_debug_targets_check(struct aa_debug_targets *d, int owner, struct aa_frame_result *fr, struct aa_error *err)
{
	fr->targets_read = 0;
	fr->intermediate_invalid = 0;
	fr->invalid_target_count = 0;
	if (!d)
		return 0;
	VkDeviceSize total = 0;
	for (int i = 0; i < d->count; i++)
		if (to_read(&d->targets[i], owner))
			total += readback_bytes(d->targets[i].img);
	if (total == 0)
		return 0;
	struct aa_gpu *gpu = d->gpu;
	if (!d->readback.buffer || d->readback.size < total) {
		aa_gpu_buffer_destroy(gpu, &d->readback);
		if (aa_gpu_buffer_create(gpu, &d->readback, total, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true, err))
			return -1;
	}
	VkCommandBuffer cmd;
	if (aa_gpu_begin(gpu, &cmd, err))
		return -1;
	VkDeviceSize offset = 0;
	for (int i = 0; i < d->count; i++) {
		struct aa_debug_target *t = &d->targets[i];
		if (!to_read(t, owner))
			continue;
		struct aa_gpu_image *img = t->img;
		const VkImageLayout keep = img->layout;
		aa_gpu_image_barrier(cmd, img, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
		VkBufferImageCopy region = {
			.bufferOffset = offset,
			.imageSubresource = {img->aspect, 0, 0, 1},
			.imageExtent = {(uint32_t)img->width, (uint32_t)img->height, 1},
		};
		vkCmdCopyImageToBuffer(cmd, img->image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, d->readback.buffer, 1,
				       &region);
		aa_gpu_image_barrier(cmd, img, keep); /* the method's next frame finds it as it left it */
		offset += readback_bytes(img);
	}
	VkMemoryBarrier host = {
		.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
		.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT,
		.dstAccessMask = VK_ACCESS_HOST_READ_BIT,
	};
	vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &host, 0, NULL,
			     0, NULL);
	if (aa_gpu_submit_wait(gpu, cmd, err))
		return -1;
	offset = 0;
	for (int i = 0; i < d->count; i++) {
		const struct aa_debug_target *t = &d->targets[i];
		if (!to_read(t, owner))
			continue;
		const long bad = aa_debug_targets_count_invalid((const char *)d->readback.mapped + offset,
								t->img->format, t->img->width, t->img->height);
		offset += readback_bytes(t->img);
		fr->targets_read++;
		fr->intermediate_invalid += bad;
		if (bad && fr->invalid_target_count < AA_MAX_INVALID_TARGETS) {
			struct aa_target_count *c = &fr->invalid_targets[fr->invalid_target_count++];
			snprintf(c->name, sizeof c->name, "%s", t->name);
			c->texels = bad;
		}
	}
	return 0;
}
