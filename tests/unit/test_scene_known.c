/* Scene loading where the answer is written down: a glTF triangle under a node with a translation and a
 * scale is loaded with the node's transform baked into its vertices (the shipped assets have none, so no
 * other test sees it) and its texture coordinates keep glTF's convention (v = 0 at the top of the image);
 * materials get the defaults of docs/scene-format.md. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <cmocka.h>

#include "run/engine.h"

/* One triangle, positions (0,0,0) (1,0,0) (0,1,0) and uvs (0,0) (1,0) (0,1), as 60 bytes of little-endian
 * floats in a data URI; node 0 moves it by (10, 20, 30) and scales it by 2. */
static const char gltf[] =
	"{\"asset\": {\"version\": \"2.0\"}, \"scene\": 0, \"scenes\": [{\"nodes\": [0]}],"
	" \"nodes\": [{\"mesh\": 0, \"translation\": [10, 20, 30], \"scale\": [2, 2, 2]}],"
	" \"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": 0, \"TEXCOORD_0\": 1}}]}],"
	" \"buffers\": [{\"byteLength\": 60, \"uri\": \"data:application/octet-stream;base64,"
	"AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAAAIA/AAAAAAAAAAAAAIA/\"}],"
	" \"bufferViews\": [{\"buffer\": 0, \"byteOffset\": 0, \"byteLength\": 36},"
	" {\"buffer\": 0, \"byteOffset\": 36, \"byteLength\": 24}],"
	" \"accessors\": [{\"bufferView\": 0, \"componentType\": 5126, \"count\": 3, \"type\": \"VEC3\","
	" \"min\": [0, 0, 0], \"max\": [1, 1, 0]},"
	" {\"bufferView\": 1, \"componentType\": 5126, \"count\": 3, \"type\": \"VEC2\"}]}";

static void test_node_transform_and_uvs(void **state)
{
	(void)state;
	char dir[] = "/tmp/aalab-mesh.XXXXXX", path[128];
	assert_non_null(mkdtemp(dir));
	snprintf(path, sizeof path, "%s/tri.gltf", dir);
	FILE *f = fopen(path, "w");
	assert_non_null(f);
	fputs(gltf, f);
	fclose(f);

	struct aa_scene *sc = NULL;
	struct aa_error err = {0};
	const char *json = "{\"meshes\": {\"tri\": {\"type\": \"file\", \"path\": \"tri.gltf\"}},"
			   " \"objects\": [{\"mesh\": \"tri\"}],"
			   " \"camera\": {\"position\": [0, 0, 5], \"target\": [0, 0, 0]}}";
	if (aa_scene_load_string(json, "tri", dir, &sc, &err))
		fail_msg("%s: %s", err.path, err.message);
	assert_int_equal(sc->mesh_count, 1);
	const struct aa_mesh *m = &sc->meshes[0];
	assert_int_equal(m->index_count, 3);
	/* each file vertex (x, y, 0) with uv (u, v) is found at (10 + 2x, 20 + 2y, 30) with the same uv */
	static const float file_xy[3][2] = {{0, 0}, {1, 0}, {0, 1}};
	for (int k = 0; k < 3; k++) {
		bool found = false;
		for (uint32_t i = 0; i < m->index_count && !found; i++) {
			const struct aa_vertex *v = &m->vertices[m->indices[i]];
			found = fabsf(v->position[0] - (10 + 2 * file_xy[k][0])) < 1e-5f &&
				fabsf(v->position[1] - (20 + 2 * file_xy[k][1])) < 1e-5f &&
				fabsf(v->position[2] - 30) < 1e-5f && fabsf(v->uv[0] - file_xy[k][0]) < 1e-6f &&
				fabsf(v->uv[1] - file_xy[k][1]) < 1e-6f;
		}
		if (!found)
			fail_msg("no vertex at (%g, %g, 30) with uv (%g, %g); vertex 0 is (%g, %g, %g) uv (%g, %g)",
				 10 + 2 * file_xy[k][0], 20 + 2 * file_xy[k][1], file_xy[k][0], file_xy[k][1],
				 m->vertices[0].position[0], m->vertices[0].position[1], m->vertices[0].position[2],
				 m->vertices[0].uv[0], m->vertices[0].uv[1]);
	}
	aa_scene_free(sc);
	unlink(path);
	rmdir(dir);
}

/* docs/scene-format.md, "materials": stripe_width 0.5, specular 0, roughness 0.5, alpha_cutout false,
 * alpha_cutoff 0.5, unlit false; the same for the implicit "default" material. */
static void test_material_defaults(void **state)
{
	(void)state;
	struct aa_scene *sc = NULL;
	struct aa_error err = {0};
	const char *json = "{\"materials\": {\"plain\": {\"color\": [0.5, 0.5, 0.5]}, "
			   "\"cut\": {\"color\": [1, 1, 1], \"alpha_cutout\": true}},"
			   " \"objects\": [{\"mesh\": \"box\", \"material\": \"plain\"}, {\"mesh\": \"box\", \"material\": \"cut\"},"
			   " {\"mesh\": \"box\"}], \"camera\": {\"position\": [0, 0, 5], \"target\": [0, 0, 0]}}";
	if (aa_scene_load_string(json, "defaults", NULL, &sc, &err))
		fail_msg("%s: %s", err.path, err.message);
	for (int o = 0; o < 3; o++) {
		const struct aa_material *m = &sc->materials[sc->objects[o].material_index];
		if (m->stripe_width != 0.5f || m->specular != 0.0f || m->roughness != 0.5f || m->alpha_cutoff != 0.5f ||
		    m->unlit || m->alpha_cutout != (o == 1))
			fail_msg("material %s: stripe_width %g, specular %g, roughness %g, alpha_cutoff %g, unlit %d, "
				 "alpha_cutout %d", m->name, m->stripe_width, m->specular, m->roughness, m->alpha_cutoff,
				 m->unlit, m->alpha_cutout);
	}
	assert_true(aa_scene_has_cutout(sc));
	aa_scene_free(sc);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_node_transform_and_uvs),
		cmocka_unit_test(test_material_defaults),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
