/* The SPIR-V of every shader, compiled from shaders/ at build time and embedded: nothing is looked up
 * on disk at run time. shader_list.h is generated from glsl_files in the Makefile. */
#include <stdint.h>
#include <string.h>

#include "gpu/gpu.h"
#include "shader_list.h"

static const struct aa_shader_code shaders[] = {AA_SHADER_ENTRIES};

const struct aa_shader_code *aa_shader_find(const char *name)
{
	for (size_t i = 0; i < sizeof shaders / sizeof shaders[0]; i++)
		if (strcmp(shaders[i].name, name) == 0)
			return &shaders[i];
	return NULL;
}
