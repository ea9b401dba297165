/* Images, buffers, barriers, one-shot command buffers, uploads and readback. */
#include <stdlib.h>
#include <string.h>

#include "gpu/gpu.h"

static int find_memory_type(struct aa_gpu *gpu, uint32_t bits, VkMemoryPropertyFlags want)
{
	for (uint32_t i = 0; i < gpu->memory_properties.memoryTypeCount; i++)
		if ((bits & (1u << i)) && (gpu->memory_properties.memoryTypes[i].propertyFlags & want) == want)
			return (int)i;
	return -1;
}

static int allocate(struct aa_gpu *gpu, VkMemoryRequirements req, VkMemoryPropertyFlags want,
		    VkDeviceMemory *out, struct aa_error *err)
{
	int type = find_memory_type(gpu, req.memoryTypeBits, want);
	if (type < 0)
		return aa_error_set(err, AA_ERR_GPU, "", "no Vulkan memory type with flags 0x%x", want);
	VkMemoryAllocateInfo ai = {
		.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
		.allocationSize = req.size,
		.memoryTypeIndex = (uint32_t)type,
	};
	VkResult vr = vkAllocateMemory(gpu->device, &ai, NULL, out);
	if (vr != VK_SUCCESS)
		return aa_error_set(err, AA_ERR_GPU, "", "cannot allocate %llu bytes of GPU memory (VkResult %d)",
				    (unsigned long long)req.size, vr);
	return 0;
}

uint32_t aa_gpu_format_bytes(VkFormat format)
{
	switch (format) {
	case VK_FORMAT_R8_UNORM: return 1;
	case VK_FORMAT_R8G8_UNORM: return 2;
	case VK_FORMAT_R16_SFLOAT:
	case VK_FORMAT_D16_UNORM: return 2;
	case VK_FORMAT_R8G8B8A8_UNORM:
	case VK_FORMAT_R8G8B8A8_SRGB:
	case VK_FORMAT_B8G8R8A8_UNORM:
	case VK_FORMAT_R32_SFLOAT:
	case VK_FORMAT_R32_UINT:
	case VK_FORMAT_D32_SFLOAT:
	case VK_FORMAT_R16G16_SFLOAT: return 4;
	case VK_FORMAT_R16G16B16A16_SFLOAT:
	case VK_FORMAT_R32G32_SFLOAT: return 8;
	case VK_FORMAT_R32G32B32A32_SFLOAT: return 16;
	default: return 4;
	}
}

int aa_gpu_image_create(struct aa_gpu *gpu, struct aa_gpu_image *img, int width, int height, VkFormat format,
			VkImageUsageFlags usage, uint32_t samples, uint32_t mip_levels, struct aa_error *err)
{
	memset(img, 0, sizeof *img);
	bool depth = format == VK_FORMAT_D32_SFLOAT || format == VK_FORMAT_D16_UNORM;
	img->format = format;
	img->aspect = depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
	img->width = width;
	img->height = height;
	img->samples = samples ? samples : 1;
	img->mip_levels = mip_levels ? mip_levels : 1;
	img->layout = VK_IMAGE_LAYOUT_UNDEFINED;
	VkImageCreateInfo ci = {
		.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO,
		.imageType = VK_IMAGE_TYPE_2D,
		.format = format,
		.extent = {(uint32_t)width, (uint32_t)height, 1},
		.mipLevels = img->mip_levels,
		.arrayLayers = 1,
		.samples = (VkSampleCountFlagBits)img->samples,
		.tiling = VK_IMAGE_TILING_OPTIMAL,
		.usage = usage,
		.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED,
	};
	VkResult vr = vkCreateImage(gpu->device, &ci, NULL, &img->image);
	if (vr != VK_SUCCESS)
		return aa_error_set(err, AA_ERR_GPU, "", "cannot create a %dx%d image (format %d, %u samples, "
				    "VkResult %d)", width, height, format, img->samples, vr);
	VkMemoryRequirements req;
	vkGetImageMemoryRequirements(gpu->device, img->image, &req);
	if (allocate(gpu, req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, &img->memory, err)) {
		aa_gpu_image_destroy(gpu, img);
		return -1;
	}
	img->bytes = req.size;
	vkBindImageMemory(gpu->device, img->image, img->memory, 0);
	VkImageViewCreateInfo vi = {
		.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO,
		.image = img->image,
		.viewType = VK_IMAGE_VIEW_TYPE_2D,
		.format = format,
		.subresourceRange = {img->aspect, 0, img->mip_levels, 0, 1},
	};
	if (vkCreateImageView(gpu->device, &vi, NULL, &img->view) != VK_SUCCESS) {
		aa_gpu_image_destroy(gpu, img);
		return aa_error_set(err, AA_ERR_GPU, "", "vkCreateImageView failed");
	}
	return 0;
}

void aa_gpu_image_destroy(struct aa_gpu *gpu, struct aa_gpu_image *img)
{
	if (!gpu->device)
		return;
	if (gpu->image_destroyed)
		gpu->image_destroyed(gpu->image_destroyed_user, img);
	if (img->view)
		vkDestroyImageView(gpu->device, img->view, NULL);
	if (img->image)
		vkDestroyImage(gpu->device, img->image, NULL);
	if (img->memory)
		vkFreeMemory(gpu->device, img->memory, NULL);
	memset(img, 0, sizeof *img);
}

void aa_gpu_image_barrier(VkCommandBuffer cmd, struct aa_gpu_image *img, VkImageLayout new_layout)
{
	VkImageMemoryBarrier b = {
		.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER,
		.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT,
		.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT,
		.oldLayout = img->layout,
		.newLayout = new_layout,
		.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
		.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
		.image = img->image,
		.subresourceRange = {img->aspect, 0, img->mip_levels, 0, 1},
	};
	vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0,
			     NULL, 0, NULL, 1, &b);
	img->layout = new_layout;
}

void aa_gpu_full_barrier(VkCommandBuffer cmd)
{
	VkMemoryBarrier b = {
		.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
		.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT,
		.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT,
	};
	vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 1,
			     &b, 0, NULL, 0, NULL);
}

int aa_gpu_buffer_create(struct aa_gpu *gpu, struct aa_gpu_buffer *buf, VkDeviceSize size,
			 VkBufferUsageFlags usage, bool host_visible, struct aa_error *err)
{
	memset(buf, 0, sizeof *buf);
	VkBufferCreateInfo ci = {
		.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
		.size = size ? size : 4,
		.usage = usage,
	};
	if (vkCreateBuffer(gpu->device, &ci, NULL, &buf->buffer) != VK_SUCCESS)
		return aa_error_set(err, AA_ERR_GPU, "", "cannot create a buffer of %llu bytes",
				    (unsigned long long)size);
	VkMemoryRequirements req;
	vkGetBufferMemoryRequirements(gpu->device, buf->buffer, &req);
	VkMemoryPropertyFlags want = host_visible ? VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
						    VK_MEMORY_PROPERTY_HOST_COHERENT_BIT
						  : VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
	if (allocate(gpu, req, want, &buf->memory, err)) {
		aa_gpu_buffer_destroy(gpu, buf);
		return -1;
	}
	vkBindBufferMemory(gpu->device, buf->buffer, buf->memory, 0);
	buf->size = ci.size;
	if (host_visible && vkMapMemory(gpu->device, buf->memory, 0, VK_WHOLE_SIZE, 0, &buf->mapped) != VK_SUCCESS) {
		aa_gpu_buffer_destroy(gpu, buf);
		return aa_error_set(err, AA_ERR_GPU, "", "vkMapMemory failed");
	}
	return 0;
}

void aa_gpu_buffer_destroy(struct aa_gpu *gpu, struct aa_gpu_buffer *buf)
{
	if (!gpu->device)
		return;
	if (buf->buffer)
		vkDestroyBuffer(gpu->device, buf->buffer, NULL);
	if (buf->memory)
		vkFreeMemory(gpu->device, buf->memory, NULL);
	memset(buf, 0, sizeof *buf);
}

int aa_gpu_interrupted(const struct aa_gpu *gpu, struct aa_error *err)
{
	if (gpu->interrupt && atomic_load(gpu->interrupt))
		return aa_error_set(err, AA_ERR_CANCELLED, "", "the job was cancelled");
	return 0;
}

int aa_gpu_begin(struct aa_gpu *gpu, VkCommandBuffer *cmd, struct aa_error *err)
{
	VkCommandBufferAllocateInfo ai = {
		.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
		.commandPool = gpu->command_pool,
		.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
		.commandBufferCount = 1,
	};
	if (vkAllocateCommandBuffers(gpu->device, &ai, cmd) != VK_SUCCESS)
		return aa_error_set(err, AA_ERR_GPU, "", "vkAllocateCommandBuffers failed");
	VkCommandBufferBeginInfo bi = {
		.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
		.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT,
	};
	vkBeginCommandBuffer(*cmd, &bi);
	return 0;
}

int aa_gpu_submit_wait(struct aa_gpu *gpu, VkCommandBuffer cmd, struct aa_error *err)
{
	vkEndCommandBuffer(cmd);
	VkSubmitInfo si = {
		.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO,
		.commandBufferCount = 1,
		.pCommandBuffers = &cmd,
	};
	VkFenceCreateInfo fci = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
	VkFence fence;
	vkCreateFence(gpu->device, &fci, NULL, &fence);
	VkResult vr = vkQueueSubmit(gpu->queue, 1, &si, fence);
	if (vr == VK_SUCCESS)
		vr = vkWaitForFences(gpu->device, 1, &fence, VK_TRUE, UINT64_MAX);
	vkDestroyFence(gpu->device, fence, NULL);
	vkFreeCommandBuffers(gpu->device, gpu->command_pool, 1, &cmd);
	if (vr != VK_SUCCESS)
		return aa_error_set(err, AA_ERR_GPU, "", "GPU submission failed (VkResult %d)", vr);
	return 0;
}

int aa_gpu_buffer_upload(struct aa_gpu *gpu, struct aa_gpu_buffer *buf, const void *data, VkDeviceSize size,
			 VkBufferUsageFlags usage, struct aa_error *err)
{
	struct aa_gpu_buffer staging;
	if (aa_gpu_buffer_create(gpu, &staging, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true, err))
		return -1;
	memcpy(staging.mapped, data, size);
	if (aa_gpu_buffer_create(gpu, buf, size, usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, false, err)) {
		aa_gpu_buffer_destroy(gpu, &staging);
		return -1;
	}
	VkCommandBuffer cmd;
	int rc = aa_gpu_begin(gpu, &cmd, err);
	if (rc == 0) {
		VkBufferCopy region = {0, 0, size};
		vkCmdCopyBuffer(cmd, staging.buffer, buf->buffer, 1, &region);
		rc = aa_gpu_submit_wait(gpu, cmd, err);
	}
	aa_gpu_buffer_destroy(gpu, &staging);
	return rc;
}

int aa_gpu_image_upload_rgba8(struct aa_gpu *gpu, struct aa_gpu_image *img, const uint8_t *const *levels,
			      struct aa_error *err)
{
	VkDeviceSize total = 0, bpp = aa_gpu_format_bytes(img->format); /* RGBA8, RG8 or R8 */
	for (uint32_t l = 0; l < img->mip_levels; l++) {
		uint32_t w = (uint32_t)img->width >> l, h = (uint32_t)img->height >> l;
		total += (VkDeviceSize)(w ? w : 1) * (h ? h : 1) * bpp;
	}
	struct aa_gpu_buffer staging;
	if (aa_gpu_buffer_create(gpu, &staging, total, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true, err))
		return -1;
	VkBufferImageCopy regions[16];
	VkDeviceSize offset = 0;
	uint32_t count = img->mip_levels < 16 ? img->mip_levels : 16;
	for (uint32_t l = 0; l < count; l++) {
		uint32_t w = (uint32_t)img->width >> l, h = (uint32_t)img->height >> l;
		w = w ? w : 1;
		h = h ? h : 1;
		memcpy((uint8_t *)staging.mapped + offset, levels[l], (size_t)(w * h * bpp));
		regions[l] = (VkBufferImageCopy){
			.bufferOffset = offset,
			.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, l, 0, 1},
			.imageExtent = {w, h, 1},
		};
		offset += (VkDeviceSize)w * h * bpp;
	}
	VkCommandBuffer cmd;
	int rc = aa_gpu_begin(gpu, &cmd, err);
	if (rc == 0) {
		aa_gpu_image_barrier(cmd, img, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
		vkCmdCopyBufferToImage(cmd, staging.buffer, img->image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, count,
				       regions);
		aa_gpu_image_barrier(cmd, img, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
		rc = aa_gpu_submit_wait(gpu, cmd, err);
	}
	aa_gpu_buffer_destroy(gpu, &staging);
	return rc;
}

int aa_gpu_record_readback(struct aa_gpu *gpu, VkCommandBuffer cmd, struct aa_gpu_image *img,
			   struct aa_gpu_buffer *buf, struct aa_error *err)
{
	VkDeviceSize need = (VkDeviceSize)img->width * img->height * aa_gpu_format_bytes(img->format);
	if (!buf->buffer || buf->size < need) {
		aa_gpu_buffer_destroy(gpu, buf);
		if (aa_gpu_buffer_create(gpu, buf, need, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true, err))
			return -1;
	}
	VkImageLayout keep = img->layout;
	aa_gpu_image_barrier(cmd, img, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
	VkBufferImageCopy region = {
		.imageSubresource = {img->aspect, 0, 0, 1},
		.imageExtent = {(uint32_t)img->width, (uint32_t)img->height, 1},
	};
	vkCmdCopyImageToBuffer(cmd, img->image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buf->buffer, 1, &region);
	VkMemoryBarrier b = {
		.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
		.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT,
		.dstAccessMask = VK_ACCESS_HOST_READ_BIT,
	};
	vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &b, 0, NULL, 0,
			     NULL);
	if (keep != VK_IMAGE_LAYOUT_UNDEFINED)
		aa_gpu_image_barrier(cmd, img, keep);
	return 0;
}

int aa_gpu_render_pass_create(struct aa_gpu *gpu, const struct aa_gpu_pass_desc *desc, VkRenderPass *out,
			      struct aa_error *err)
{
	VkAttachmentDescription att[2 * AA_GPU_MAX_COLOR + 1];
	VkAttachmentReference color_refs[AA_GPU_MAX_COLOR], resolve_refs[AA_GPU_MAX_COLOR], depth_ref;
	uint32_t n = 0;
	VkSampleCountFlagBits samples = (VkSampleCountFlagBits)(desc->samples ? desc->samples : 1);
	for (int i = 0; i < desc->color_count; i++) {
		if (desc->color_formats[i] == VK_FORMAT_UNDEFINED) { /* the shader's writes there are dropped */
			color_refs[i] = (VkAttachmentReference){VK_ATTACHMENT_UNUSED, VK_IMAGE_LAYOUT_UNDEFINED};
			continue;
		}
		att[n] = (VkAttachmentDescription){
			.format = desc->color_formats[i],
			.samples = samples,
			.loadOp = desc->color_load[i] ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_CLEAR,
			.storeOp = VK_ATTACHMENT_STORE_OP_STORE,
			.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE,
			.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE,
			.initialLayout = desc->color_load[i] ? VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL
							     : VK_IMAGE_LAYOUT_UNDEFINED,
			.finalLayout = desc->color_load[i] ? VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL
						   : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
		};
		color_refs[i] = (VkAttachmentReference){n++, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
	}
	bool has_depth = desc->depth_format != VK_FORMAT_UNDEFINED;
	if (has_depth) {
		att[n] = (VkAttachmentDescription){
			.format = desc->depth_format,
			.samples = samples,
			.loadOp = desc->depth_load ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_CLEAR,
			.storeOp = desc->depth_readable || desc->depth_store ? VK_ATTACHMENT_STORE_OP_STORE
									     : VK_ATTACHMENT_STORE_OP_DONT_CARE,
			.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE,
			.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE,
			.initialLayout = desc->depth_load ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL
							  : VK_IMAGE_LAYOUT_UNDEFINED,
			.finalLayout = desc->depth_readable ? VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL
							    : VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
		};
		depth_ref = (VkAttachmentReference){n++, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
	}
	bool resolve = desc->resolve && samples > 1;
	if (resolve)
		for (int i = 0; i < desc->color_count; i++) {
			if (desc->color_formats[i] == VK_FORMAT_UNDEFINED) {
				resolve_refs[i] = (VkAttachmentReference){VK_ATTACHMENT_UNUSED,
									  VK_IMAGE_LAYOUT_UNDEFINED};
				continue;
			}
			att[n] = (VkAttachmentDescription){
				.format = desc->color_formats[i],
				.samples = VK_SAMPLE_COUNT_1_BIT,
				.loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE,
				.storeOp = VK_ATTACHMENT_STORE_OP_STORE,
				.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE,
				.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE,
				.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED,
				.finalLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
			};
			resolve_refs[i] = (VkAttachmentReference){n++, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
		}
	VkSubpassDescription sub = {
		.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS,
		.colorAttachmentCount = (uint32_t)desc->color_count,
		.pColorAttachments = color_refs,
		.pResolveAttachments = resolve ? resolve_refs : NULL,
		.pDepthStencilAttachment = has_depth ? &depth_ref : NULL,
	};
	/* Make earlier writes visible before the pass, and the pass's writes visible to whatever follows. */
	VkSubpassDependency deps[2] = {
		{VK_SUBPASS_EXTERNAL, 0, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_ALL_GRAPHICS_BIT,
		 VK_ACCESS_MEMORY_WRITE_BIT, VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT, 0},
		{0, VK_SUBPASS_EXTERNAL, VK_PIPELINE_STAGE_ALL_GRAPHICS_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
		 VK_ACCESS_MEMORY_WRITE_BIT, VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT, 0},
	};
	VkRenderPassCreateInfo ci = {
		.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO,
		.attachmentCount = n,
		.pAttachments = att,
		.subpassCount = 1,
		.pSubpasses = &sub,
		.dependencyCount = 2,
		.pDependencies = deps,
	};
	if (vkCreateRenderPass(gpu->device, &ci, NULL, out) != VK_SUCCESS)
		return aa_error_set(err, AA_ERR_GPU, "", "vkCreateRenderPass failed");
	return 0;
}

int aa_gpu_framebuffer_create(struct aa_gpu *gpu, VkRenderPass pass, struct aa_gpu_image *const *attachments,
			      int count, VkFramebuffer *out, struct aa_error *err)
{
	VkImageView views[2 * AA_GPU_MAX_COLOR + 1];
	for (int i = 0; i < count; i++)
		views[i] = attachments[i]->view;
	VkFramebufferCreateInfo ci = {
		.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO,
		.renderPass = pass,
		.attachmentCount = (uint32_t)count,
		.pAttachments = views,
		.width = (uint32_t)attachments[0]->width,
		.height = (uint32_t)attachments[0]->height,
		.layers = 1,
	};
	if (vkCreateFramebuffer(gpu->device, &ci, NULL, out) != VK_SUCCESS)
		return aa_error_set(err, AA_ERR_GPU, "", "vkCreateFramebuffer failed");
	return 0;
}

void aa_gpu_begin_pass(VkCommandBuffer cmd, VkRenderPass pass, VkFramebuffer fb, int width, int height,
		       const VkClearValue *clears, int clear_count)
{
	VkRenderPassBeginInfo bi = {
		.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO,
		.renderPass = pass,
		.framebuffer = fb,
		.renderArea = {{0, 0}, {(uint32_t)width, (uint32_t)height}},
		.clearValueCount = (uint32_t)clear_count,
		.pClearValues = clears,
	};
	vkCmdBeginRenderPass(cmd, &bi, VK_SUBPASS_CONTENTS_INLINE);
	VkViewport vp = {0, 0, (float)width, (float)height, 0.0f, 1.0f};
	VkRect2D sc = {{0, 0}, {(uint32_t)width, (uint32_t)height}};
	vkCmdSetViewport(cmd, 0, 1, &vp);
	vkCmdSetScissor(cmd, 0, 1, &sc);
}
