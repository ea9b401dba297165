/* Mesh files (glTF 2.0, OBJ, anything assimp reads) merged into one aa_mesh through assimp's C API. */
#include "mesh_procedural.h"

#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static bool finite3(const struct aiVector3D *v)
{
	return isfinite(v->x) && isfinite(v->y) && isfinite(v->z);
}

int aa_mesh_load_file(struct sj *s, const char *path, const char *shown, uint64_t max_triangles,
		      struct aa_mesh *out)
{
	struct stat st;
	memset(out, 0, sizeof *out);
	if (stat(path, &st) != 0 || !S_ISREG(st.st_mode))
		return sj_fail(s, AA_ERR_NOT_FOUND, "mesh file '%s' not found", shown);
	if ((uint64_t)st.st_size > AA_MESH_FILE_MAX_BYTES)
		return sj_fail(s, AA_ERR_LIMIT, "mesh file '%s' is %lld bytes, over the limit of %u", shown,
			       (long long)st.st_size, (unsigned)AA_MESH_FILE_MAX_BYTES);

	/* PreTransformVertices bakes the node hierarchy so every mesh is in model space; FlipUVs puts
	 * v = 0 at the top of the image, as glTF and our textures expect. */
	const struct aiScene *sc = aiImportFile(path, aiProcess_Triangulate | aiProcess_GenSmoothNormals |
							      aiProcess_JoinIdenticalVertices |
							      aiProcess_PreTransformVertices | aiProcess_SortByPType |
							      aiProcess_FlipUVs);
	if (!sc)
		return sj_fail(s, AA_ERR_INVALID, "cannot read mesh file '%s': %s", shown, aiGetErrorString());

	uint64_t tris = 0, verts = 0;
	for (unsigned i = 0; i < sc->mNumMeshes; i++) {
		const struct aiMesh *m = sc->mMeshes[i];
		if (!(m->mPrimitiveTypes & aiPrimitiveType_TRIANGLE))
			continue; /* points and lines have no area to render */
		verts += m->mNumVertices;
		for (unsigned f = 0; f < m->mNumFaces; f++)
			tris += m->mFaces[f].mNumIndices == 3;
	}
	int rc = 0;
	if (tris == 0)
		rc = sj_fail(s, AA_ERR_INVALID, "mesh file '%s' has no triangle meshes", shown);
	else if (tris > max_triangles)
		rc = sj_fail(s, AA_ERR_LIMIT, "mesh file '%s' has %llu triangles, over the limit of %llu", shown,
			     (unsigned long long)tris, (unsigned long long)max_triangles);
	else if (verts > UINT32_MAX / 2)
		rc = sj_fail(s, AA_ERR_LIMIT, "mesh file '%s' has too many vertices", shown);
	if (rc) {
		aiReleaseImport(sc);
		return -1;
	}

	out->vertices = calloc(verts, sizeof *out->vertices);
	out->indices = malloc(tris * 3 * sizeof *out->indices);
	if (!out->vertices || !out->indices) {
		aiReleaseImport(sc);
		aa_mesh_free(out);
		return sj_fail(s, AA_ERR_INTERNAL, "out of memory loading '%s'", shown);
	}
	const char *base = strrchr(shown, '/');
	snprintf(out->name, sizeof out->name, "%s", base ? base + 1 : shown);
	for (unsigned i = 0; i < sc->mNumMeshes && !rc; i++) {
		const struct aiMesh *m = sc->mMeshes[i];
		if (!(m->mPrimitiveTypes & aiPrimitiveType_TRIANGLE))
			continue;
		uint32_t first = out->vertex_count;
		for (unsigned v = 0; v < m->mNumVertices; v++) {
			struct aa_vertex *o = &out->vertices[first + v];
			const struct aiVector3D *p = &m->mVertices[v];
			if (!finite3(p)) {
				rc = sj_fail(s, AA_ERR_INVALID, "mesh file '%s' has a non-finite vertex position", shown);
				break;
			}
			o->position[0] = p->x, o->position[1] = p->y, o->position[2] = p->z;
			/* GenSmoothNormals fills missing normals; a zero one (degenerate faces) gets +y. */
			struct aiVector3D n = m->mNormals ? m->mNormals[v] : (struct aiVector3D){0, 1, 0};
			float len = finite3(&n) ? sqrtf(n.x * n.x + n.y * n.y + n.z * n.z) : 0.0f;
			if (len > 1e-12f)
				o->normal[0] = n.x / len, o->normal[1] = n.y / len, o->normal[2] = n.z / len;
			else
				o->normal[1] = 1.0f;
			if (m->mTextureCoords[0] && isfinite(m->mTextureCoords[0][v].x) &&
			    isfinite(m->mTextureCoords[0][v].y)) {
				o->uv[0] = m->mTextureCoords[0][v].x;
				o->uv[1] = m->mTextureCoords[0][v].y;
			}
		}
		out->vertex_count += m->mNumVertices;
		for (unsigned f = 0; f < m->mNumFaces && !rc; f++) {
			const struct aiFace *face = &m->mFaces[f];
			if (face->mNumIndices != 3)
				continue;
			for (int k = 0; k < 3; k++) {
				if (face->mIndices[k] >= m->mNumVertices) {
					rc = sj_fail(s, AA_ERR_INVALID, "mesh file '%s' has an out-of-range index", shown);
					break;
				}
				out->indices[out->index_count++] = first + face->mIndices[k];
			}
		}
	}
	aiReleaseImport(sc);
	if (rc)
		aa_mesh_free(out);
	return rc ? -1 : 0;
}
