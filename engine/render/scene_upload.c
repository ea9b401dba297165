/* Uploads a scene's meshes (one vertex and one index buffer), materials and textures (with their CPU mip
 * chains, plus a white stand-in) to the GPU. */
#include <stdlib.h>
#include <string.h>

#include "render/renderer.h"
#include "render/scene_upload.h"

static int upload_geometry(struct aa_scene_upload *r, const struct aa_scene *s, struct aa_error *err)
{
	size_t nv = 0, ni = 0;
	for (int i = 0; i < s->mesh_count; i++) {
		nv += s->meshes[i].vertex_count;
		ni += s->meshes[i].index_count;
	}
	if (nv == 0 || ni == 0)
		return aa_error_set(err, AA_ERR_INVALID, "objects", "the scene has no geometry to draw");
	struct aa_vertex *v = malloc(nv * sizeof *v);
	uint32_t *idx = malloc(ni * sizeof *idx);
	r->mesh_first_index = calloc((size_t)s->mesh_count, sizeof(uint32_t));
	r->mesh_vertex_offset = calloc((size_t)s->mesh_count, sizeof(uint32_t));
	if (!v || !idx || !r->mesh_first_index || !r->mesh_vertex_offset) {
		free(v);
		free(idx);
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory uploading the scene");
	}
	size_t ov = 0, oi = 0;
	for (int i = 0; i < s->mesh_count; i++) {
		const struct aa_mesh *m = &s->meshes[i];
		r->mesh_vertex_offset[i] = (uint32_t)ov;
		r->mesh_first_index[i] = (uint32_t)oi;
		memcpy(v + ov, m->vertices, m->vertex_count * sizeof *v);
		memcpy(idx + oi, m->indices, m->index_count * sizeof *idx);
		ov += m->vertex_count;
		oi += m->index_count;
	}
	int rc = aa_gpu_buffer_upload(r->gpu, &r->vertices, v, nv * sizeof *v, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT,
				      err);
	if (rc == 0)
		rc = aa_gpu_buffer_upload(r->gpu, &r->indices, idx, ni * sizeof *idx,
					  VK_BUFFER_USAGE_INDEX_BUFFER_BIT, err);
	free(v);
	free(idx);
	return rc;
}

/* One aa_material_gpu per material at material_stride bytes, bound per draw as a uniform buffer at the
 * material's dynamic offset (the stride keeps every offset at the device's alignment). */
static int upload_materials(struct aa_scene_upload *r, const struct aa_scene *s, struct aa_error *err)
{
	int n = s->material_count > 0 ? s->material_count : 1;
	VkDeviceSize align = r->gpu->properties.limits.minUniformBufferOffsetAlignment;
	if (align < 1)
		align = 1;
	r->material_stride = (sizeof(struct aa_material_gpu) + align - 1) / align * align;
	uint8_t *bytes = calloc((size_t)n, (size_t)r->material_stride);
	if (!bytes)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	for (int i = 0; i < s->material_count; i++) {
		const struct aa_material *m = &s->materials[i];
		struct aa_material_gpu *g = (struct aa_material_gpu *)(bytes + (size_t)i * r->material_stride);
		memcpy(g->base_color, m->base_color, sizeof g->base_color);
		memcpy(g->color2, m->color2, 3 * sizeof(float));
		g->color2[3] = (float)m->pattern;
		g->pattern[0] = m->scale[0];
		g->pattern[1] = m->scale[1];
		g->pattern[2] = m->stripe_width;
		g->shading[0] = m->specular;
		g->shading[1] = m->roughness;
		g->shading[2] = m->alpha_cutoff;
		g->shading[3] = (float)((m->alpha_cutout ? 1 : 0) | (m->unlit ? 2 : 0) | (m->vertex_color ? 4 : 0));
		memcpy(g->emissive, m->emissive, sizeof m->emissive);
		g->emissive[3] = m->metallic;
		g->maps[0] = m->normal_scale;
		g->maps[1] = m->occlusion_strength;
		for (int k = 0; k < AA_MAP_COUNT; k++) {
			memcpy(g->uv_rows[2 * k], m->uv_transform[k], 3 * sizeof(float));
			memcpy(g->uv_rows[2 * k + 1], m->uv_transform[k] + 3, 3 * sizeof(float));
		}
	}
	int rc = aa_gpu_buffer_upload(r->gpu, &r->materials, bytes, (VkDeviceSize)n * r->material_stride,
				      VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, err);
	free(bytes);
	return rc;
}

static int upload_textures(struct aa_scene_upload *r, const struct aa_scene *s, struct aa_error *err)
{
	r->textures = calloc((size_t)s->texture_count + 1, sizeof *r->textures);
	if (!r->textures)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	VkImageUsageFlags usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
	for (int i = 0; i < s->texture_count; i++) {
		const struct aa_texture *t = &s->textures[i];
		/* colour is stored sRGB-encoded; normal, roughness and occlusion maps are data, read as stored */
		VkFormat format = t->linear ? VK_FORMAT_R8G8B8A8_UNORM : VK_FORMAT_R8G8B8A8_SRGB;
		if (aa_gpu_image_create(r->gpu, &r->textures[i], t->width, t->height, format, usage,
					1, (uint32_t)t->mip_levels, err) ||
		    aa_gpu_image_upload_rgba8(r->gpu, &r->textures[i], (const uint8_t *const *)t->mips, err))
			return -1;
	}
	static const uint8_t white[4] = {255, 255, 255, 255};
	const uint8_t *levels[1] = {white};
	struct aa_gpu_image *w = &r->textures[s->texture_count];
	if (aa_gpu_image_create(r->gpu, w, 1, 1, VK_FORMAT_R8G8B8A8_SRGB, usage, 1, 1, err) ||
	    aa_gpu_image_upload_rgba8(r->gpu, w, levels, err))
		return -1;
	return 0;
}

int aa_scene_upload_create(struct aa_gpu *gpu, const struct aa_scene *scene, struct aa_scene_upload **out,
			   struct aa_error *err)
{
	struct aa_scene_upload *up = calloc(1, sizeof *up);
	if (!up)
		return aa_error_set(err, AA_ERR_INTERNAL, "", "out of memory");
	up->gpu = gpu;
	up->scene_uid = scene->uid;
	up->texture_count = scene->texture_count;
	if (upload_geometry(up, scene, err) || upload_materials(up, scene, err) || upload_textures(up, scene, err)) {
		aa_scene_upload_destroy(up);
		return -1;
	}
	up->bytes = up->vertices.size + up->indices.size + up->materials.size;
	for (int i = 0; i <= up->texture_count; i++)
		up->bytes += up->textures[i].bytes;
	*out = up;
	return 0;
}

void aa_scene_upload_destroy(struct aa_scene_upload *up)
{
	if (!up)
		return;
	if (up->textures)
		for (int i = 0; i <= up->texture_count; i++)
			aa_gpu_image_destroy(up->gpu, &up->textures[i]);
	aa_gpu_buffer_destroy(up->gpu, &up->vertices);
	aa_gpu_buffer_destroy(up->gpu, &up->indices);
	aa_gpu_buffer_destroy(up->gpu, &up->materials);
	free(up->textures);
	free(up->mesh_first_index);
	free(up->mesh_vertex_offset);
	free(up);
}
