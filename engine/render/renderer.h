/* The renderer: a scene uploaded to the GPU, the scene and shadow passes, full-screen passes, and the
 * frame context methods render into. Methods use these functions and never see the scene's buffers. */
#ifndef AA_RENDERER_H
#define AA_RENDERER_H

#include <stdbool.h>

#include "render/frame_plan.h"
#include "gpu/gpu.h"
#include "types/job.h"
#include "scene/scene.h"
#include "render/scene_upload.h"
#include "render/shadow_fit.h"

struct aa_debug_targets;

#define AA_MAX_LIGHTS 8
#define AA_SCENE_COLOR_FORMAT VK_FORMAT_R16G16B16A16_SFLOAT
#define AA_DEPTH_FORMAT VK_FORMAT_D32_SFLOAT
#define AA_SHADOW_MAP_SIZE 2048 /* the atlas: AA_SHADOW_CASCADES maps of AA_SHADOW_TILE_SIZE^2 in a 2x2 grid (as many
				 * texels as one 2048^2 map: the shadow pass costs what one map over the scene did) */
#define AA_SHADOW_TILE_SIZE (AA_SHADOW_MAP_SIZE / 2)
/* 16 bits are ample over each cascade's tight depth range, and half the memory of 32 */
#define AA_SHADOW_FORMAT VK_FORMAT_D16_UNORM

/* std140 layout of `Frame` in shaders/common.glsl */
struct aa_frame_uniforms {
	float view_proj[16];
	float prev_view_proj[16];
	float shadow_view_proj[16];
	float ambient[4];
	float frame_size[4];
	float camera_planes[4];
	int32_t counts[4];
	struct {
		float position_type[4];
		float color_range[4];
		float shadow[4];
	} lights[AA_MAX_LIGHTS];
	float shadow_light_view[16];
	float shadow_cascade_scale[AA_SHADOW_CASCADES][4];  /* w: half a texel of the tile (uv clamp) */
	float shadow_cascade_offset[AA_SHADOW_CASCADES][4]; /* w: depth bias, a texel's depth */
	float shadow_splits[4];
	float camera_forward[4];
};

/* std140 `Material` */
struct aa_material_gpu {
	float base_color[4];
	float color2[4];
	float pattern[4];
	float shading[4];
	float emissive[4];           /* w: metallic */
	float maps[4];               /* x: normal scale, y: occlusion strength */
	float uv_rows[AA_MAP_COUNT * 2][4];
};

/* push constants `Draw` (128 bytes, the guaranteed minimum) */
struct aa_draw_push {
	float model[16];
	float normal_matrix[12];
	uint32_t material;
	uint32_t object_id;
	float jitter_ndc[2];
};

/* What a scene target holds beyond one colour sample and depth per pixel. Each distinct description is a
 * render pass + pipeline variant, created on first use and cached by the renderer. */
/* Extra per-pixel outputs of the G-buffer variant (gbuffer.vert/.frag), at fixed colour locations. */
enum aa_scene_output {
	AA_OUT_VELOCITY = 1u << 0, /* location 1, RG16F: screen motion in pixels since the previous frame,
				    * camera and object motion, without jitter; history is at p - velocity */
	AA_OUT_IDS = 1u << 1,      /* location 2, R32UI: the object's model_id (0 = background) */
	AA_OUT_POSITION = 1u << 2, /* location 3, RGBA32F: world position, w = 1 (0 = background) */
	AA_OUT_NORMAL = 1u << 3,   /* location 4, RGBA16F: geometric (triangle) normal, w = 1 */
	AA_OUT_SURFACE = 1u << 4,  /* location 5, RG32F: unlit luma (albedo), linear view depth */
};
#define AA_SCENE_OUTPUT_COUNT 5

struct aa_scene_target_desc {
	uint32_t samples;           /* 1, or a hardware MSAA count the device supports (resolved by box) */
	unsigned outputs;           /* AA_OUT_* bits: a G-buffer pass; only single-sample targets */
	bool depth_readable;        /* depth is stored and left sampleable (depth edge detection) */
	bool edge_distances;        /* GBAA: a geometry shader writes distances to triangle edges (RG16F) */
	uint32_t virtual_samples;   /* one rasterisation of an N-sample virtual MSAA pattern (2, 4 or 8; the
				     * standard positions): geometry is drawn jittered so that one position lands
				     * on the pixel centre, and colour and the alpha test are evaluated once per
				     * pixel and triangle at its shading point (shaders/shading_point.glsl), as
				     * hardware MSAA does; the target must be frame-sized */
	bool geometry_at_sample;    /* virtual G-buffer samples: position, normal and velocity stay at the
				     * sample (RSAA's subsamples); only colour and alpha use the shading point */
	bool alpha_to_coverage;     /* MSAA targets (samples > 1 or virtual): cut-out alpha is tested against the
				     * cutoff at each sample instead of once at the shading point */
	float texture_lod_bias;     /* added to every texture fetch's mip level (the reference: finer) */
	bool constant_colour;       /* the `floor` benchmark: the same geometry and depth test, no shading */
};

/* What a scene pipeline compiles in for one kind of material: shaders/shading.glsl's specialization
 * constants. llvmpipe executes every branch under a mask, so each class gets only its own paths. */
#define AA_MAX_MATERIAL_CLASSES 64
struct aa_material_class {
	uint32_t pattern;          /* AA_PATTERN_* */
	bool unlit, specular;
	/* materials from mesh files, and how the class is drawn */
	bool metal_rough, vertex_color, normal_map, metal_rough_map, occlusion_map, uv_transform;
	uint32_t emissive;         /* 0 none, 1 a colour, 2 a colour times a texture */
	bool blend;                /* alpha blended after the opaque objects, no depth writes */
	bool single_sided;         /* back faces culled */
	bool skinned;              /* velocity from the previous frame's skinned positions */
	bool opaque_used, cutout_used; /* drawn by an opaque object / a cut-out object with alpha test */
};

struct aa_scene_variant {
	struct aa_scene_target_desc desc;
	VkRenderPass pass;
	/* per material class (renderer.material_classes); borrow the renderer's scene layout */
	struct aa_gpu_pipeline opaque[AA_MAX_MATERIAL_CLASSES], cutout[AA_MAX_MATERIAL_CLASSES];
};

/* A colour + depth target the scene pass draws into. */
struct aa_scene_target {
	struct aa_gpu_image color, depth;
	struct aa_gpu_image resolved;  /* samples > 1: the box-resolved single-sample colour */
	struct aa_gpu_image edges;     /* edge_distances: RG16F signed distances in pixels */
	struct aa_gpu_image extra[AA_SCENE_OUTPUT_COUNT]; /* outputs: [i] for bit i (velocity, ids, ...) */
	struct aa_gpu_image *output;   /* resolved colour when multisampled, else &color */
	VkFramebuffer framebuffer;
	int width, height;
	int variant;
};

/* What a method needs to render one frame. */
struct aa_frame_ctx {
	int frame;                  /* frame index on the path */
	int ordinal;                /* 0..frames-1 within the job */
	double time;                /* seconds */
	bool cut;                   /* camera cut at this frame: reset history */
	int width, height;
	struct aa_camera camera;
	mat4 view, proj, view_proj; /* unjittered */
	mat4 prev_view_proj;        /* previous frame's, unjittered (= view_proj when there is none) */
	VkCommandBuffer cmd;
	struct aa_gpu_timer *timer;
	struct aa_gpu_image *output; /* set by the method: linear RGBA16F, width x height */
};

struct aa_renderer {
	struct aa_gpu *gpu;
	const struct aa_scene *scene;
	struct aa_frame_plan plan;
	int width, height;

	const struct aa_scene_upload *upload; /* the scene's buffers and textures, borrowed from the engine */
	struct aa_gpu_buffer frame_ubo;
	struct aa_gpu_image shadow_map;  /* AA_SHADOW_MAP_SIZE^2 when the plan has shadows, else 1x1 */
	VkFramebuffer shadow_framebuffer;
	VkRenderPass shadow_pass;
	struct aa_gpu_pipeline scene_layout;    /* layout of every scene and shadow pipeline */
	struct aa_scene_variant variants[24]; /* one per distinct target kind in the job */
	int variant_count;
	struct { VkFormat format[2]; int outputs; bool load; VkRenderPass pass; } color_passes[16]; /* by targets */
	int color_pass_count;
	struct aa_gpu_pipeline shadow_pipeline, shadow_cutout_pipeline;
	VkDescriptorPool pool;           /* the texture sets */
	VkDescriptorPool pass_pool;      /* the sets of the job's full-screen passes: reset for the next job */
	VkDescriptorSet *material_sets;  /* one per material: frame UBO, materials, its textures, shadow map */
	struct aa_material_class material_classes[AA_MAX_MATERIAL_CLASSES];
	int material_class_count;
	uint8_t *object_class;           /* per object: its material's class */
	int light_count, shadow_light;   /* lights in the frame uniforms; the one using the shadow map or -1 */
	uint32_t point_lights;           /* bit i: light i is a point light */
	struct aa_frame_uniforms uniforms;
	struct aa_gpu_buffer prev_models; /* per model_id - 1, previous frame's model matrix (host-visible) */
	mat4 *models;                    /* per object, this frame */
	mat4 shadow_view_proj;
	struct aa_shadow_fit shadow_fit; /* this frame's cascades */
	struct aa_box *bounds;           /* per object, this frame's world box */
	int *blend_order;                /* the blended objects, farthest first this frame */
	int blend_count;
	int *opaque_order;               /* every object, the one whose box ends nearest first this frame */
	/* skinned and animated mesh parts, posed on the CPU each frame: this frame's vertices (drawn instead of
	 * the uploaded ones) and the previous frame's positions (read by the G-buffer for velocity) */
	struct aa_gpu_buffer skinned_vertices, skinned_previous;
	int32_t *skin_offset;            /* per object: its first vertex in those buffers, -1 if not skinned */
	mat4 *joint_matrices;            /* scratch, the largest rig's joints */
	struct aa_vertex *skin_scratch;  /* scratch, the largest skinned part's vertices */
	bool inject_nonfinite;           /* stability tests: the next set_frame poisons some pixels */
	struct aa_debug_targets *debug_targets; /* job option debug_targets: the images made here are entered
						 * (engine/render/debug_targets.h); NULL when off */
};

int aa_renderer_create(struct aa_gpu *gpu, const struct aa_scene *scene, const struct aa_scene_upload *upload,
		       const struct aa_frame_plan *plan, int width, int height, struct aa_renderer **out,
		       struct aa_error *err);
void aa_renderer_destroy(struct aa_renderer *r);
/* Whether r, made for an earlier job, serves a job on the same uploaded scene, plan and size; a renderer
 * kept for reuse keeps its pipelines, which lavapipe would otherwise compile again for every job. */
bool aa_renderer_fits(const struct aa_renderer *r, const struct aa_scene *scene,
		      const struct aa_scene_upload *upload, const struct aa_frame_plan *plan, int width, int height);
/* Makes r ready for a new job (r fits it): the job's scene and plan; the passes' sets of the last job are
 * freed (every method and reference of that job must have been destroyed). */
void aa_renderer_reuse(struct aa_renderer *r, const struct aa_scene *scene, const struct aa_frame_plan *plan);

/* Sets the camera and object transforms for time t and writes the frame uniforms. Call before recording
 * a frame's command buffers (the uniform buffer is shared by everything recorded for the frame).
 * prev_camera/prev_t: the previous frame, for velocity; NULL (first frame, camera cut): no motion. */
void aa_renderer_set_frame(struct aa_renderer *r, const struct aa_camera *camera, double t,
			   const struct aa_camera *prev_camera, double prev_t, struct aa_frame_ctx *ctx);
/* Records the shadow-map pass (only when the plan has one). */
void aa_renderer_record_shadow(struct aa_renderer *r, VkCommandBuffer cmd);

/* Scene targets of any size; memory is added to info when not NULL. The plain form is one sample per
 * pixel; the _desc form takes the options above (desc NULL = plain). */
int aa_scene_target_create(struct aa_renderer *r, struct aa_scene_target *t, int width, int height,
			   const char *name, struct aa_method_result *info, struct aa_error *err);
int aa_scene_target_create_desc(struct aa_renderer *r, struct aa_scene_target *t, int width, int height,
				const struct aa_scene_target_desc *desc, const char *name,
				struct aa_method_result *info, struct aa_error *err);
void aa_scene_target_destroy(struct aa_renderer *r, struct aa_scene_target *t);
/* Draws the whole scene into t, with a sub-pixel jitter given in pixels of t (geometry moves by the
 * jitter). Leaves t->output (and edges, readable depth) in SHADER_READ_ONLY_OPTIMAL. */
void aa_renderer_draw_scene(struct aa_renderer *r, VkCommandBuffer cmd, struct aa_scene_target *t,
			    float jitter_x_px, float jitter_y_px);
/* Sorts order[0..count) (indices into bounds) so that the object whose box ends nearest to eye comes first,
 * ascending index on ties: the opaque draw order, which lets the early depth test reject the hidden parts
 * of large objects. Returns -1 (order unchanged) without memory for the keys. */
int aa_draw_order_front_to_back(const struct aa_box *bounds, int count, vec3 eye, int *order);

/* A full-screen pass: a fragment shader reads up to eight sampled images (bindings 0..7, in order) and
 * writes one colour target of any format, or two (a resolve that writes history and the displayed
 * image at once). Used by every post-process method. */
#define AA_PASS_MAX_SOURCES 8
struct aa_fullscreen_desc {
	const char *frag;
	const struct aa_shader_code *frag_code; /* instead of frag: SPIR-V made at run time (user methods) */
	int source_count;
	struct aa_gpu_image *sources[AA_PASS_MAX_SOURCES];
	bool linear[AA_PASS_MAX_SOURCES]; /* bilinear, clamp-to-edge sampling instead of nearest */
	struct aa_gpu_image *target;
	int outputs;                      /* colour locations the shader writes: 1 (0 means 1) or 2 */
	struct aa_gpu_image *second_target; /* location 1's target, same size; NULL drops its writes */
	bool accumulate;                  /* blend ONE+ONE into the kept contents (reference accumulation) */
	bool keep;                        /* keep the target's contents (no clear), e.g. with discard */
	uint32_t push_size;               /* bytes of push constants the shader takes */
	const VkSpecializationInfo *specialization;
};
struct aa_fullscreen_pass {
	struct aa_gpu_pipeline pipeline;
	VkDescriptorSet set;
	VkFramebuffer framebuffer;
	VkRenderPass render_pass;         /* borrowed from the renderer's cache */
	struct aa_gpu_image *target, *second_target;
	bool load;
};
int aa_fullscreen_pass_create(struct aa_renderer *r, struct aa_fullscreen_pass *p,
			      const struct aa_fullscreen_desc *desc, struct aa_error *err);
/* Records the pass; push may be NULL when push_size is 0. Leaves the target SHADER_READ_ONLY_OPTIMAL
 * (COLOR_ATTACHMENT_OPTIMAL for accumulate/keep passes). */
void aa_fullscreen_pass_record(struct aa_renderer *r, VkCommandBuffer cmd, struct aa_fullscreen_pass *p,
			       const void *push, uint32_t push_size);
void aa_fullscreen_pass_destroy(struct aa_renderer *r, struct aa_fullscreen_pass *p);
/* Inside a begun render pass: binds the pipeline and its one descriptor set, pushes the constants (when
 * push_size is not 0), draws the full-screen triangle and ends the pass. */
void aa_fullscreen_draw(VkCommandBuffer cmd, const struct aa_gpu_pipeline *pipeline, VkDescriptorSet set,
			const void *push, uint32_t push_size);

/* A single-subpass render pass writing `outputs` colour locations (1 or 2) of these formats (cached);
 * VK_FORMAT_UNDEFINED for location 1: no attachment, the shader's writes there are dropped. */
int aa_renderer_color_pass(struct aa_renderer *r, const VkFormat format[2], int outputs, bool load,
			   VkRenderPass *out, struct aa_error *err);
/* Creates a GPU image and records it in info->memory under `name`. */
int aa_renderer_image_create(struct aa_renderer *r, struct aa_gpu_image *img, int width, int height,
			     VkFormat format, VkImageUsageFlags usage, const char *name,
			     struct aa_method_result *info, struct aa_error *err);
void aa_method_result_add_memory(struct aa_method_result *info, const char *name, uint64_t bytes);

#endif
