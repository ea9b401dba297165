/* Questions the renderer and the frame plan ask of a scene: where an object is at time t, and which
 * effects (motion, cut-outs, shadows) the scene calls for. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "scene/scene.h"

static vec3 f3(const float a[3])
{
	return v3(a[0], a[1], a[2]);
}

mat4 aa_object_model_matrix(const struct aa_object *object, double t)
{
	static const double world_origin[3] = {0, 0, 0};
	return aa_object_model_relative(object, t, world_origin);
}

mat4 aa_object_model_relative(const struct aa_object *object, double t, const double eye[3])
{
	const struct aa_animation *a = &object->animation;
	double move[3] = {0, 0, 0};
	mat4 m = object->transform;
	if (a->active && isfinite(t)) {
		/* Phases are reduced in double before going to float so long runs stay smooth. */
		double phase = fmod((double)a->oscillate_frequency * t, 1.0);
		double osc = a->oscillate_amplitude * sin(2.0 * 3.14159265358979323846 * phase);
		for (int k = 0; k < 3; k++)
			move[k] = (double)a->velocity[k] * t + (double)a->oscillate_axis[k] * osc;
		if (a->spin_degrees_per_second != 0.0f) {
			double deg = fmod((double)a->spin_degrees_per_second * t, 360.0);
			vec3 pivot = f3(a->pivot);
			mat4 spin = mat4_mul(mat4_translate(pivot),
					     mat4_mul(mat4_rotate(f3(a->spin_axis), (float)(deg * 3.14159265358979323846 / 180.0)),
						      mat4_translate(v3_scale(pivot, -1.0f))));
			m = mat4_mul(spin, m);
		}
	}
	vec3 offset = v3((float)(object->origin[0] + move[0] - eye[0]), (float)(object->origin[1] + move[1] - eye[1]),
			 (float)(object->origin[2] + move[2] - eye[2]));
	return mat4_mul(mat4_translate(offset), m);
}

void aa_camera_eye(const struct aa_camera *camera, double eye[3])
{
	eye[0] = camera->origin[0] + camera->position.x;
	eye[1] = camera->origin[1] + camera->position.y;
	eye[2] = camera->origin[2] + camera->position.z;
}

bool aa_object_is_animated(const struct aa_scene *scene, const struct aa_object *object)
{
	if (object->animation.active)
		return true;
	const struct aa_mesh *m = &scene->meshes[object->mesh_index];
	if (m->rig < 0 || object->pose.clip < 0 || object->pose.clip_speed == 0.0)
		return false;
	const struct aa_rig_clip *clip = &scene->rigs[m->rig].clips[object->pose.clip];
	return clip->channel_count > 0 && clip->duration > 0;
}

bool aa_scene_has_animation(const struct aa_scene *scene)
{
	for (int i = 0; i < scene->object_count; i++)
		if (aa_object_is_animated(scene, &scene->objects[i]))
			return true;
	return false;
}

void aa_scene_warn(struct aa_scene *scene, const char *fmt, ...)
{
	char msg[sizeof scene->warnings[0]];
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(msg, sizeof msg, fmt, ap);
	va_end(ap);
	for (int i = 0; i < scene->warning_count; i++)
		if (strcmp(scene->warnings[i], msg) == 0)
			return;
	if (scene->warning_count < AA_SCENE_MAX_WARNINGS)
		memcpy(scene->warnings[scene->warning_count++], msg, sizeof msg);
	else
		scene->warnings_dropped++;
}

bool aa_scene_has_cutout(const struct aa_scene *scene)
{
	for (int i = 0; i < scene->object_count; i++) {
		int m = scene->objects[i].material_index;
		if (m >= 0 && m < scene->material_count && scene->materials[m].alpha_cutout)
			return true;
	}
	return false;
}

bool aa_scene_has_shadow_caster_light(const struct aa_scene *scene)
{
	for (int i = 0; i < scene->light_count; i++)
		if (scene->lights[i].casts_shadow)
			return true;
	return false;
}

uint64_t aa_scene_triangle_count(const struct aa_scene *scene)
{
	uint64_t n = 0;
	for (int i = 0; i < scene->object_count; i++) {
		int m = scene->objects[i].mesh_index;
		if (m >= 0 && m < scene->mesh_count)
			n += scene->meshes[m].index_count / 3;
	}
	return n;
}

size_t aa_scene_bytes(const struct aa_scene *scene)
{
	size_t n = 0;
	for (int i = 0; i < scene->mesh_count; i++)
		n += (size_t)scene->meshes[i].vertex_count * sizeof(struct aa_vertex) +
		     (size_t)scene->meshes[i].index_count * sizeof(uint32_t);
	for (int i = 0; i < scene->texture_count; i++) {
		const struct aa_texture *t = &scene->textures[i];
		for (int l = 0; l < t->mip_levels; l++) {
			int w = t->width >> l, h = t->height >> l;
			n += (size_t)(w > 0 ? w : 1) * (size_t)(h > 0 ? h : 1) * 4;
		}
	}
	return n;
}

uint64_t aa_scene_new_uid(void)
{
	static uint64_t next;
	return __atomic_add_fetch(&next, 1, __ATOMIC_RELAXED);
}
