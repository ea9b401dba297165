/* libFuzzer target: the scene JSON parser (engine/scene/scene_load.c) as submit checks an inline scene:
 * no scene folder, so file meshes and textures are refused. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "scene/scene.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	if (memchr(data, 0, size))
		return 0; /* the daemon refuses a scene with NUL bytes before parsing */
	char *text = malloc(size + 1);
	if (!text)
		return 0;
	memcpy(text, data, size);
	text[size] = 0;
	struct aa_scene *scene = NULL;
	struct aa_error err = {0};
	if (aa_scene_load_string(text, "fuzz", NULL, &scene, &err) != 0 && !err.message[0])
		__builtin_trap();
	aa_scene_free(scene);
	free(text);
	return 0;
}
