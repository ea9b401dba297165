/* Pipelines, pipeline layouts and descriptor sets. Every pipeline uses dynamic viewport/scissor so one
 * pipeline serves any target size. */
#include <stdlib.h>
#include <string.h>

#include "gpu/gpu.h"
#include "util/sha256.h"
#include "scene/scene.h"

static int make_module_code(struct aa_gpu *gpu, const struct aa_shader_code *code, VkShaderModule *out,
			    struct aa_error *err)
{
	VkShaderModuleCreateInfo ci = {
		.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO,
		.codeSize = code->size,
		.pCode = code->words,
	};
	if (vkCreateShaderModule(gpu->device, &ci, NULL, out) != VK_SUCCESS)
		return aa_error_set(err, AA_ERR_GPU, "", "vkCreateShaderModule failed for %s", code->name);
	return 0;
}

static int make_module(struct aa_gpu *gpu, const char *name, VkShaderModule *out, struct aa_error *err)
{
	const struct aa_shader_code *code = aa_shader_find(name);
	if (!code)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "shader '%s' is not embedded in this build", name);
	return make_module_code(gpu, code, out, err);
}

/* One stage into a pipeline's code digest: its SPIR-V and the specialization constants it is built with. */
static void digest_stage(struct aa_sha256 *h, const char *tag, const struct aa_shader_code *code,
			 const VkSpecializationInfo *spec)
{
	aa_sha256_update(h, tag, strlen(tag) + 1);
	uint64_t size = code ? code->size : 0;
	aa_sha256_update(h, &size, sizeof size);
	if (code)
		aa_sha256_update(h, code->words, code->size);
	uint32_t entries = spec ? spec->mapEntryCount : 0;
	aa_sha256_update(h, &entries, sizeof entries);
	for (uint32_t i = 0; i < entries; i++) {
		const VkSpecializationMapEntry *e = &spec->pMapEntries[i];
		uint32_t v[3] = {e->constantID, e->offset, (uint32_t)e->size};
		aa_sha256_update(h, v, sizeof v);
	}
	if (spec && spec->dataSize)
		aa_sha256_update(h, spec->pData, spec->dataSize);
}

int aa_gpu_layout_create(struct aa_gpu *gpu, const VkDescriptorType *types, const uint32_t *counts,
			 int binding_count, uint32_t push_size, struct aa_gpu_pipeline *out, struct aa_error *err)
{
	memset(out, 0, sizeof *out);
	VkDescriptorSetLayoutBinding b[16];
	if (binding_count > 16)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "at most 16 descriptor bindings");
	for (int i = 0; i < binding_count; i++)
		b[i] = (VkDescriptorSetLayoutBinding){
			.binding = (uint32_t)i,
			.descriptorType = types[i],
			.descriptorCount = counts ? counts[i] : 1,
			.stageFlags = VK_SHADER_STAGE_ALL,
		};
	VkDescriptorSetLayoutCreateInfo sci = {
		.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
		.bindingCount = (uint32_t)binding_count,
		.pBindings = b,
	};
	if (vkCreateDescriptorSetLayout(gpu->device, &sci, NULL, &out->set_layout) != VK_SUCCESS)
		return aa_error_set(err, AA_ERR_GPU, "", "vkCreateDescriptorSetLayout failed");
	VkPushConstantRange pr = {VK_SHADER_STAGE_ALL, 0, push_size};
	VkPipelineLayoutCreateInfo lci = {
		.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
		.setLayoutCount = 1,
		.pSetLayouts = &out->set_layout,
		.pushConstantRangeCount = push_size ? 1 : 0,
		.pPushConstantRanges = &pr,
	};
	if (vkCreatePipelineLayout(gpu->device, &lci, NULL, &out->layout) != VK_SUCCESS)
		return aa_error_set(err, AA_ERR_GPU, "", "vkCreatePipelineLayout failed");
	return 0;
}

int aa_gpu_graphics_pipeline_create(struct aa_gpu *gpu, const struct aa_gpu_graphics_desc *d,
				    struct aa_gpu_pipeline *p, struct aa_error *err)
{
	VkShaderModule vs = VK_NULL_HANDLE, fs = VK_NULL_HANDLE, gs = VK_NULL_HANDLE;
	struct aa_sha256 h;
	aa_sha256_init(&h);
	digest_stage(&h, "vert", aa_shader_find(d->vert), d->vert_specialization);
	digest_stage(&h, "geom", d->geom ? aa_shader_find(d->geom) : NULL, NULL);
	digest_stage(&h, "frag", d->frag_code ? d->frag_code : d->frag ? aa_shader_find(d->frag) : NULL,
		     d->frag_specialization);
	aa_sha256_final(&h, p->code_sha256);
	if (make_module(gpu, d->vert, &vs, err) ||
	    (d->frag_code ? make_module_code(gpu, d->frag_code, &fs, err) : d->frag && make_module(gpu, d->frag, &fs, err)) ||
	    (d->geom && make_module(gpu, d->geom, &gs, err))) {
		vkDestroyShaderModule(gpu->device, vs, NULL);
		vkDestroyShaderModule(gpu->device, fs, NULL);
		return -1;
	}
	VkPipelineShaderStageCreateInfo stages[3] = {
		{.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, .stage = VK_SHADER_STAGE_VERTEX_BIT,
		 .module = vs, .pName = "main", .pSpecializationInfo = d->vert_specialization},
	};
	uint32_t stage_count = 1;
	if (gs)
		stages[stage_count++] = (VkPipelineShaderStageCreateInfo){
			.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
			.stage = VK_SHADER_STAGE_GEOMETRY_BIT, .module = gs, .pName = "main"};
	if (fs)
		stages[stage_count++] = (VkPipelineShaderStageCreateInfo){
			.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
			.stage = VK_SHADER_STAGE_FRAGMENT_BIT, .module = fs, .pName = "main",
			.pSpecializationInfo = d->frag_specialization};
	VkVertexInputBindingDescription vb = {0, sizeof(struct aa_vertex), VK_VERTEX_INPUT_RATE_VERTEX};
	VkVertexInputAttributeDescription va[5] = {
		{0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(struct aa_vertex, position)},
		{1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(struct aa_vertex, normal)},
		{2, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(struct aa_vertex, uv)},
		{3, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(struct aa_vertex, tangent)},
		{4, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(struct aa_vertex, color)},
	};
	bool scene = d->vertex_layout == AA_VERTEX_SCENE;
	VkPipelineVertexInputStateCreateInfo vi = {
		.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO,
		.vertexBindingDescriptionCount = scene ? 1 : 0,
		.pVertexBindingDescriptions = &vb,
		.vertexAttributeDescriptionCount = scene ? 5 : 0,
		.pVertexAttributeDescriptions = va,
	};
	VkPipelineInputAssemblyStateCreateInfo ia = {
		.sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO,
		.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST,
	};
	VkPipelineViewportStateCreateInfo vp = {
		.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO,
		.viewportCount = 1,
		.scissorCount = 1,
	};
	bool bias = d->depth_bias_constant != 0.0f || d->depth_bias_slope != 0.0f;
	VkPipelineRasterizationStateCreateInfo rs = {
		.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO,
		.polygonMode = VK_POLYGON_MODE_FILL,
		.cullMode = d->cull,
		.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE,
		.depthBiasEnable = bias,
		.depthBiasConstantFactor = d->depth_bias_constant,
		.depthBiasSlopeFactor = d->depth_bias_slope,
		.lineWidth = 1.0f,
	};
	VkPipelineMultisampleStateCreateInfo ms = {
		.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO,
		.rasterizationSamples = (VkSampleCountFlagBits)(d->samples ? d->samples : 1),
	};
	VkPipelineDepthStencilStateCreateInfo ds = {
		.sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO,
		.depthTestEnable = d->depth_test,
		.depthWriteEnable = d->depth_write,
		.depthCompareOp = d->depth_always ? VK_COMPARE_OP_ALWAYS : VK_COMPARE_OP_GREATER_OR_EQUAL, /* reversed-Z */
	};
	VkPipelineColorBlendAttachmentState cb[AA_GPU_MAX_COLOR];
	for (int i = 0; i < AA_GPU_MAX_COLOR; i++) {
		cb[i] = (VkPipelineColorBlendAttachmentState){
			.blendEnable = d->blend == AA_BLEND_ADD,
			.srcColorBlendFactor = VK_BLEND_FACTOR_ONE,
			.dstColorBlendFactor = VK_BLEND_FACTOR_ONE,
			.colorBlendOp = VK_BLEND_OP_ADD,
			.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE,
			.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE,
			.alphaBlendOp = VK_BLEND_OP_ADD,
			.colorWriteMask = 0xf,
		};
		if (d->blend == AA_BLEND_ALPHA) {
			cb[i].blendEnable = i == 0;
			cb[i].srcColorBlendFactor = VK_BLEND_FACTOR_SRC_ALPHA;
			cb[i].dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
			cb[i].dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
			cb[i].colorWriteMask = i == 0 ? 0xf : 0;
		}
	}
	VkPipelineColorBlendStateCreateInfo blend = {
		.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO,
		.attachmentCount = (uint32_t)d->color_count,
		.pAttachments = cb,
	};
	VkDynamicState dyn[2] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
	VkPipelineDynamicStateCreateInfo dy = {
		.sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO,
		.dynamicStateCount = 2,
		.pDynamicStates = dyn,
	};
	VkGraphicsPipelineCreateInfo ci = {
		.sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO,
		.stageCount = stage_count,
		.pStages = stages,
		.pVertexInputState = &vi,
		.pInputAssemblyState = &ia,
		.pViewportState = &vp,
		.pRasterizationState = &rs,
		.pMultisampleState = &ms,
		.pDepthStencilState = &ds,
		.pColorBlendState = &blend,
		.pDynamicState = &dy,
		.layout = d->layout,
		.renderPass = d->render_pass,
	};
	VkResult vr = vkCreateGraphicsPipelines(gpu->device, VK_NULL_HANDLE, 1, &ci, NULL, &p->pipeline);
	vkDestroyShaderModule(gpu->device, vs, NULL);
	vkDestroyShaderModule(gpu->device, fs, NULL);
	vkDestroyShaderModule(gpu->device, gs, NULL);
	if (vr != VK_SUCCESS)
		return aa_error_set(err, AA_ERR_GPU, "", "cannot create the %s/%s pipeline (VkResult %d)", d->vert,
				    d->frag_code ? d->frag_code->name : d->frag ? d->frag : "-", vr);
	p->bind_point = VK_PIPELINE_BIND_POINT_GRAPHICS;
	return 0;
}

int aa_gpu_compute_pipeline_create(struct aa_gpu *gpu, const char *comp, struct aa_gpu_pipeline *p,
				   struct aa_error *err)
{
	VkShaderModule cs;
	struct aa_sha256 h;
	aa_sha256_init(&h);
	digest_stage(&h, "comp", aa_shader_find(comp), NULL);
	aa_sha256_final(&h, p->code_sha256);
	if (make_module(gpu, comp, &cs, err))
		return -1;
	VkComputePipelineCreateInfo ci = {
		.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
		.stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
			  .stage = VK_SHADER_STAGE_COMPUTE_BIT, .module = cs, .pName = "main"},
		.layout = p->layout,
	};
	VkResult vr = vkCreateComputePipelines(gpu->device, VK_NULL_HANDLE, 1, &ci, NULL, &p->pipeline);
	vkDestroyShaderModule(gpu->device, cs, NULL);
	if (vr != VK_SUCCESS)
		return aa_error_set(err, AA_ERR_GPU, "", "cannot create the %s pipeline (VkResult %d)", comp, vr);
	p->bind_point = VK_PIPELINE_BIND_POINT_COMPUTE;
	return 0;
}

void aa_gpu_pipeline_destroy(struct aa_gpu *gpu, struct aa_gpu_pipeline *p)
{
	if (!gpu->device)
		return;
	if (p->pipeline)
		vkDestroyPipeline(gpu->device, p->pipeline, NULL);
	if (p->layout)
		vkDestroyPipelineLayout(gpu->device, p->layout, NULL);
	if (p->set_layout)
		vkDestroyDescriptorSetLayout(gpu->device, p->set_layout, NULL);
	memset(p, 0, sizeof *p);
}

int aa_gpu_descriptor_pool_create(struct aa_gpu *gpu, uint32_t max_sets, VkDescriptorPool *out,
				  struct aa_error *err)
{
	VkDescriptorPoolSize sizes[] = {
		{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, max_sets * 24},
		{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, max_sets * 2},
		{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC, max_sets},
		{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, max_sets * 4},
		{VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, max_sets * 4},
	};
	VkDescriptorPoolCreateInfo ci = {
		.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
		.maxSets = max_sets,
		.poolSizeCount = 5,
		.pPoolSizes = sizes,
	};
	if (vkCreateDescriptorPool(gpu->device, &ci, NULL, out) != VK_SUCCESS)
		return aa_error_set(err, AA_ERR_GPU, "", "vkCreateDescriptorPool failed");
	return 0;
}

int aa_gpu_descriptor_set_alloc(struct aa_gpu *gpu, VkDescriptorPool pool, const struct aa_gpu_pipeline *p,
				VkDescriptorSet *out, struct aa_error *err)
{
	VkDescriptorSetAllocateInfo ai = {
		.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
		.descriptorPool = pool,
		.descriptorSetCount = 1,
		.pSetLayouts = &p->set_layout,
	};
	if (vkAllocateDescriptorSets(gpu->device, &ai, out) != VK_SUCCESS)
		return aa_error_set(err, AA_ERR_GPU, "", "vkAllocateDescriptorSets failed");
	return 0;
}

void aa_gpu_write_image(struct aa_gpu *gpu, VkDescriptorSet set, uint32_t binding, uint32_t element,
			VkDescriptorType type, VkSampler sampler, const struct aa_gpu_image *img,
			VkImageLayout layout)
{
	VkDescriptorImageInfo ii = {sampler, img->view, layout};
	VkWriteDescriptorSet w = {
		.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
		.dstSet = set,
		.dstBinding = binding,
		.dstArrayElement = element,
		.descriptorCount = 1,
		.descriptorType = type,
		.pImageInfo = &ii,
	};
	vkUpdateDescriptorSets(gpu->device, 1, &w, 0, NULL);
}

void aa_gpu_write_buffer(struct aa_gpu *gpu, VkDescriptorSet set, uint32_t binding, VkDescriptorType type,
			 const struct aa_gpu_buffer *buf)
{
	aa_gpu_write_buffer_range(gpu, set, binding, type, buf, VK_WHOLE_SIZE);
}

void aa_gpu_write_buffer_range(struct aa_gpu *gpu, VkDescriptorSet set, uint32_t binding, VkDescriptorType type,
			       const struct aa_gpu_buffer *buf, VkDeviceSize range)
{
	VkDescriptorBufferInfo bi = {buf->buffer, 0, range};
	VkWriteDescriptorSet w = {
		.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
		.dstSet = set,
		.dstBinding = binding,
		.descriptorCount = 1,
		.descriptorType = type,
		.pBufferInfo = &bi,
	};
	vkUpdateDescriptorSets(gpu->device, 1, &w, 0, NULL);
}
