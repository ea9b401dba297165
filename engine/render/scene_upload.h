/* A scene's data on the GPU: geometry, materials and textures, uploaded once and shared by every job
 * that renders the scene (the engine keeps them in a cache by scene identity and byte budget). */
#ifndef AA_SCENE_UPLOAD_H
#define AA_SCENE_UPLOAD_H

#include "gpu/gpu.h"
#include "scene/scene.h"

struct aa_scene_upload {
	uint64_t scene_uid;              /* aa_scene.uid of the scene this holds */
	struct aa_gpu *gpu;
	struct aa_gpu_buffer vertices, indices, materials;
	VkDeviceSize material_stride;    /* bytes from one material to the next (a dynamic offset's alignment) */
	struct aa_gpu_image *textures;   /* scene->texture_count, plus white at [texture_count] */
	int texture_count;
	uint32_t *mesh_first_index, *mesh_vertex_offset;
	uint64_t bytes;                  /* GPU memory held */
	uint64_t last_used;              /* for least-recently-used eviction */
};

int aa_scene_upload_create(struct aa_gpu *gpu, const struct aa_scene *scene, struct aa_scene_upload **out,
			   struct aa_error *err);
void aa_scene_upload_destroy(struct aa_scene_upload *up);

#endif
