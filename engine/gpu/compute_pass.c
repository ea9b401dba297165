/* Compute passes: a compute pipeline with its own descriptor set, recorded as direct or indirect
 * dispatches with the layout transitions and the barrier the pass needs. */
#include <string.h>

#include "gpu/compute_pass.h"

static VkDescriptorType descriptor_type(enum aa_compute_binding_kind kind)
{
	switch (kind) {
	case AA_COMPUTE_SAMPLED:
	case AA_COMPUTE_SAMPLED_LINEAR: return VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
	case AA_COMPUTE_STORAGE_IMAGE: return VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
	case AA_COMPUTE_STORAGE_BUFFER: return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
	}
	return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
}

static bool binding_is_valid(const struct aa_compute_binding *b)
{
	return b->kind == AA_COMPUTE_STORAGE_BUFFER ? b->buffer && b->buffer->buffer : b->image && b->image->view;
}

/* The pipeline layout comes from the GPU layer; the pipeline is made here because it may take
 * specialization constants. */
static int make_pipeline(struct aa_gpu *gpu, struct aa_compute_pass *p, const struct aa_compute_desc *d,
			 struct aa_error *err)
{
	const struct aa_shader_code *code = d->comp_code ? d->comp_code : aa_shader_find(d->comp);
	if (!code)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "shader '%s' is not embedded in this build", d->comp);
	VkShaderModuleCreateInfo mci = {
		.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO,
		.codeSize = code->size,
		.pCode = code->words,
	};
	VkShaderModule module;
	if (vkCreateShaderModule(gpu->device, &mci, NULL, &module) != VK_SUCCESS)
		return aa_error_set(err, AA_ERR_GPU, "", "vkCreateShaderModule failed for %s", d->comp);
	VkComputePipelineCreateInfo ci = {
		.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
		.stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
			  .stage = VK_SHADER_STAGE_COMPUTE_BIT, .module = module, .pName = "main",
			  .pSpecializationInfo = d->specialization},
		.layout = p->pipeline.layout,
	};
	VkResult vr = vkCreateComputePipelines(gpu->device, VK_NULL_HANDLE, 1, &ci, NULL, &p->pipeline.pipeline);
	vkDestroyShaderModule(gpu->device, module, NULL);
	if (vr != VK_SUCCESS)
		return aa_error_set(err, AA_ERR_GPU, "", "cannot create the %s pipeline (VkResult %d)", d->comp, vr);
	p->pipeline.bind_point = VK_PIPELINE_BIND_POINT_COMPUTE;
	return 0;
}

/* A pool sized for exactly this pass's one set, so compute passes never exhaust a shared pool. */
static int make_set(struct aa_gpu *gpu, struct aa_compute_pass *p, struct aa_error *err)
{
	VkDescriptorPoolSize sizes[3];
	uint32_t n_sampled = 0, n_images = 0, n_buffers = 0, count = 0;
	for (int i = 0; i < p->binding_count; i++) {
		VkDescriptorType t = descriptor_type(p->bindings[i].kind);
		n_sampled += t == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
		n_images += t == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
		n_buffers += t == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
	}
	if (n_sampled)
		sizes[count++] = (VkDescriptorPoolSize){VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, n_sampled};
	if (n_images)
		sizes[count++] = (VkDescriptorPoolSize){VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, n_images};
	if (n_buffers)
		sizes[count++] = (VkDescriptorPoolSize){VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, n_buffers};
	if (count == 0) /* a pool needs at least one size; a shader without bindings still gets an empty set */
		sizes[count++] = (VkDescriptorPoolSize){VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1};
	VkDescriptorPoolCreateInfo ci = {
		.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
		.maxSets = 1,
		.poolSizeCount = count,
		.pPoolSizes = sizes,
	};
	if (vkCreateDescriptorPool(gpu->device, &ci, NULL, &p->pool) != VK_SUCCESS)
		return aa_error_set(err, AA_ERR_GPU, "", "vkCreateDescriptorPool failed");
	if (aa_gpu_descriptor_set_alloc(gpu, p->pool, &p->pipeline, &p->set, err))
		return -1;
	for (int i = 0; i < p->binding_count; i++) {
		const struct aa_compute_binding *b = &p->bindings[i];
		VkDescriptorType t = descriptor_type(b->kind);
		switch (b->kind) {
		case AA_COMPUTE_SAMPLED:
		case AA_COMPUTE_SAMPLED_LINEAR:
			aa_gpu_write_image(gpu, p->set, (uint32_t)i, 0, t,
					   b->kind == AA_COMPUTE_SAMPLED ? gpu->sampler_nearest
									 : gpu->sampler_linear_clamp,
					   b->image, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
			break;
		case AA_COMPUTE_STORAGE_IMAGE:
			aa_gpu_write_image(gpu, p->set, (uint32_t)i, 0, t, VK_NULL_HANDLE, b->image,
					   VK_IMAGE_LAYOUT_GENERAL);
			break;
		case AA_COMPUTE_STORAGE_BUFFER:
			aa_gpu_write_buffer(gpu, p->set, (uint32_t)i, t, b->buffer);
			break;
		}
	}
	return 0;
}

int aa_compute_pass_create(struct aa_gpu *gpu, struct aa_compute_pass *p, const struct aa_compute_desc *d,
			   struct aa_error *err)
{
	memset(p, 0, sizeof *p);
	if (d->binding_count < 0 || d->binding_count > AA_COMPUTE_MAX_BINDINGS)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "%s: %d bindings, at most %d", d->comp,
				    d->binding_count, AA_COMPUTE_MAX_BINDINGS);
	p->binding_count = d->binding_count;
	VkDescriptorType types[AA_COMPUTE_MAX_BINDINGS];
	for (int i = 0; i < d->binding_count; i++) {
		if (!binding_is_valid(&d->bindings[i]))
			return aa_error_set(err, AA_ERR_INTERNAL, "", "%s: binding %d has no resource", d->comp, i);
		p->bindings[i] = d->bindings[i];
		types[i] = descriptor_type(d->bindings[i].kind);
	}
	if (aa_gpu_layout_create(gpu, types, NULL, d->binding_count, d->push_size, &p->pipeline, err) ||
	    make_pipeline(gpu, p, d, err) || make_set(gpu, p, err))
		return -1;
	return 0;
}

void aa_compute_pass_destroy(struct aa_gpu *gpu, struct aa_compute_pass *p)
{
	if (!gpu->device)
		return;
	if (p->pool)
		vkDestroyDescriptorPool(gpu->device, p->pool, NULL); /* frees the set */
	aa_gpu_pipeline_destroy(gpu, &p->pipeline);
	memset(p, 0, sizeof *p);
}

static void prepare(VkCommandBuffer cmd, struct aa_compute_pass *p, const void *push, uint32_t push_size)
{
	for (int i = 0; i < p->binding_count; i++) {
		struct aa_compute_binding *b = &p->bindings[i];
		if (b->kind == AA_COMPUTE_STORAGE_BUFFER)
			continue;
		VkImageLayout want = b->kind == AA_COMPUTE_STORAGE_IMAGE ? VK_IMAGE_LAYOUT_GENERAL
									 : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
		if (b->image->layout != want)
			aa_gpu_image_barrier(cmd, b->image, want);
	}
	aa_gpu_full_barrier(cmd);
	vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->pipeline.pipeline);
	vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p->pipeline.layout, 0, 1, &p->set, 0, NULL);
	if (push_size)
		vkCmdPushConstants(cmd, p->pipeline.layout, VK_SHADER_STAGE_ALL, 0, push_size, push);
}

void aa_compute_pass_dispatch(VkCommandBuffer cmd, struct aa_compute_pass *p, const void *push,
			      uint32_t push_size, uint32_t groups_x, uint32_t groups_y, uint32_t groups_z)
{
	prepare(cmd, p, push, push_size);
	if (groups_x && groups_y && groups_z)
		vkCmdDispatch(cmd, groups_x, groups_y, groups_z);
}

void aa_compute_pass_dispatch_indirect(VkCommandBuffer cmd, struct aa_compute_pass *p, const void *push,
				       uint32_t push_size, const struct aa_gpu_buffer *args, VkDeviceSize offset)
{
	prepare(cmd, p, push, push_size);
	vkCmdDispatchIndirect(cmd, args->buffer, offset);
}
