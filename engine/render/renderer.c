/* The renderer: uploads a scene once, then records shadow, scene and full-screen passes for methods and
 * the reference. Only the passes in the frame plan are created or recorded. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render/debug_targets.h"
#include "gpu/sample_positions.h"
#include "render/renderer.h"

void aa_method_result_add_memory(struct aa_method_result *info, const char *name, uint64_t bytes)
{
	if (!info)
		return;
	if (info->memory_count < AA_MAX_MEMORY_ITEMS) {
		struct aa_memory_item *m = &info->memory[info->memory_count++];
		snprintf(m->name, sizeof m->name, "%s", name);
		m->bytes = bytes;
	}
	info->memory_bytes += bytes;
}

int aa_renderer_image_create(struct aa_renderer *r, struct aa_gpu_image *img, int width, int height,
			     VkFormat format, VkImageUsageFlags usage, const char *name,
			     struct aa_method_result *info, struct aa_error *err)
{
	usage = aa_debug_targets_usage(r->debug_targets, format, usage, 1);
	if (aa_gpu_image_create(r->gpu, img, width, height, format, usage, 1, 1, err))
		return -1;
	aa_method_result_add_memory(info, name, img->bytes);
	return aa_debug_targets_add(r->debug_targets, img, usage, name, err);
}

/* The shadow map, or a 1x1 cleared stand-in so the descriptor is always valid. */
static int create_shadow_map(struct aa_renderer *r, struct aa_error *err)
{
	int size = r->plan.shadow_map ? AA_SHADOW_MAP_SIZE : 1;
	if (aa_gpu_image_create(r->gpu, &r->shadow_map, size, size, AA_SHADOW_FORMAT,
				VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
				VK_IMAGE_USAGE_TRANSFER_DST_BIT, 1, 1, err))
		return -1;
	VkCommandBuffer cmd;
	if (aa_gpu_begin(r->gpu, &cmd, err))
		return -1;
	aa_gpu_image_barrier(cmd, &r->shadow_map, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
	VkClearDepthStencilValue zero = {0.0f, 0};
	VkImageSubresourceRange range = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, 0, 1};
	vkCmdClearDepthStencilImage(cmd, r->shadow_map.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero, 1,
				    &range);
	aa_gpu_image_barrier(cmd, &r->shadow_map, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
	if (aa_gpu_submit_wait(r->gpu, cmd, err))
		return -1;
	if (!r->plan.shadow_map)
		return 0;
	struct aa_gpu_pass_desc pd = {.depth_format = AA_SHADOW_FORMAT, .depth_readable = true, .samples = 1};
	struct aa_gpu_image *att[1] = {&r->shadow_map};
	return aa_gpu_render_pass_create(r->gpu, &pd, &r->shadow_pass, err) ||
	       aa_gpu_framebuffer_create(r->gpu, r->shadow_pass, att, 1, &r->shadow_framebuffer, err);
}

static int create_pipelines(struct aa_renderer *r, struct aa_error *err)
{
	struct aa_gpu *g = r->gpu;
	/* 0 frame, 1 material, 2 base texture, 3 shadow map, 4 previous models, 5-8 the file materials' maps
	 * (emissive, normal, metal-rough, occlusion), 9 previous skinned positions */
	VkDescriptorType types[10] = {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC,
				      VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
				      VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
				      VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
				      VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
				      VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
	if (aa_gpu_layout_create(g, types, NULL, 10, sizeof(struct aa_draw_push), &r->scene_layout, err))
		return -1;
	if (r->plan.shadow_map) {
		struct aa_gpu_graphics_desc sd = {
			.vert = "shadow.vert", .vertex_layout = AA_VERTEX_SCENE, .render_pass = r->shadow_pass,
			.samples = 1, .depth_test = true, .depth_write = true, .cull = VK_CULL_MODE_NONE,
			.layout = r->scene_layout.layout,
			/* reversed-Z: push stored depths away from the light (smaller) against acne */
			.depth_bias_constant = -2.0f, .depth_bias_slope = -2.0f,
		};
		if (aa_gpu_graphics_pipeline_create(g, &sd, &r->shadow_pipeline, err))
			return -1;
		if (r->plan.alpha_test) {
			sd.frag = "shadow_cutout.frag";
			if (aa_gpu_graphics_pipeline_create(g, &sd, &r->shadow_cutout_pipeline, err))
				return -1;
		}
	}
	return 0;
}

static const VkFormat scene_output_formats[AA_SCENE_OUTPUT_COUNT] = {
	VK_FORMAT_R16G16_SFLOAT,       /* velocity */
	VK_FORMAT_R32_UINT,            /* model ID */
	VK_FORMAT_R32G32B32A32_SFLOAT, /* world position */
	VK_FORMAT_R16G16B16A16_SFLOAT, /* geometric normal */
	VK_FORMAT_R32G32_SFLOAT,       /* unlit luma, linear depth */
};
static const char *const scene_output_names[AA_SCENE_OUTPUT_COUNT] = {
	"velocity", "model ids", "world position", "geometric normal", "unlit luma + depth",
};

/* Field by field: the struct has padding, which memcmp would compare too. */
static bool desc_equal(const struct aa_scene_target_desc *a, const struct aa_scene_target_desc *b)
{
	return a->samples == b->samples && a->outputs == b->outputs && a->depth_readable == b->depth_readable &&
	       a->edge_distances == b->edge_distances && a->virtual_samples == b->virtual_samples &&
	       a->geometry_at_sample == b->geometry_at_sample && a->alpha_to_coverage == b->alpha_to_coverage &&
	       a->texture_lod_bias == b->texture_lod_bias && a->constant_colour == b->constant_colour;
}

/* Specialization constants of the scene fragment shaders, one 4-byte value per constant_id in order: the
 * alpha test, the G-buffer's geometry_at_sample, the texture LOD bias, then shading_point.glsl's mode,
 * pattern size, alpha to coverage and the pattern's positions, then shading.glsl's material class and
 * the scene's lights (what each pipeline compiles in). IDs a shader lacks are ignored. */
#define SCENE_CONSTANT_COUNT 37
struct scene_constants {
	VkBool32 alpha_test, geometry_at_sample;
	float lod_bias;
	int32_t mode, pattern_samples;
	VkBool32 alpha_to_coverage;
	float pattern[16]; /* x0, y0, ... x7, y7 */
	uint32_t material_pattern;  /* 22: struct aa_material_class */
	VkBool32 unlit, specular;
	int32_t light_count;        /* 25: the frame uniforms' lights */
	uint32_t point_lights;
	int32_t shadow_light;
	VkBool32 metal_rough, vertex_color, normal_map; /* 28: file materials (struct aa_material_class) */
	int32_t emissive;
	VkBool32 metal_rough_map, occlusion_map, uv_transform, blend;
	VkBool32 skinned;           /* 36: gbuffer.vert, velocity of skinned parts */
};
_Static_assert(sizeof(struct scene_constants) == SCENE_CONSTANT_COUNT * 4, "one 4-byte value per constant");

static void scene_constants_fill(const struct aa_scene_target_desc *d, struct scene_constants *c,
				 VkSpecializationMapEntry *entries, VkSpecializationInfo *spec)
{
	memset(c, 0, sizeof *c);
	c->geometry_at_sample = d->geometry_at_sample;
	c->lod_bias = d->texture_lod_bias;
	c->mode = d->samples > 1 ? 1 : d->virtual_samples ? 2 : 0; /* SHADING_POINT_HARDWARE, _VIRTUAL */
	c->pattern_samples = d->samples > 1 ? (int32_t)d->samples : d->virtual_samples ? (int32_t)d->virtual_samples : 1;
	c->alpha_to_coverage = d->alpha_to_coverage;
	const float (*pos)[2] = aa_standard_sample_positions(c->pattern_samples);
	for (int i = 0; i < 8; i++) {
		c->pattern[2 * i] = pos && i < c->pattern_samples ? pos[i][0] : 0.5f;
		c->pattern[2 * i + 1] = pos && i < c->pattern_samples ? pos[i][1] : 0.5f;
	}
	for (uint32_t i = 0; i < SCENE_CONSTANT_COUNT; i++)
		entries[i] = (VkSpecializationMapEntry){i, 4 * i, 4};
	*spec = (VkSpecializationInfo){SCENE_CONSTANT_COUNT, entries, sizeof *c, c};
}

/* The render pass and pipelines of one kind of scene target, created on first use. */
static int scene_variant(struct aa_renderer *r, const struct aa_scene_target_desc *d, struct aa_error *err)
{
	for (int i = 0; i < r->variant_count; i++)
		if (desc_equal(&r->variants[i].desc, d))
			return i;
	if (r->variant_count == (int)(sizeof r->variants / sizeof r->variants[0]))
		return aa_error_set(err, AA_ERR_INTERNAL, "", "too many scene target kinds");
	if (d->samples > 1 && !(r->gpu->color_sample_counts & d->samples))
		return aa_error_set(err, AA_ERR_GPU, "", "the device cannot render %u samples per pixel", d->samples);
	if (d->outputs && (d->samples > 1 || d->edge_distances))
		return aa_error_set(err, AA_ERR_INTERNAL, "", "G-buffer outputs need a plain single-sample target");
	if (d->virtual_samples && (d->samples > 1 || d->edge_distances || d->virtual_samples > 8 ||
				   !aa_standard_sample_positions((int)d->virtual_samples)))
		return aa_error_set(err, AA_ERR_INTERNAL, "", "virtual samples: a single-sample target and 2, 4 or 8 "
				    "positions");
	struct aa_scene_variant *v = &r->variants[r->variant_count];
	memset(v, 0, sizeof *v);
	v->desc = *d;
	struct aa_gpu_pass_desc pass = {
		.color_count = d->edge_distances ? 2 : 1,
		.color_formats = {AA_SCENE_COLOR_FORMAT, VK_FORMAT_R16G16_SFLOAT},
		.depth_format = AA_DEPTH_FORMAT, .depth_readable = d->depth_readable,
		.samples = d->samples, .resolve = d->samples > 1,
	};
	if (d->outputs) {
		pass.color_count = 1 + AA_SCENE_OUTPUT_COUNT;
		for (int i = 0; i < AA_SCENE_OUTPUT_COUNT; i++)
			pass.color_formats[1 + i] = (d->outputs & (1u << i)) ? scene_output_formats[i]
									     : VK_FORMAT_UNDEFINED;
	}
	if (aa_gpu_render_pass_create(r->gpu, &pass, &v->pass, err))
		return -1;
	struct scene_constants constants;
	VkSpecializationMapEntry entries[SCENE_CONSTANT_COUNT];
	VkSpecializationInfo spec;
	scene_constants_fill(d, &constants, entries, &spec);
	constants.light_count = r->light_count;
	constants.point_lights = r->point_lights;
	constants.shadow_light = r->shadow_light;
	const char *geom = d->edge_distances ? "gbaa.geom" : NULL;
	if (d->virtual_samples) /* the barycentric coordinates shading_point.glsl tests coverage with */
		geom = d->outputs ? "virtual_sample_gbuffer.geom" : "virtual_sample.geom";
	struct aa_gpu_graphics_desc g = {
		.vert = d->outputs ? "gbuffer.vert" : "scene.vert",
		.frag = d->outputs ? "gbuffer.frag" : d->edge_distances ? "gbaa.frag"
			: d->constant_colour ? "floor.frag" : "scene.frag",
		.geom = geom, .vertex_layout = AA_VERTEX_SCENE,
		.render_pass = v->pass, .color_count = pass.color_count, .samples = d->samples ? d->samples : 1,
		.depth_test = true, .depth_write = true, .cull = VK_CULL_MODE_NONE,
		.layout = r->scene_layout.layout, .frag_specialization = &spec,
	};
	for (int c = 0; c < r->material_class_count; c++) {
		const struct aa_material_class *mc = &r->material_classes[c];
		constants.material_pattern = mc->pattern;
		constants.unlit = mc->unlit;
		constants.specular = mc->specular;
		constants.metal_rough = mc->metal_rough;
		constants.vertex_color = mc->vertex_color;
		constants.normal_map = mc->normal_map;
		constants.emissive = (int32_t)mc->emissive;
		constants.metal_rough_map = mc->metal_rough_map;
		constants.occlusion_map = mc->occlusion_map;
		constants.uv_transform = mc->uv_transform;
		constants.blend = mc->blend;
		constants.skinned = mc->skinned;
		struct aa_gpu_graphics_desc gc = g;
		gc.cull = mc->single_sided ? VK_CULL_MODE_BACK_BIT : VK_CULL_MODE_NONE;
		gc.vert_specialization = mc->skinned ? &spec : NULL;
		if (mc->blend) { /* over what is drawn, into the colour only, without hiding what lies behind */
			gc.blend = AA_BLEND_ALPHA;
			gc.depth_write = false;
		}
		constants.alpha_test = VK_FALSE;
		if (mc->opaque_used && aa_gpu_graphics_pipeline_create(r->gpu, &gc, &v->opaque[c], err))
			return -1;
		constants.alpha_test = VK_TRUE;
		if (mc->cutout_used && aa_gpu_graphics_pipeline_create(r->gpu, &gc, &v->cutout[c], err))
			return -1;
	}
	return r->variant_count++;
}

/* One set per material: the frame, the materials (at the material's dynamic offset), its textures (white
 * where it has none: never sampled, its class does not compile the fetch in), the shadow map and the
 * previous frame's models and skinned positions. */
static int create_descriptors(struct aa_renderer *r, struct aa_error *err)
{
	const struct aa_scene *s = r->scene;
	int n = s->material_count > 0 ? s->material_count : 1;
	if (aa_gpu_descriptor_pool_create(r->gpu, (uint32_t)n, &r->pool, err) ||
	    aa_gpu_descriptor_pool_create(r->gpu, 256, &r->pass_pool, err))
		return -1;
	r->material_sets = calloc((size_t)n, sizeof *r->material_sets);
	if (!r->material_sets)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	for (int i = 0; i < n; i++) {
		if (aa_gpu_descriptor_set_alloc(r->gpu, r->pool, &r->scene_layout, &r->material_sets[i], err))
			return -1;
		VkDescriptorSet set = r->material_sets[i];
		const struct aa_material *m = i < s->material_count ? &s->materials[i] : NULL;
		aa_gpu_write_buffer(r->gpu, set, 0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, &r->frame_ubo);
		aa_gpu_write_buffer_range(r->gpu, set, 1, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC, &r->upload->materials,
					  sizeof(struct aa_material_gpu));
		static const uint32_t map_binding[AA_MAP_COUNT] = {2, 5, 6, 7, 8};
		for (int k = 0; k < AA_MAP_COUNT; k++) {
			int t = m ? (k == AA_MAP_BASE ? (m->pattern == AA_PATTERN_TEXTURE ? m->texture_index : -1) : m->maps[k])
				  : -1;
			if (t < 0 || t >= s->texture_count)
				t = s->texture_count; /* the white stand-in */
			aa_gpu_write_image(r->gpu, set, map_binding[k], 0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
					   r->gpu->sampler_linear, &r->upload->textures[t], VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
		}
		aa_gpu_write_image(r->gpu, set, 3, 0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
				   r->gpu->sampler_shadow, &r->shadow_map, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
		aa_gpu_write_buffer(r->gpu, set, 4, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &r->prev_models);
		aa_gpu_write_buffer(r->gpu, set, 9, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &r->skinned_previous);
	}
	return 0;
}

/* Whether two classes compile the same pipelines (what they are used for aside). */
static bool class_equal(const struct aa_material_class *a, const struct aa_material_class *b)
{
	return a->pattern == b->pattern && a->unlit == b->unlit && a->specular == b->specular &&
	       a->metal_rough == b->metal_rough && a->vertex_color == b->vertex_color && a->normal_map == b->normal_map &&
	       a->metal_rough_map == b->metal_rough_map && a->occlusion_map == b->occlusion_map &&
	       a->uv_transform == b->uv_transform && a->emissive == b->emissive && a->blend == b->blend &&
	       a->single_sided == b->single_sided && a->skinned == b->skinned;
}

/* The scene's lights as the frame uniforms hold them, and the material classes its objects draw with. */
static int classify_scene(struct aa_renderer *r, struct aa_error *err)
{
	const struct aa_scene *s = r->scene;
	r->shadow_light = -1;
	r->light_count = s->light_count < AA_MAX_LIGHTS ? s->light_count : AA_MAX_LIGHTS;
	for (int i = 0; i < r->light_count; i++) {
		const struct aa_light *l = &s->lights[i];
		bool point = l->type == AA_LIGHT_POINT;
		if (point)
			r->point_lights |= 1u << i;
		if (r->plan.shadow_map && r->shadow_light < 0 && l->casts_shadow && !point)
			r->shadow_light = i;
	}
	r->object_class = calloc((size_t)(s->object_count ? s->object_count : 1), sizeof *r->object_class);
	if (!r->object_class)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	for (int o = 0; o < s->object_count; o++) {
		const struct aa_material *m = &s->materials[s->objects[o].material_index];
		struct aa_material_class key = {0};
		key.pattern = (uint32_t)m->pattern;
		key.unlit = m->unlit;
		key.specular = m->specular > 0.0f;
		key.metal_rough = m->model == AA_SHADING_METAL_ROUGH;
		key.vertex_color = m->vertex_color;
		key.normal_map = m->maps[AA_MAP_NORMAL] >= 0 && !m->unlit;
		key.emissive = m->unlit ? 0 : m->maps[AA_MAP_EMISSIVE] >= 0 ? 2
			       : (m->emissive[0] > 0 || m->emissive[1] > 0 || m->emissive[2] > 0) ? 1 : 0;
		key.metal_rough_map = key.metal_rough && m->maps[AA_MAP_METAL_ROUGH] >= 0;
		key.occlusion_map = m->maps[AA_MAP_OCCLUSION] >= 0 && !m->unlit;
		key.uv_transform = m->uv_transformed;
		key.blend = m->blend;
		key.single_sided = m->single_sided;
		key.skinned = s->meshes[s->objects[o].mesh_index].skin != NULL;
		int c = 0;
		while (c < r->material_class_count && !class_equal(&r->material_classes[c], &key))
			c++;
		if (c == r->material_class_count) {
			if (c == AA_MAX_MATERIAL_CLASSES)
				return aa_error_set(err, AA_ERR_LIMIT, "", "the scene's materials need more than %d different "
						    "shader variants (pattern, unlit, specular, maps, blend, sides, skin)",
						    AA_MAX_MATERIAL_CLASSES);
			r->material_classes[r->material_class_count++] = key;
		}
		if (m->alpha_cutout && r->plan.alpha_test && !m->blend)
			r->material_classes[c].cutout_used = true;
		else
			r->material_classes[c].opaque_used = true;
		r->object_class[o] = (uint8_t)c;
	}
	return 0;
}

/* Buffers for the parts posed on the CPU: each skinned object gets its own run of vertices (objects sharing
 * a mesh may be posed differently). A scene without skins gets a 16-byte stand-in for the descriptor. */
static int create_skinning(struct aa_renderer *r, struct aa_error *err)
{
	const struct aa_scene *s = r->scene;
	size_t total = 0, largest = 1;
	int joints = 1;
	if (!(r->skin_offset = calloc((size_t)(s->object_count ? s->object_count : 1), sizeof *r->skin_offset)))
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	for (int o = 0; o < s->object_count; o++) {
		const struct aa_mesh *m = &s->meshes[s->objects[o].mesh_index];
		r->skin_offset[o] = -1;
		if (!m->skin)
			continue;
		r->skin_offset[o] = (int32_t)total;
		total += m->vertex_count;
		largest = m->vertex_count > largest ? m->vertex_count : largest;
		if (m->rig >= 0 && s->rigs[m->rig].joint_count > joints)
			joints = s->rigs[m->rig].joint_count;
	}
	if (total > INT32_MAX / 2)
		return aa_error_set(err, AA_ERR_LIMIT, "", "too many skinned vertices");
	r->joint_matrices = calloc((size_t)joints, sizeof *r->joint_matrices);
	r->skin_scratch = calloc(largest, sizeof *r->skin_scratch);
	if (!r->joint_matrices || !r->skin_scratch)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	return aa_gpu_buffer_create(r->gpu, &r->skinned_vertices, (total ? total : 1) * sizeof(struct aa_vertex),
				    VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, true, err) ||
	       aa_gpu_buffer_create(r->gpu, &r->skinned_previous, (total ? total : 1) * 4 * sizeof(float),
				    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true, err);
}

int aa_renderer_create(struct aa_gpu *gpu, const struct aa_scene *scene, const struct aa_scene_upload *upload,
		       const struct aa_frame_plan *plan, int width, int height, struct aa_renderer **out,
		       struct aa_error *err)
{
	struct aa_renderer *r = calloc(1, sizeof *r);
	if (!r)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	r->gpu = gpu;
	r->scene = scene;
	r->upload = upload;
	r->plan = *plan;
	r->width = width;
	r->height = height;
	size_t objects = (size_t)(scene->object_count ? scene->object_count : 1);
	int models = scene->model_count > 0 ? scene->model_count : scene->object_count;
	r->models = calloc(objects, sizeof *r->models);
	r->bounds = calloc(objects, sizeof *r->bounds);
	r->blend_order = calloc(objects, sizeof *r->blend_order);
	r->opaque_order = calloc(objects, sizeof *r->opaque_order);
	if (!r->models || !r->bounds || !r->blend_order || !r->opaque_order ||
	    aa_gpu_buffer_create(gpu, &r->frame_ubo, sizeof(struct aa_frame_uniforms),
				 VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true, err) ||
	    aa_gpu_buffer_create(gpu, &r->prev_models, sizeof(mat4) * (VkDeviceSize)(models > 0 ? models : 1),
				 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true, err) ||
	    create_skinning(r, err) || classify_scene(r, err) || create_shadow_map(r, err) ||
	    create_pipelines(r, err) || create_descriptors(r, err)) {
		if (!r->models || !r->bounds || !r->blend_order || !r->opaque_order)
			aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
		aa_renderer_destroy(r);
		return -1;
	}
	*out = r;
	return 0;
}

void aa_renderer_destroy(struct aa_renderer *r)
{
	if (!r)
		return;
	struct aa_gpu *g = r->gpu;
	vkDeviceWaitIdle(g->device);
	aa_gpu_pipeline_destroy(g, &r->shadow_cutout_pipeline);
	aa_gpu_pipeline_destroy(g, &r->shadow_pipeline);
	/* variant pipelines borrow the scene layout, so they own only their VkPipeline */
	for (int i = 0; i < r->variant_count; i++) {
		for (int c = 0; c < r->material_class_count; c++) {
			aa_gpu_pipeline_destroy(g, &r->variants[i].opaque[c]);
			aa_gpu_pipeline_destroy(g, &r->variants[i].cutout[c]);
		}
		vkDestroyRenderPass(g->device, r->variants[i].pass, NULL);
	}
	aa_gpu_pipeline_destroy(g, &r->scene_layout);
	if (r->pool)
		vkDestroyDescriptorPool(g->device, r->pool, NULL);
	if (r->pass_pool)
		vkDestroyDescriptorPool(g->device, r->pass_pool, NULL);
	if (r->shadow_pass)
		vkDestroyRenderPass(g->device, r->shadow_pass, NULL);
	for (int i = 0; i < r->color_pass_count; i++)
		vkDestroyRenderPass(g->device, r->color_passes[i].pass, NULL);
	if (r->shadow_framebuffer)
		vkDestroyFramebuffer(g->device, r->shadow_framebuffer, NULL);
	aa_gpu_image_destroy(g, &r->shadow_map);
	aa_gpu_buffer_destroy(g, &r->frame_ubo);
	aa_gpu_buffer_destroy(g, &r->prev_models);
	aa_gpu_buffer_destroy(g, &r->skinned_vertices);
	aa_gpu_buffer_destroy(g, &r->skinned_previous);
	free(r->material_sets);
	free(r->models);
	free(r->bounds);
	free(r->blend_order);
	free(r->opaque_order);
	free(r->skin_offset);
	free(r->joint_matrices);
	free(r->skin_scratch);
	free(r->object_class);
	free(r);
}

bool aa_renderer_fits(const struct aa_renderer *r, const struct aa_scene *scene,
		      const struct aa_scene_upload *upload, const struct aa_frame_plan *plan, int width, int height)
{
	/* the renderer's own objects depend on the plan only through these two */
	return r->upload == upload && upload->scene_uid == scene->uid && r->width == width &&
	       r->height == height && r->plan.shadow_map == plan->shadow_map &&
	       r->plan.alpha_test == plan->alpha_test;
}

void aa_renderer_reuse(struct aa_renderer *r, const struct aa_scene *scene, const struct aa_frame_plan *plan)
{
	r->scene = scene; /* the same scene (same uid), perhaps another copy of it */
	r->plan = *plan;
	r->inject_nonfinite = false;
	vkResetDescriptorPool(r->gpu->device, r->pass_pool, 0);
}

static void push_object(struct aa_renderer *r, VkCommandBuffer cmd, int o, float jx, float jy)
{
	struct aa_draw_push push;
	memset(&push, 0, sizeof push);
	mat4 model = r->models[o], inv;
	memcpy(push.model, model.m, sizeof push.model);
	if (mat4_invert(model, &inv) != 0)
		inv = mat4_identity();
	mat4 nt = mat4_transpose(inv);
	for (int c = 0; c < 3; c++)
		for (int k = 0; k < 3; k++)
			push.normal_matrix[c * 4 + k] = nt.m[c * 4 + k];
	push.material = (uint32_t)r->scene->objects[o].material_index;
	push.object_id = r->scene->objects[o].model_id;
	push.jitter_ndc[0] = jx;
	push.jitter_ndc[1] = jy;
	vkCmdPushConstants(cmd, r->scene_layout.layout, VK_SHADER_STAGE_ALL, 0, sizeof push, &push);
}

/* Draws one object: its material's set at the material's offset, its transform, its mesh from the
 * uploaded vertices or, posed this frame, from the skinned ones. *bound tracks the vertex buffer. */
static void draw_object(struct aa_renderer *r, VkCommandBuffer cmd, int o, float jx, float jy, uint32_t instance,
			VkBuffer *bound)
{
	const struct aa_object *obj = &r->scene->objects[o];
	VkDescriptorSet set = r->material_sets[obj->material_index];
	uint32_t material_offset = (uint32_t)(obj->material_index * r->upload->material_stride);
	vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, r->scene_layout.layout, 0, 1, &set, 1,
				&material_offset);
	push_object(r, cmd, o, jx, jy);
	const struct aa_mesh *m = &r->scene->meshes[obj->mesh_index];
	bool skinned = r->skin_offset[o] >= 0;
	VkBuffer vertices = skinned ? r->skinned_vertices.buffer : r->upload->vertices.buffer;
	if (vertices != *bound) {
		VkDeviceSize zero = 0;
		vkCmdBindVertexBuffers(cmd, 0, 1, &vertices, &zero);
		*bound = vertices;
	}
	vkCmdDrawIndexed(cmd, m->index_count, 1, r->upload->mesh_first_index[obj->mesh_index],
			 skinned ? r->skin_offset[o] : (int32_t)r->upload->mesh_vertex_offset[obj->mesh_index], instance);
}

/* Draws every object: opaque ones first, cut-outs with the discard pipelines after them, each in
 * opaque_order (the nearest first, so that the early depth test rejects more of what they hide), then the
 * blended ones from the farthest (both sorted each frame). opaque and cutout hold one pipeline per material class, or
 * with classes 0 one for all objects: the shadow map, where instance is the cascade, blended objects
 * cast no shadow and visible[o] false skips an object outside the cascade. */
static void draw_objects(struct aa_renderer *r, VkCommandBuffer cmd, const struct aa_gpu_pipeline *opaque,
			 const struct aa_gpu_pipeline *cutout, int classes, float jx, float jy, uint32_t instance,
			 const bool *visible)
{
	VkBuffer bound = VK_NULL_HANDLE;
	vkCmdBindIndexBuffer(cmd, r->upload->indices.buffer, 0, VK_INDEX_TYPE_UINT32);
	for (int pass = 0; pass < 3; pass++) {
		VkPipeline pipeline = VK_NULL_HANDLE;
		int count = pass == 2 ? (classes > 0 ? r->blend_count : 0) : r->scene->object_count;
		for (int k = 0; k < count; k++) {
			int o = pass == 2 ? r->blend_order[k] : r->opaque_order[k];
			const struct aa_object *obj = &r->scene->objects[o];
			const struct aa_material *mat = &r->scene->materials[obj->material_index];
			int c = classes > 0 ? r->object_class[o] : 0;
			bool is_cutout = mat->alpha_cutout && !mat->blend && cutout && cutout[c].pipeline;
			if ((pass < 2 && (mat->blend || is_cutout != (pass == 1))) || (visible && !visible[o]))
				continue;
			const struct aa_gpu_pipeline *p = is_cutout ? &cutout[c] : &opaque[c];
			if (!p->pipeline)
				continue;
			if (p->pipeline != pipeline) {
				vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p->pipeline);
				pipeline = p->pipeline;
			}
			draw_object(r, cmd, o, jx, jy, instance, &bound);
		}
	}
}

/* The cascades, each drawn into its quarter of the atlas with only the objects over its window. */
void aa_renderer_record_shadow(struct aa_renderer *r, VkCommandBuffer cmd)
{
	if (!r->plan.shadow_map)
		return;
	VkClearValue clear = {.depthStencil = {0.0f, 0}};
	/* only the tiles of the cascades in use are cleared and drawn: the shader never reads past the last
	 * (its split is infinite) */
	int count = r->shadow_fit.cascade_count;
	aa_gpu_begin_pass(cmd, r->shadow_pass, r->shadow_framebuffer, count > 1 ? AA_SHADOW_MAP_SIZE : AA_SHADOW_TILE_SIZE,
			  count > 2 ? AA_SHADOW_MAP_SIZE : AA_SHADOW_TILE_SIZE, &clear, 1);
	bool *visible = malloc((size_t)(r->scene->object_count ? r->scene->object_count : 1) * sizeof *visible);
	for (int i = 0; i < r->shadow_fit.cascade_count && visible; i++) {
		VkViewport viewport = {(float)((i & 1) * AA_SHADOW_TILE_SIZE), (float)((i >> 1) * AA_SHADOW_TILE_SIZE),
				       AA_SHADOW_TILE_SIZE, AA_SHADOW_TILE_SIZE, 0.0f, 1.0f};
		VkRect2D scissor = {{(i & 1) * AA_SHADOW_TILE_SIZE, (i >> 1) * AA_SHADOW_TILE_SIZE},
				    {AA_SHADOW_TILE_SIZE, AA_SHADOW_TILE_SIZE}};
		vkCmdSetViewport(cmd, 0, 1, &viewport);
		vkCmdSetScissor(cmd, 0, 1, &scissor);
		for (int o = 0; o < r->scene->object_count; o++)
			visible[o] = aa_shadow_cascade_sees(&r->shadow_fit, i, &r->bounds[o]);
		draw_objects(r, cmd, &r->shadow_pipeline, &r->shadow_cutout_pipeline, 0, 0.0f, 0.0f, (uint32_t)i, visible);
	}
	free(visible);
	vkCmdEndRenderPass(cmd);
	r->shadow_map.layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
}

int aa_scene_target_create(struct aa_renderer *r, struct aa_scene_target *t, int width, int height,
			   const char *name, struct aa_method_result *info, struct aa_error *err)
{
	return aa_scene_target_create_desc(r, t, width, height, NULL, name, info, err);
}

static int target_image(struct aa_renderer *r, struct aa_gpu_image *img, int width, int height, VkFormat format,
			VkImageUsageFlags usage, uint32_t samples, const char *name, const char *what,
			struct aa_method_result *info, struct aa_error *err)
{
	char label[48];
	snprintf(label, sizeof label, "%s %s", name, what);
	usage = aa_debug_targets_usage(r->debug_targets, format, usage, samples);
	if (aa_gpu_image_create(r->gpu, img, width, height, format, usage, samples, 1, err))
		return -1;
	aa_method_result_add_memory(info, label, img->bytes);
	return aa_debug_targets_add(r->debug_targets, img, usage, label, err);
}

int aa_scene_target_create_desc(struct aa_renderer *r, struct aa_scene_target *t, int width, int height,
				const struct aa_scene_target_desc *desc, const char *name,
				struct aa_method_result *info, struct aa_error *err)
{
	memset(t, 0, sizeof *t);
	struct aa_scene_target_desc d = desc ? *desc : (struct aa_scene_target_desc){0};
	if (d.samples == 0)
		d.samples = 1;
	t->width = width;
	t->height = height;
	t->variant = scene_variant(r, &d, err);
	if (t->variant < 0)
		return -1;
	VkImageUsageFlags color_usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
					VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
	VkImageUsageFlags depth_usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT |
					(d.depth_readable ? VK_IMAGE_USAGE_SAMPLED_BIT : 0);
	struct aa_gpu_image *att[4 + AA_SCENE_OUTPUT_COUNT];
	int n = 0;
	if (target_image(r, &t->color, width, height, AA_SCENE_COLOR_FORMAT,
			 d.samples > 1 ? VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT : color_usage,
			 d.samples, name,
			 d.samples > 1 ? "colour samples" : "colour", info, err))
		return -1;
	att[n++] = &t->color;
	if (d.edge_distances) {
		if (target_image(r, &t->edges, width, height, VK_FORMAT_R16G16_SFLOAT, color_usage, 1, name,
				 "edge distances", info, err))
			return -1;
		att[n++] = &t->edges;
	}
	for (int i = 0; i < AA_SCENE_OUTPUT_COUNT; i++) {
		if (!(d.outputs & (1u << i)))
			continue;
		if (target_image(r, &t->extra[i], width, height, scene_output_formats[i],
				 color_usage & ~(VkImageUsageFlags)VK_IMAGE_USAGE_TRANSFER_SRC_BIT, 1, name,
				 scene_output_names[i], info, err))
			return -1;
		att[n++] = &t->extra[i];
	}
	if (target_image(r, &t->depth, width, height, AA_DEPTH_FORMAT, depth_usage, d.samples, name,
			 d.samples > 1 ? "depth samples" : "depth", info, err))
		return -1;
	att[n++] = &t->depth;
	t->output = &t->color;
	if (d.samples > 1) {
		if (target_image(r, &t->resolved, width, height, AA_SCENE_COLOR_FORMAT, color_usage, 1, name,
				 "resolved colour", info, err))
			return -1;
		att[n++] = &t->resolved;
		t->output = &t->resolved;
	}
	return aa_gpu_framebuffer_create(r->gpu, r->variants[t->variant].pass, att, n, &t->framebuffer, err);
}

void aa_scene_target_destroy(struct aa_renderer *r, struct aa_scene_target *t)
{
	if (t->framebuffer)
		vkDestroyFramebuffer(r->gpu->device, t->framebuffer, NULL);
	aa_gpu_image_destroy(r->gpu, &t->color);
	aa_gpu_image_destroy(r->gpu, &t->depth);
	aa_gpu_image_destroy(r->gpu, &t->resolved);
	aa_gpu_image_destroy(r->gpu, &t->edges);
	for (int i = 0; i < AA_SCENE_OUTPUT_COUNT; i++)
		aa_gpu_image_destroy(r->gpu, &t->extra[i]);
	memset(t, 0, sizeof *t);
}

void aa_renderer_draw_scene(struct aa_renderer *r, VkCommandBuffer cmd, struct aa_scene_target *t,
			    float jitter_x_px, float jitter_y_px)
{
	const struct aa_scene_variant *v = &r->variants[t->variant];
	const float *bg = r->scene->background;
	/* attachment order: colour, [edges], [outputs], depth, [resolve] */
	VkClearValue clears[4 + AA_SCENE_OUTPUT_COUNT];
	int n = 0;
	clears[n++] = (VkClearValue){.color = {.float32 = {bg[0], bg[1], bg[2], 1.0f}}};
	if (v->desc.edge_distances) /* (0.5, 0.5): no edge in this pixel (GBAA's "nothing to blend") */
		clears[n++] = (VkClearValue){.color = {.float32 = {0.5f, 0.5f, 0.0f, 0.0f}}};
	for (int i = 0; i < AA_SCENE_OUTPUT_COUNT; i++)
		if (v->desc.outputs & (1u << i)) /* background: no motion, id 0, w 0, depth at the far plane */
			clears[n++] = (VkClearValue){.color = {.float32 = {0.0f, i == 4 ? r->uniforms.camera_planes[1]
										      : 0.0f, 0.0f, 0.0f}}};
	clears[n++] = (VkClearValue){.depthStencil = {0.0f, 0}}; /* reversed-Z: far is 0 */
	clears[n++] = (VkClearValue){.color = {.float32 = {0, 0, 0, 0}}};
	aa_gpu_begin_pass(cmd, v->pass, t->framebuffer, t->width, t->height, clears, n);
	/* NDC spans 2 units over the target: a jitter of j pixels is 2j/size in NDC. */
	draw_objects(r, cmd, v->opaque, v->cutout, r->material_class_count, 2.0f * jitter_x_px / t->width,
		     2.0f * jitter_y_px / t->height, 0, NULL);
	vkCmdEndRenderPass(cmd);
	t->color.layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
	t->resolved.layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
	t->edges.layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
	for (int i = 0; i < AA_SCENE_OUTPUT_COUNT; i++)
		t->extra[i].layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
	t->depth.layout = v->desc.depth_readable ? VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL
						 : VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
}

int aa_renderer_color_pass(struct aa_renderer *r, const VkFormat format[2], int outputs, bool load,
			   VkRenderPass *out, struct aa_error *err)
{
	VkFormat second = outputs > 1 ? format[1] : VK_FORMAT_UNDEFINED;
	for (int i = 0; i < r->color_pass_count; i++)
		if (r->color_passes[i].format[0] == format[0] && r->color_passes[i].format[1] == second &&
		    r->color_passes[i].outputs == outputs && r->color_passes[i].load == load) {
			*out = r->color_passes[i].pass;
			return 0;
		}
	if (r->color_pass_count == (int)(sizeof r->color_passes / sizeof r->color_passes[0]))
		return aa_error_set(err, AA_ERR_INTERNAL, "", "too many colour pass formats");
	struct aa_gpu_pass_desc d = {.color_count = outputs, .color_formats = {format[0], second},
				     .color_load = {load, load}, .samples = 1};
	if (aa_gpu_render_pass_create(r->gpu, &d, out, err))
		return -1;
	r->color_passes[r->color_pass_count].format[0] = format[0];
	r->color_passes[r->color_pass_count].format[1] = second;
	r->color_passes[r->color_pass_count].outputs = outputs;
	r->color_passes[r->color_pass_count].load = load;
	r->color_passes[r->color_pass_count++].pass = *out;
	return 0;
}

int aa_fullscreen_pass_create(struct aa_renderer *r, struct aa_fullscreen_pass *p,
			      const struct aa_fullscreen_desc *d, struct aa_error *err)
{
	memset(p, 0, sizeof *p);
	p->target = d->target;
	p->second_target = d->outputs > 1 ? d->second_target : NULL;
	p->load = d->accumulate || d->keep;
	int outputs = d->outputs > 1 ? 2 : 1;
	VkFormat formats[2] = {d->target->format, p->second_target ? p->second_target->format : VK_FORMAT_UNDEFINED};
	VkDescriptorType types[AA_PASS_MAX_SOURCES];
	for (int i = 0; i < d->source_count; i++)
		types[i] = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
	if (aa_renderer_color_pass(r, formats, outputs, p->load, &p->render_pass, err) ||
	    aa_gpu_layout_create(r->gpu, types, NULL, d->source_count, d->push_size, &p->pipeline, err))
		return -1;
	struct aa_gpu_graphics_desc g = {
		.vert = "fullscreen.vert", .frag = d->frag, .frag_code = d->frag_code, .vertex_layout = AA_VERTEX_NONE,
		.render_pass = p->render_pass, .color_count = outputs, .samples = 1, .cull = VK_CULL_MODE_NONE,
		.blend = d->accumulate ? AA_BLEND_ADD : AA_BLEND_NONE, .layout = p->pipeline.layout,
		.frag_specialization = d->specialization,
	};
	struct aa_gpu_image *att[2] = {d->target, p->second_target};
	if (aa_gpu_graphics_pipeline_create(r->gpu, &g, &p->pipeline, err) ||
	    aa_gpu_descriptor_set_alloc(r->gpu, r->pass_pool, &p->pipeline, &p->set, err) ||
	    aa_gpu_framebuffer_create(r->gpu, p->render_pass, att, p->second_target ? 2 : 1, &p->framebuffer, err))
		return -1;
	for (int i = 0; i < d->source_count; i++)
		aa_gpu_write_image(r->gpu, p->set, (uint32_t)i, 0, types[i],
				   d->linear[i] ? r->gpu->sampler_linear_clamp : r->gpu->sampler_nearest,
				   d->sources[i], VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
	return 0;
}

void aa_fullscreen_draw(VkCommandBuffer cmd, const struct aa_gpu_pipeline *pipeline, VkDescriptorSet set,
			const void *push, uint32_t push_size)
{
	vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline->pipeline);
	vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline->layout, 0, 1, &set, 0, NULL);
	if (push_size)
		vkCmdPushConstants(cmd, pipeline->layout, VK_SHADER_STAGE_ALL, 0, push_size, push);
	vkCmdDraw(cmd, 3, 1, 0, 0);
	vkCmdEndRenderPass(cmd);
}

void aa_fullscreen_pass_record(struct aa_renderer *r, VkCommandBuffer cmd, struct aa_fullscreen_pass *p,
			       const void *push, uint32_t push_size)
{
	(void)r;
	struct aa_gpu_image *targets[2] = {p->target, p->second_target};
	int count = p->second_target ? 2 : 1;
	for (int i = 0; i < count; i++)
		if (p->load && targets[i]->layout != VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL)
			aa_gpu_image_barrier(cmd, targets[i], VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
	VkClearValue clear[2] = {{.color = {.float32 = {0, 0, 0, 0}}}, {.color = {.float32 = {0, 0, 0, 0}}}};
	aa_gpu_begin_pass(cmd, p->render_pass, p->framebuffer, p->target->width, p->target->height, clear, count);
	aa_fullscreen_draw(cmd, &p->pipeline, p->set, push, push_size);
	for (int i = 0; i < count; i++)
		targets[i]->layout = p->load ? VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL
					     : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
}

void aa_fullscreen_pass_destroy(struct aa_renderer *r, struct aa_fullscreen_pass *p)
{
	if (p->framebuffer)
		vkDestroyFramebuffer(r->gpu->device, p->framebuffer, NULL);
	aa_gpu_pipeline_destroy(r->gpu, &p->pipeline);
	memset(p, 0, sizeof *p);
}
