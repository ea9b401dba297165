/* A compute pass: one compute shader, its own descriptor set of sampled images, storage images and
 * storage buffers (bindings 0..n-1 in the order given), push constants and specialization constants;
 * recorded as a direct dispatch or an indirect one whose group counts a previous pass wrote. */
#ifndef AA_COMPUTE_PASS_H
#define AA_COMPUTE_PASS_H

#include <stdint.h>

#include "gpu/gpu.h"

#define AA_COMPUTE_MAX_BINDINGS 13

enum aa_compute_binding_kind {
	AA_COMPUTE_SAMPLED,         /* sampler2D, nearest filtering: texelFetch */
	AA_COMPUTE_SAMPLED_LINEAR,  /* sampler2D, bilinear with clamp-to-edge */
	AA_COMPUTE_STORAGE_IMAGE,   /* image2D, read/write, GENERAL layout */
	AA_COMPUTE_STORAGE_BUFFER,  /* buffer block, the whole buffer */
};

struct aa_compute_binding {
	enum aa_compute_binding_kind kind;
	struct aa_gpu_image *image;   /* images: borrowed; layouts are tracked and transitioned here */
	struct aa_gpu_buffer *buffer; /* storage buffers: borrowed */
};

struct aa_compute_desc {
	const char *comp;             /* embedded shader name, e.g. "fxaa_cs_luma.comp" */
	const struct aa_shader_code *comp_code; /* instead of comp: SPIR-V made at run time (user methods) */
	int binding_count;
	struct aa_compute_binding bindings[AA_COMPUTE_MAX_BINDINGS];
	uint32_t push_size;           /* bytes of push constants the shader takes */
	const VkSpecializationInfo *specialization;
};

struct aa_compute_pass {
	struct aa_gpu_pipeline pipeline;
	VkDescriptorPool pool;
	VkDescriptorSet set;
	int binding_count;
	struct aa_compute_binding bindings[AA_COMPUTE_MAX_BINDINGS];
};

int aa_compute_pass_create(struct aa_gpu *gpu, struct aa_compute_pass *p, const struct aa_compute_desc *desc,
			   struct aa_error *err);
void aa_compute_pass_destroy(struct aa_gpu *gpu, struct aa_compute_pass *p);

/* Both record: layout transitions of the pass's images (sampled -> SHADER_READ_ONLY_OPTIMAL, storage ->
 * GENERAL), one full barrier so the pass sees everything recorded before it (writes of earlier passes,
 * buffer updates, indirect arguments), then the dispatch. push may be NULL when push_size is 0. */
void aa_compute_pass_dispatch(VkCommandBuffer cmd, struct aa_compute_pass *p, const void *push,
			      uint32_t push_size, uint32_t groups_x, uint32_t groups_y, uint32_t groups_z);
/* Group counts are read on the device from args (a VkDispatchIndirectCommand: three uint32) at offset;
 * the buffer needs VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT. */
void aa_compute_pass_dispatch_indirect(VkCommandBuffer cmd, struct aa_compute_pass *p, const void *push,
				       uint32_t push_size, const struct aa_gpu_buffer *args, VkDeviceSize offset);

/* Work groups of `local` invocations needed to cover `size` items. */
static inline uint32_t aa_compute_groups(int size, int local)
{
	return size <= 0 ? 0 : (uint32_t)((size + local - 1) / local);
}

#endif
