/* The GPU layer: Vulkan instance/device on whatever ICD is present, images, buffers, render passes,
 * pipelines, timestamp queries and readback, behind a few well-named functions. Methods speak in images
 * and passes; the Vulkan details stay here. */
#ifndef AA_GPU_H
#define AA_GPU_H

#include <stdatomic.h>
#include <stdbool.h>
#include <stdint.h>

#include <vulkan/vulkan.h>

#include "util/error.h"

struct aa_gpu_image;

struct aa_gpu {
	VkInstance instance;
	VkPhysicalDevice physical;
	VkDevice device;
	VkQueue queue;
	uint32_t queue_family;
	VkCommandPool command_pool;
	VkPhysicalDeviceProperties properties;
	VkPhysicalDeviceMemoryProperties memory_properties;
	VkDebugUtilsMessengerEXT messenger;
	bool validation;
	int validation_errors;
	uint32_t timestamp_valid_bits;
	double timestamp_period_ns;
	VkSampleCountFlags color_sample_counts; /* supported for RGBA16F + D32F attachments */
	char driver_info[256];
	char driver_build[256];  /* the driver's name and build ("llvmpipe Mesa 22.3.6 (LLVM 15.0.6)"), or "" */
	VkSampler sampler_nearest, sampler_linear, sampler_linear_clamp, sampler_shadow;
	/* called by aa_gpu_image_destroy before an image goes (job option debug_targets: its registry
	 * forgets the image); NULL otherwise */
	void (*image_destroyed)(void *user, const struct aa_gpu_image *img);
	void *image_destroyed_user;
	/* set by whoever runs jobs (aa_engine_set_interrupt), else NULL: non-zero asks the job on this device
	 * to stop before its next piece of GPU work (aa_gpu_interrupted) */
	const atomic_int *interrupt; /* lock-free: a signal handler may set it */
};

/* -1 with AA_ERR_CANCELLED when the job was asked to stop: called between the bounded pieces of a job's
 * GPU work (a reference batch, a method's render or repeat, a warm-up), never inside one. */
int aa_gpu_interrupted(const struct aa_gpu *gpu, struct aa_error *err);

/* device_select: NULL/"" = first device (or $AALAB_DEVICE), a decimal index, or a substring of the
 * device name. validation: enable VK_LAYER_KHRONOS_validation when it is installed. */
int aa_gpu_create(struct aa_gpu *gpu, const char *device_select, bool validation, struct aa_error *err);
void aa_gpu_destroy(struct aa_gpu *gpu);

struct aa_gpu_image {
	VkImage image;
	VkDeviceMemory memory;
	VkImageView view;
	VkFormat format;
	VkImageAspectFlags aspect;
	int width, height;
	uint32_t samples, mip_levels;
	VkImageLayout layout; /* tracked by aa_gpu_image_barrier */
	uint64_t bytes;       /* allocation size */
};

int aa_gpu_image_create(struct aa_gpu *gpu, struct aa_gpu_image *img, int width, int height, VkFormat format,
			VkImageUsageFlags usage, uint32_t samples, uint32_t mip_levels, struct aa_error *err);
void aa_gpu_image_destroy(struct aa_gpu *gpu, struct aa_gpu_image *img);
/* Transitions the whole image to new_layout, with a full read/write dependency (simple and correct;
 * lavapipe gains nothing from finer stages). */
void aa_gpu_image_barrier(VkCommandBuffer cmd, struct aa_gpu_image *img, VkImageLayout new_layout);
/* Execution + memory barrier for everything before vs. everything after (compute <-> graphics). */
void aa_gpu_full_barrier(VkCommandBuffer cmd);

struct aa_gpu_buffer {
	VkBuffer buffer;
	VkDeviceMemory memory;
	VkDeviceSize size;
	void *mapped; /* host-visible buffers stay mapped */
};

int aa_gpu_buffer_create(struct aa_gpu *gpu, struct aa_gpu_buffer *buf, VkDeviceSize size,
			 VkBufferUsageFlags usage, bool host_visible, struct aa_error *err);
void aa_gpu_buffer_destroy(struct aa_gpu *gpu, struct aa_gpu_buffer *buf);
/* Creates a device-local buffer filled with data (through a staging copy). */
int aa_gpu_buffer_upload(struct aa_gpu *gpu, struct aa_gpu_buffer *buf, const void *data, VkDeviceSize size,
			 VkBufferUsageFlags usage, struct aa_error *err);
/* Uploads mip levels of an RGBA8 image (levels[i] tightly packed) and leaves it SHADER_READ_ONLY. Other
 * formats (RG8, R8, RGBA32F) work too: the texel size comes from img->format. */
int aa_gpu_image_upload_rgba8(struct aa_gpu *gpu, struct aa_gpu_image *img, const uint8_t *const *levels,
			      struct aa_error *err);

/* One-shot command buffers. */
int aa_gpu_begin(struct aa_gpu *gpu, VkCommandBuffer *cmd, struct aa_error *err);
int aa_gpu_submit_wait(struct aa_gpu *gpu, VkCommandBuffer cmd, struct aa_error *err); /* frees cmd */

/* Readback: records a copy of a single-sample colour image into a host buffer (created/grown as
 * needed); after submit_wait the pixels are in buf->mapped, tightly packed. */
int aa_gpu_record_readback(struct aa_gpu *gpu, VkCommandBuffer cmd, struct aa_gpu_image *img,
			   struct aa_gpu_buffer *buf, struct aa_error *err);
uint32_t aa_gpu_format_bytes(VkFormat format);

/* Render passes and framebuffers: `color_count` colour attachments (cleared or loaded), an optional
 * depth attachment (cleared), all with `samples` samples; optional single-sample resolve targets for the
 * colour attachments when samples > 1. Final layouts: colour -> SHADER_READ_ONLY_OPTIMAL (loaded colour
 * attachments start and stay COLOR_ATTACHMENT_OPTIMAL, for accumulation),
 * depth -> DEPTH_STENCIL_ATTACHMENT_OPTIMAL (or SHADER_READ_ONLY if depth_readable). */
#define AA_GPU_MAX_COLOR 8
struct aa_gpu_pass_desc {
	int color_count;         /* colour locations; a location with VK_FORMAT_UNDEFINED has no attachment */
	VkFormat color_formats[AA_GPU_MAX_COLOR];
	bool color_load[AA_GPU_MAX_COLOR]; /* keep existing contents instead of clearing */
	VkFormat depth_format;   /* VK_FORMAT_UNDEFINED: none */
	bool depth_readable;
	bool depth_load, depth_store; /* keep the depth from an earlier pass / for a later pass (attachment
				       * layout throughout; depth_readable ends in the sampled layout) */
	uint32_t samples;
	bool resolve;
};
int aa_gpu_render_pass_create(struct aa_gpu *gpu, const struct aa_gpu_pass_desc *desc, VkRenderPass *out,
			      struct aa_error *err);
int aa_gpu_framebuffer_create(struct aa_gpu *gpu, VkRenderPass pass, struct aa_gpu_image *const *attachments,
			      int count, VkFramebuffer *out, struct aa_error *err);
/* Begins a render pass over the framebuffer's full area; clear values in attachment order. Callers set
 * the images' tracked layouts to the pass's final layouts after vkCmdEndRenderPass. */
void aa_gpu_begin_pass(VkCommandBuffer cmd, VkRenderPass pass, VkFramebuffer fb, int width, int height,
		       const VkClearValue *clears, int clear_count);

/* Pipelines. Shaders are SPIR-V words embedded at build time (shader_table.c). */
struct aa_shader_code {
	const char *name;
	const uint32_t *words;
	size_t size; /* bytes */
};
const struct aa_shader_code *aa_shader_find(const char *name); /* "scene.vert" */
/* Tests: pipelines made from now on get code instead of the embedded SPIR-V of `name` (NULL: the
 * embedded again). At most a few names at once; returns -1 when full. */
int aa_shader_substitute(const char *name, const struct aa_shader_code *code);

/* ALPHA: "over" into colour attachment 0 (straight alpha); every other attachment keeps what it holds
 * (a G-buffer keeps the surface behind a blended one). */
enum aa_blend { AA_BLEND_NONE, AA_BLEND_ADD, AA_BLEND_ALPHA };
enum aa_vertex_layout { AA_VERTEX_NONE /* full-screen triangle from gl_VertexIndex */, AA_VERTEX_SCENE };

struct aa_gpu_graphics_desc {
	const char *vert, *frag;     /* shader names; frag may be NULL (depth only) */
	const struct aa_shader_code *frag_code; /* instead of frag: SPIR-V made at run time (user methods) */
	const char *geom;            /* optional geometry shader */
	enum aa_vertex_layout vertex_layout;
	VkRenderPass render_pass;
	int color_count;
	uint32_t samples;
	bool depth_test, depth_write; /* reversed-Z: compare GREATER_OR_EQUAL */
	bool depth_always;            /* compare ALWAYS instead (a mask drawn over its clear value) */
	VkCullModeFlags cull;
	enum aa_blend blend;
	float depth_bias_constant, depth_bias_slope;
	VkPipelineLayout layout;
	const VkSpecializationInfo *frag_specialization;
	const VkSpecializationInfo *vert_specialization; /* optional */
};

struct aa_gpu_pipeline {
	VkPipeline pipeline;
	VkPipelineLayout layout;      /* owned when created by aa_gpu_layout_create */
	VkDescriptorSetLayout set_layout;
	VkPipelineBindPoint bind_point;
	uint8_t code_sha256[32];      /* the SPIR-V of its stages and their specialization constants: what of
				       * its pixels the GPU code decides (stored references are keyed by it) */
};

/* A pipeline layout with one descriptor set of `binding_count` bindings (types[i], counts[i] descriptors,
 * visible to all stages) and push constants of push_size bytes (all stages). */
int aa_gpu_layout_create(struct aa_gpu *gpu, const VkDescriptorType *types, const uint32_t *counts,
			 int binding_count, uint32_t push_size, struct aa_gpu_pipeline *out, struct aa_error *err);
int aa_gpu_graphics_pipeline_create(struct aa_gpu *gpu, const struct aa_gpu_graphics_desc *desc,
				    struct aa_gpu_pipeline *p, struct aa_error *err);
int aa_gpu_compute_pipeline_create(struct aa_gpu *gpu, const char *comp, struct aa_gpu_pipeline *p,
				   struct aa_error *err);
void aa_gpu_pipeline_destroy(struct aa_gpu *gpu, struct aa_gpu_pipeline *p);

/* Descriptor sets come from one pool per owner; write helpers take a binding and the resource. */
int aa_gpu_descriptor_pool_create(struct aa_gpu *gpu, uint32_t max_sets, VkDescriptorPool *out,
				  struct aa_error *err);
int aa_gpu_descriptor_set_alloc(struct aa_gpu *gpu, VkDescriptorPool pool, const struct aa_gpu_pipeline *p,
				VkDescriptorSet *out, struct aa_error *err);
void aa_gpu_write_image(struct aa_gpu *gpu, VkDescriptorSet set, uint32_t binding, uint32_t element,
			VkDescriptorType type, VkSampler sampler, const struct aa_gpu_image *img,
			VkImageLayout layout);
void aa_gpu_write_buffer(struct aa_gpu *gpu, VkDescriptorSet set, uint32_t binding, VkDescriptorType type,
			 const struct aa_gpu_buffer *buf);
/* The first `range` bytes of buf: a dynamic uniform buffer, moved over buf by the offset given at bind. */
void aa_gpu_write_buffer_range(struct aa_gpu *gpu, VkDescriptorSet set, uint32_t binding, VkDescriptorType type,
			       const struct aa_gpu_buffer *buf, VkDeviceSize range);

/* Timestamps around passes. Start stamps are written at BOTTOM_OF_PIPE followed by an execution barrier,
 * because lavapipe only flushes queued work before non-TOP_OF_PIPE stamps (lavapipe-costs.md, trap 1). */
#define AA_GPU_TIMER_MAX 512
struct aa_gpu_timer {
	VkQueryPool pool;
	uint32_t used;
	struct { char name[32]; uint32_t begin, end; } spans[AA_GPU_TIMER_MAX / 2];
	int span_count;
};
int aa_gpu_timer_create(struct aa_gpu *gpu, struct aa_gpu_timer *t, struct aa_error *err);
void aa_gpu_timer_destroy(struct aa_gpu *gpu, struct aa_gpu_timer *t);
void aa_gpu_timer_reset(VkCommandBuffer cmd, struct aa_gpu_timer *t);   /* before the first span */
int aa_gpu_timer_begin(VkCommandBuffer cmd, struct aa_gpu_timer *t, const char *name); /* returns span */
void aa_gpu_timer_end(VkCommandBuffer cmd, struct aa_gpu_timer *t, int span);
/* After the command buffer completed: ms of each span (ms has span_count entries). */
int aa_gpu_timer_read(struct aa_gpu *gpu, struct aa_gpu_timer *t, double *ms, struct aa_error *err);

double aa_now_ms(void); /* CLOCK_MONOTONIC */

#endif
