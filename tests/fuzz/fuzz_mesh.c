/* libFuzzer target: mesh files through the entry point `aalab run` uses (aa_scene_load of a scene file
 * that names the mesh). The first input byte picks the file type (OBJ, glTF, PLY, STL, OFF), the rest is
 * the file. Files live under one temporary folder, in tmpfs where there is one. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "scene/scene.h"

static char dir[256], scene_path[300];

static const char *const extensions[] = {"obj", "gltf", "ply", "stl", "off"};

static void setup(void)
{
	const char *base = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
	snprintf(dir, sizeof dir, "%s/aalab-fuzz-mesh.%ld", base, (long)getpid());
	if (!mkdtemp(strcat(dir, ".XXXXXX")))
		abort();
	snprintf(scene_path, sizeof scene_path, "%s/scene.json", dir);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	if (!dir[0])
		setup();
	if (size < 1)
		return 0;
	const char *ext = extensions[data[0] % (sizeof extensions / sizeof extensions[0])];
	char mesh[320];
	snprintf(mesh, sizeof mesh, "%s/mesh.%s", dir, ext);
	FILE *f = fopen(mesh, "wb");
	if (!f)
		abort();
	fwrite(data + 1, 1, size - 1, f);
	fclose(f);
	f = fopen(scene_path, "w");
	if (!f)
		abort();
	fprintf(f, "{\"camera\": {\"position\": [0, 0, 5], \"target\": [0, 0, 0]},\n"
		   " \"objects\": [{\"name\": \"m\", \"mesh\": {\"type\": \"file\", \"path\": \"mesh.%s\"}}]}\n", ext);
	fclose(f);
	struct aa_scene *scene = NULL;
	struct aa_error err = {0};
	if (aa_scene_load(scene_path, &scene, &err) != 0 && !err.message[0])
		__builtin_trap();
	aa_scene_free(scene);
	unlink(mesh);
	return 0;
}
