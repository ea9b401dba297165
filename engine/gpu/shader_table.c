/* The SPIR-V of every shader, compiled from shaders/ at build time and embedded: nothing is looked up
 * on disk at run time. Adding a shader adds it to SHADER_SOURCES in Makefile.am and one line here. */
#include <stdint.h>
#include <string.h>

#include "gpu.h"

#include "scene.vert.h"
#include "scene.frag.h"
#include "shadow.vert.h"
#include "shadow_cutout.frag.h"
#include "fullscreen.vert.h"
#include "resolve_box.frag.h"
#include "accumulate.frag.h"
#include "copy.frag.h"

#define SHADER(file, array) {file, array, sizeof array}

static const struct aa_shader_code shaders[] = {
	SHADER("scene.vert", spv_scene_vert),
	SHADER("scene.frag", spv_scene_frag),
	SHADER("shadow.vert", spv_shadow_vert),
	SHADER("shadow_cutout.frag", spv_shadow_cutout_frag),
	SHADER("fullscreen.vert", spv_fullscreen_vert),
	SHADER("resolve_box.frag", spv_resolve_box_frag),
	SHADER("accumulate.frag", spv_accumulate_frag),
	SHADER("copy.frag", spv_copy_frag),
};

const struct aa_shader_code *aa_shader_find(const char *name)
{
	for (size_t i = 0; i < sizeof shaders / sizeof shaders[0]; i++)
		if (strcmp(shaders[i].name, name) == 0)
			return &shaders[i];
	return NULL;
}
