/* A mesh file's materials as aalab materials, and the textures they name (embedded or beside the file),
 * for mesh_file.c (docs/scene-format.md, "Materials from mesh files"). */
#include <assimp/GltfMaterial.h>
#include <assimp/cimport.h>
#include <assimp/material.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "image/image.h"
#include "scene/mesh_file_loader.h"
#include "scene/texture.h"
#include "util/file_open.h"

static int add_texture_slot(struct loader *L)
{
	struct aa_scene *sc = L->scene;
	if (sc->texture_count >= AA_SCENE_MAX_ALL_TEXTURES)
		return FAIL(L, AA_ERR_LIMIT, "the scene has more than %d textures with those of its mesh files",
			    AA_SCENE_MAX_ALL_TEXTURES);
	struct aa_texture *grown = realloc(sc->textures, (size_t)(sc->texture_count + 1) * sizeof *grown);
	if (!grown)
		return FAIL(L, AA_ERR_INTERNAL, "out of memory");
	sc->textures = grown;
	memset(&sc->textures[sc->texture_count], 0, sizeof *sc->textures);
	return sc->texture_count;
}

/* A texture a material names: embedded ("*N") or a file beside the mesh file; loaded once per file and
 * kind (colour or data). -1 with *missing set when the file is absent and the object asked for warnings. */
static int load_texture(struct loader *L, const char *ref, bool linear, const char *what, bool *missing)
{
	struct aa_scene *sc = L->scene;
	char source[sizeof sc->textures[0].source];
	snprintf(source, sizeof source, "%.200s:%.280s%s", L->shown, ref, linear ? " (data)" : "");
	for (int i = 0; i < sc->texture_count; i++)
		if (strcmp(sc->textures[i].source, source) == 0)
			return i;
	struct aa_image_rgba8 img = {0};
	struct aa_error e = {0};
	int rc;
	if (ref[0] == '*') {
		char *end;
		long index = strtol(ref + 1, &end, 10);
		if (*end || index < 0 || index >= (long)L->ai->mNumTextures)
			return FAIL(L, AA_ERR_INVALID, "%s names embedded texture %s, which the file does not have", what, ref);
		const struct aiTexture *t = L->ai->mTextures[index];
		if (t->mHeight == 0) { /* compressed: PNG, JPEG, ... */
			rc = aa_image_decode_rgba8(t->pcData, t->mWidth, source, t->achFormatHint, &img, &e);
		} else if ((rc = aa_image_rgba8_alloc(&img, (int)t->mWidth, (int)t->mHeight)) == 0) {
			for (size_t p = 0; p < (size_t)t->mWidth * t->mHeight; p++) {
				img.pixels[p * 4 + 0] = t->pcData[p].r;
				img.pixels[p * 4 + 1] = t->pcData[p].g;
				img.pixels[p * 4 + 2] = t->pcData[p].b;
				img.pixels[p * 4 + 3] = t->pcData[p].a;
			}
		} else {
			aa_error_set(&e, AA_ERR_INTERNAL, "", "out of memory");
		}
	} else {
		char full[PATH_MAX];
		struct stat st;
		rc = aa_resolve_beside(L->path, L->base_dir, ref, full, sizeof full, &e);
		if (rc && e.code == AA_ERR_NOT_FOUND && L->options->missing_warn) {
			aa_scene_warn(sc, "%s: %s: texture '%s' not found: drawn without it", L->shown, what, ref);
			*missing = true;
			return -1;
		}
		if (rc)
			return FAIL(L, e.code, "%s: texture %s", what, e.message);
		int fd = aa_file_open_regular(full, "", &e); /* never blocks on a FIFO */
		if (fd < 0 && e.code == AA_ERR_INVALID)
			return FAIL(L, AA_ERR_INVALID, "%s: texture '%s' is not a regular file (a FIFO, socket or device)", what, ref);
		if (fd >= 0)
			close(fd);
		if (stat(full, &st) != 0 || (uint64_t)st.st_size > AA_MESH_FILE_MAX_BYTES)
			return FAIL(L, AA_ERR_LIMIT, "%s: texture '%s' is over %u bytes", what, ref,
				    (unsigned)AA_MESH_FILE_MAX_BYTES);
		rc = aa_image_read_rgba8(full, &img, &e);
	}
	if (rc)
		return FAIL(L, e.code ? e.code : AA_ERR_INVALID, "%s: texture '%s': %s", what, ref, e.message);
	if (img.width > AA_TEXTURE_MAX_SIZE || img.height > AA_TEXTURE_MAX_SIZE ||
	    L->texture_bytes + aa_texture_bytes(img.width, img.height) > AA_SCENE_MAX_TEXTURE_BYTES) {
		aa_image_rgba8_free(&img);
		return FAIL(L, AA_ERR_LIMIT, "%s: texture '%s' is %dx%d: textures may be at most %dx%d and %u bytes in "
			    "all", what, ref, img.width, img.height, AA_TEXTURE_MAX_SIZE, AA_TEXTURE_MAX_SIZE,
			    (unsigned)AA_SCENE_MAX_TEXTURE_BYTES);
	}
	int slot = add_texture_slot(L);
	if (slot < 0) {
		aa_image_rgba8_free(&img);
		return -1;
	}
	struct aa_texture *tex = &sc->textures[slot];
	rc = aa_texture_from_rgba8_data(tex, img.pixels, img.width, img.height, linear, &e);
	aa_image_rgba8_free(&img);
	if (rc)
		return FAIL(L, e.code, "%s: texture '%s': %s", what, ref, e.message);
	sc->texture_count++;
	L->texture_bytes += aa_texture_bytes(tex->width, tex->height);
	snprintf(tex->source, sizeof tex->source, "%s", source);
	snprintf(tex->name, sizeof tex->name, "%.40s#%d", L->shown, slot);
	return slot;
}

static bool material_float(const struct aiMaterial *mat, const char *key, unsigned type, unsigned index, float *out)
{
	ai_real v;
	unsigned one = 1;
	if (aiGetMaterialFloatArray(mat, key, type, index, &v, &one) != AI_SUCCESS || !isfinite(v))
		return false;
	*out = (float)v;
	return true;
}

static bool material_color(const struct aiMaterial *mat, const char *key, unsigned type, unsigned index, float out[4])
{
	struct aiColor4D c;
	if (aiGetMaterialColor(mat, key, type, index, &c) != AI_SUCCESS)
		return false;
	float v[4] = {c.r, c.g, c.b, c.a};
	for (int k = 0; k < 4; k++)
		out[k] = isfinite(v[k]) ? v[k] : -1.0f; /* out of range: clamped and warned about by clamp_values */
	return true;
}

/* Values outside what the format allows are clamped, and the scene says so once per field. */
static void clamp_values(struct loader *L, const char *what, const char *field, float *v, int n, float lo, float hi)
{
	bool clamped = false;
	for (int k = 0; k < n; k++) {
		float c = isfinite(v[k]) ? fminf(fmaxf(v[k], lo), hi) : lo;
		clamped |= c != v[k];
		v[k] = c;
	}
	if (clamped)
		aa_scene_warn(L->scene, "%s: %s: %s outside [%g, %g] (or not a number): clamped", L->shown, what, field, lo, hi);
}

/* The texture of a map, if the material has one: loads it into maps[map]. */
static int material_map(struct loader *L, const struct aiMaterial *mat, enum aiTextureType type, int map,
			bool linear, const char *what, struct aa_material *m)
{
	struct aiString path;
	if (aiGetMaterialTextureCount(mat, type) == 0 ||
	    aiGetMaterialTexture(mat, type, 0, &path, NULL, NULL, NULL, NULL, NULL, NULL) != AI_SUCCESS ||
	    m->maps[map] >= 0)
		return 0;
	bool missing = false;
	int t = load_texture(L, path.data, linear, what, &missing);
	if (t < 0 && !missing)
		return -1;
	m->maps[map] = t;
	return 0;
}

/* The 2x3 matrix of KHR_texture_transform: T(offset) R(rotation) S(scale) on (u, v, 1), glTF's order and
 * direction (rotation counter-clockwise in uv, about the uv origin). */
static void uv_matrix(const struct aa_gltf_map *g, float m[6])
{
	float c = cosf(g->rotation), s = sinf(g->rotation);
	m[0] = c * g->scale[0], m[1] = s * g->scale[1], m[2] = g->offset[0];
	m[3] = -s * g->scale[0], m[4] = c * g->scale[1], m[5] = g->offset[1];
}

/* A file material as an aalab material (docs/scene-format.md, "Materials from mesh files"). */
static int convert_material(struct loader *L, unsigned index, struct aa_material *m)
{
	const struct aiMaterial *mat = L->ai->mMaterials[index];
	struct aiString name = {0};
	aiGetMaterialString(mat, AI_MATKEY_NAME, &name);
	char what[160];
	snprintf(what, sizeof what, "materials[%u] '%.60s'", index, name.data);
	aa_material_defaults(m);
	m->scale[0] = m->scale[1] = 1.0f; /* textures map once over uv 0..1 (the transform, if any, does the rest) */
	snprintf(m->name, sizeof m->name, "%.40s/%.20s", L->shown, name.length ? name.data : "material");
	snprintf(m->source, sizeof m->source, "%.60s: %.90s", L->shown, what);
	float color[4] = {1, 1, 1, 1};
	if (!material_color(mat, AI_MATKEY_BASE_COLOR, color))
		material_color(mat, AI_MATKEY_COLOR_DIFFUSE, color);
	clamp_values(L, what, L->gltf ? "baseColorFactor" : "diffuse colour (Kd)", color, 4, 0.0f, 1.0f);
	memcpy(m->base_color, color, sizeof color);
	int shading = 0;
	unsigned one = 1;
	bool unlit = aiGetMaterialIntegerArray(mat, AI_MATKEY_SHADING_MODEL, &shading, &one) == AI_SUCCESS &&
		     shading == aiShadingMode_Unlit;
	if (L->gltf) {
		const struct aa_gltf_material *g = index < (unsigned)L->gltf_info.material_count ?
							   &L->gltf_info.materials[index] : NULL;
		m->model = AA_SHADING_METAL_ROUGH;
		m->metallic = 1.0f, m->roughness = 1.0f; /* glTF's defaults */
		material_float(mat, AI_MATKEY_METALLIC_FACTOR, &m->metallic);
		material_float(mat, AI_MATKEY_ROUGHNESS_FACTOR, &m->roughness);
		clamp_values(L, what, "metallicFactor", &m->metallic, 1, 0.0f, 1.0f);
		clamp_values(L, what, "roughnessFactor", &m->roughness, 1, 0.0f, 1.0f);
		float emissive[4] = {0, 0, 0, 1};
		material_color(mat, AI_MATKEY_COLOR_EMISSIVE, emissive);
		clamp_values(L, what, "emissiveFactor", emissive, 3, 0.0f, 1.0f);
		for (int k = 0; k < 3; k++)
			m->emissive[k] = emissive[k] * (g ? g->emissive_strength : 1.0f);
		struct aiString mode = {0};
		aiGetMaterialString(mat, AI_MATKEY_GLTF_ALPHAMODE, &mode);
		if (strcmp(mode.data, "MASK") == 0) {
			m->alpha_cutout = true;
			m->alpha_cutoff = 0.5f;
			material_float(mat, AI_MATKEY_GLTF_ALPHACUTOFF, &m->alpha_cutoff);
			clamp_values(L, what, "alphaCutoff", &m->alpha_cutoff, 1, 0.0f, 1.0f);
			/* the cut-out path discards alpha < cutoff: at 0 nothing would go, so keep a hair above */
			m->alpha_cutoff = fmaxf(m->alpha_cutoff, 1e-4f);
		} else if (strcmp(mode.data, "BLEND") == 0) {
			m->blend = true;
		} else {
			m->base_color[3] = 1.0f; /* OPAQUE: alpha is ignored */
		}
		int two_sided = 0;
		one = 1;
		aiGetMaterialIntegerArray(mat, AI_MATKEY_TWOSIDED, &two_sided, &one);
		m->single_sided = !two_sided;
		material_float(mat, AI_MATKEY_GLTF_TEXTURE_SCALE(aiTextureType_NORMALS, 0), &m->normal_scale);
		material_float(mat, AI_MATKEY_GLTF_TEXTURE_STRENGTH(aiTextureType_LIGHTMAP, 0), &m->occlusion_strength);
		if (material_map(L, mat, aiTextureType_BASE_COLOR, AA_MAP_BASE, false, what, m) ||
		    material_map(L, mat, aiTextureType_DIFFUSE, AA_MAP_BASE, false, what, m) ||
		    material_map(L, mat, aiTextureType_EMISSIVE, AA_MAP_EMISSIVE, false, what, m) ||
		    material_map(L, mat, aiTextureType_NORMALS, AA_MAP_NORMAL, true, what, m) ||
		    material_map(L, mat, aiTextureType_UNKNOWN, AA_MAP_METAL_ROUGH, true, what, m) ||
		    material_map(L, mat, aiTextureType_METALNESS, AA_MAP_METAL_ROUGH, true, what, m) ||
		    material_map(L, mat, aiTextureType_LIGHTMAP, AA_MAP_OCCLUSION, true, what, m) ||
		    material_map(L, mat, aiTextureType_AMBIENT_OCCLUSION, AA_MAP_OCCLUSION, true, what, m))
			return -1;
		for (int k = 0; g && k < AA_MAP_COUNT; k++)
			if (g->maps[k].transformed) {
				uv_matrix(&g->maps[k], m->uv_transform[k]);
				m->uv_transformed = true;
			}
	} else {
		/* OBJ and the rest: the scene's own model, Lambert + Blinn-Phong from Kd, Ks, Ns, d */
		float ks[4] = {0, 0, 0, 1}, shininess = 0, opacity = 1, emissive[4] = {0, 0, 0, 1};
		material_color(mat, AI_MATKEY_COLOR_SPECULAR, ks);
		material_float(mat, AI_MATKEY_SHININESS, &shininess);
		material_float(mat, AI_MATKEY_OPACITY, &opacity);
		material_color(mat, AI_MATKEY_COLOR_EMISSIVE, emissive);
		clamp_values(L, what, "specular colour (Ks)", ks, 3, 0.0f, 1.0f);
		clamp_values(L, what, "emissive colour (Ke)", emissive, 3, 0.0f, 1.0f);
		clamp_values(L, what, "opacity (d)", &opacity, 1, 0.0f, 1.0f);
		memcpy(m->emissive, emissive, sizeof m->emissive);
		m->specular = fmaxf(ks[0], fmaxf(ks[1], ks[2]));
		/* the exponent maps onto roughness the way scene materials do (512 at 0, 4 at 1) */
		m->roughness = shininess > 0 ? fminf(fmaxf((512.0f - shininess) / 508.0f, 0.01f), 1.0f) : 0.5f;
		m->base_color[3] = fminf(fmaxf(opacity, 0.0f), 1.0f);
		m->blend = m->base_color[3] < 1.0f;
		if (material_map(L, mat, aiTextureType_DIFFUSE, AA_MAP_BASE, false, what, m) ||
		    material_map(L, mat, aiTextureType_EMISSIVE, AA_MAP_EMISSIVE, false, what, m) ||
		    material_map(L, mat, aiTextureType_NORMALS, AA_MAP_NORMAL, true, what, m))
			return -1;
		if (aiGetMaterialTextureCount(mat, aiTextureType_HEIGHT) || aiGetMaterialTextureCount(mat, aiTextureType_OPACITY))
			aa_scene_warn(L->scene, "%s: %s: bump (height) and opacity maps are not drawn", L->shown, what);
	}
	m->unlit = unlit;
	if (m->maps[AA_MAP_BASE] >= 0) {
		m->texture_index = m->maps[AA_MAP_BASE];
		m->pattern = AA_PATTERN_TEXTURE;
	}
	if (m->maps[AA_MAP_EMISSIVE] >= 0 && m->emissive[0] == 0 && m->emissive[1] == 0 && m->emissive[2] == 0)
		m->maps[AA_MAP_EMISSIVE] = -1; /* times a zero factor: nothing to sample */
	if (m->unlit && (m->maps[AA_MAP_NORMAL] >= 0 || m->maps[AA_MAP_EMISSIVE] >= 0))
		m->maps[AA_MAP_NORMAL] = m->maps[AA_MAP_EMISSIVE] = -1;
	return 0;
}

int aa_mesh_file_add_material(struct loader *L, unsigned index, int *out)
{
	struct aa_scene *sc = L->scene;
	if (sc->material_count >= AA_SCENE_MAX_ALL_MATERIALS)
		return FAIL(L, AA_ERR_LIMIT, "the scene has more than %d materials with those of its mesh files",
			    AA_SCENE_MAX_ALL_MATERIALS);
	struct aa_material *grown = realloc(sc->materials, (size_t)(sc->material_count + 1) * sizeof *grown);
	if (!grown)
		return FAIL(L, AA_ERR_INTERNAL, "out of memory");
	sc->materials = grown;
	struct aa_material m;
	if (convert_material(L, index, &m))
		return -1;
	sc->materials[sc->material_count] = m;
	*out = sc->material_count++;
	return 0;
}

/* Whether a file material is the importer's stand-in for "no material" (glTF primitives without one, OBJ
 * without a .mtl): those parts take the scene's default material. */
bool aa_mesh_file_is_default_material(struct loader *L, unsigned index)
{
	if (L->gltf)
		return index >= (unsigned)L->gltf_info.material_count;
	struct aiString name = {0};
	aiGetMaterialString(L->ai->mMaterials[index], AI_MATKEY_NAME, &name);
	return strcmp(name.data, AI_DEFAULT_MATERIAL_NAME) == 0;
}
