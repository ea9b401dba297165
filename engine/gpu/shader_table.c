/* The SPIR-V of every shader, compiled from shaders/ at build time and embedded: nothing is looked up
 * on disk at run time. shader_list.h is generated from glsl_files in the Makefile. */
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "gpu/gpu.h"
#include "shader_list.h"

static const struct aa_shader_code shaders[] = {AA_SHADER_ENTRIES};

static struct {
	char name[64];
	const struct aa_shader_code *code;
} substitutes[4];

int aa_shader_substitute(const char *name, const struct aa_shader_code *code)
{
	int free_slot = -1;
	for (int i = 0; i < 4; i++) {
		if (substitutes[i].code && strcmp(substitutes[i].name, name) == 0) {
			substitutes[i].code = code;
			return 0;
		}
		if (!substitutes[i].code && free_slot < 0)
			free_slot = i;
	}
	if (!code)
		return 0;
	if (free_slot < 0)
		return -1;
	snprintf(substitutes[free_slot].name, sizeof substitutes[free_slot].name, "%s", name);
	substitutes[free_slot].code = code;
	return 0;
}

const struct aa_shader_code *aa_shader_find(const char *name)
{
	for (int i = 0; i < 4; i++)
		if (substitutes[i].code && strcmp(substitutes[i].name, name) == 0)
			return substitutes[i].code;
	for (size_t i = 0; i < sizeof shaders / sizeof shaders[0]; i++)
		if (strcmp(shaders[i].name, name) == 0)
			return &shaders[i];
	return NULL;
}
