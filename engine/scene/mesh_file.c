/* Mesh files (glTF 2.0, OBJ, PLY, STL, OFF) through assimp's C API: read first by aalab itself
 * (gltf_check.c, mesh_text_check.c), checked raw again (finite positions within 1e7, indices that name
 * vertices) before assimp's post-processing can hide a fault, then split into one mesh per material with
 * node transforms baked in, except where a skin or an animation moves the vertices: those keep their
 * bind-space positions and a rig (scene_rig.c) poses them per frame. Materials and their textures come
 * from the file unless the object overrides them (mesh_file_materials.c). */
#include "scene/mesh_file_loader.h"

#include <assimp/cfileio.h>
#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "scene/mesh_procedural.h"
#include "util/file_open.h"
#include "scene/mesh_text_check.h"
#include "scene/texture.h"

#define POSITION_MAX 1e7 /* as every number in a scene file (SJ_MAX_ABS) */

/* ---------------------------------------------------------------- small helpers */

static mat4 from_ai(const struct aiMatrix4x4 *a) /* assimp is row-major, mat4 column-major */
{
	mat4 m = {{a->a1, a->b1, a->c1, a->d1, a->a2, a->b2, a->c2, a->d2, a->a3, a->b3, a->c3, a->d3, a->a4, a->b4,
		   a->c4, a->d4}};
	return m;
}

static float det3(mat4 m)
{
	const float *a = m.m;
	return a[0] * (a[5] * a[10] - a[9] * a[6]) - a[4] * (a[1] * a[10] - a[9] * a[2]) +
	       a[8] * (a[1] * a[6] - a[5] * a[2]);
}

static vec3 normalized_or(vec3 v, vec3 fallback)
{
	float len = v3_length(v);
	return len > 1e-20f && isfinite(len) ? v3_scale(v, 1.0f / len) : fallback;
}

/* ---------------------------------------------------------------- errors and the raw import */

int aa_mesh_file_fail(struct loader *L, enum aa_error_code code, const char *fmt, ...)
{
	char msg[600];
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(msg, sizeof msg, fmt, ap);
	va_end(ap);
	return sj_fail(L->s, code, "mesh file '%s': %s", L->shown, msg);
}

/* assimp's messages, said as what is wrong with which file. */
static int import_error(struct loader *L)
{
	const char *msg = aiGetErrorString();
	if (strstr(msg, "No suitable reader found"))
		return FAIL(L, AA_ERR_INVALID, "is not in a format aalab reads (glTF 2.0 .gltf or .glb, OBJ .obj, "
			    "PLY .ply, STL .stl, OFF .off)");
	char copy[512];
	snprintf(copy, sizeof copy, "%s", msg);
	char *at = strstr(copy, L->path); /* assimp quotes the absolute path; the scene's name is enough */
	if (at)
		memmove(at, at + strlen(L->path), strlen(at + strlen(L->path)) + 1);
	return FAIL(L, AA_ERR_INVALID, "cannot be read (assimp: %s)", copy);
}

/* The file as assimp read it, before post-processing merges vertices (which hides a NaN) or drops faces:
 * finite positions within 1e7 and face indices that name vertices, in every format. */
static int check_raw(struct loader *L)
{
	for (unsigned i = 0; i < L->ai->mNumMeshes; i++) {
		const struct aiMesh *m = L->ai->mMeshes[i];
		if (m->mNumAnimMeshes)
			return FAIL(L, AA_ERR_INVALID, "mesh '%s' has morph targets, which aalab does not support",
				    m->mName.data);
		for (unsigned v = 0; v < m->mNumVertices; v++) {
			const struct aiVector3D *p = &m->mVertices[v];
			if (!isfinite(p->x) || !isfinite(p->y) || !isfinite(p->z))
				return FAIL(L, AA_ERR_INVALID, "mesh '%s' vertex %u has a position that is not a finite number "
					    "(%g, %g, %g)", m->mName.data, v, p->x, p->y, p->z);
			if (fabsf(p->x) > POSITION_MAX || fabsf(p->y) > POSITION_MAX || fabsf(p->z) > POSITION_MAX)
				return FAIL(L, AA_ERR_INVALID, "mesh '%s' vertex %u is at (%g, %g, %g): positions must be within "
					    "%g of the origin", m->mName.data, v, p->x, p->y, p->z, POSITION_MAX);
		}
		for (unsigned f = 0; f < m->mNumFaces; f++)
			for (unsigned k = 0; k < m->mFaces[f].mNumIndices; k++)
				if (m->mFaces[f].mIndices[k] >= m->mNumVertices)
					return FAIL(L, AA_ERR_INVALID, "mesh '%s' face %u names vertex %u, but the mesh has %u "
						    "vertices", m->mName.data, f, m->mFaces[f].mIndices[k], m->mNumVertices);
	}
	return 0;
}

/* ---------------------------------------------------------------- nodes, parts and the rig */

static int find_node(struct loader *L, const char *name)
{
	for (int i = 0; i < L->node_count; i++)
		if (strcmp(L->nodes[i].node->mName.data, name) == 0)
			return i;
	return -1;
}

static int count_nodes(const struct aiNode *n)
{
	int c = 1;
	for (unsigned i = 0; i < n->mNumChildren; i++)
		c += count_nodes(n->mChildren[i]);
	return c;
}

/* Depth first, parents before children, with rest-pose world matrices. */
static void flatten(struct loader *L, const struct aiNode *n, int parent)
{
	int i = L->node_count++;
	L->nodes[i].node = n;
	L->nodes[i].parent = parent;
	mat4 local = from_ai(&n->mTransformation);
	L->nodes[i].world = parent >= 0 ? mat4_mul(L->nodes[parent].world, local) : local;
	for (unsigned c = 0; c < n->mNumChildren; c++)
		flatten(L, n->mChildren[c], i);
}

static int build_nodes(struct loader *L)
{
	int n = count_nodes(L->ai->mRootNode);
	if (!(L->nodes = calloc((size_t)n, sizeof *L->nodes)))
		return FAIL(L, AA_ERR_INTERNAL, "out of memory");
	flatten(L, L->ai->mRootNode, -1);
	for (unsigned a = 0; a < L->ai->mNumAnimations; a++) {
		const struct aiAnimation *anim = L->ai->mAnimations[a];
		for (unsigned c = 0; c < anim->mNumChannels; c++) {
			int node = find_node(L, anim->mChannels[c]->mNodeName.data);
			if (node >= 0)
				L->nodes[node].moves = true;
		}
	}
	for (int i = 0; i < L->node_count; i++) /* parents first: a moving ancestor moves its subtree */
		if (L->nodes[i].parent >= 0 && L->nodes[L->nodes[i].parent].moves)
			L->nodes[i].moves = true;
	return 0;
}

static int add_joint(struct loader *L, int node, mat4 ibm)
{
	for (int j = 0; j < L->joint_count; j++)
		if (L->joint_node[j] == node && memcmp(&L->joint_ibm[j], &ibm, sizeof ibm) == 0)
			return j;
	if (L->joint_count == L->joint_cap) {
		int cap = L->joint_cap ? 2 * L->joint_cap : 16;
		int *nn = realloc(L->joint_node, (size_t)cap * sizeof *nn);
		if (nn)
			L->joint_node = nn;
		mat4 *nm = realloc(L->joint_ibm, (size_t)cap * sizeof *nm);
		if (nm)
			L->joint_ibm = nm;
		if (!nn || !nm)
			return -1;
		L->joint_cap = cap;
	}
	if (L->joint_count >= 65535)
		return -1;
	L->joint_node[L->joint_count] = node;
	L->joint_ibm[L->joint_count] = ibm;
	return L->joint_count++;
}

static struct part *part_for(struct loader *L, unsigned material)
{
	for (int i = 0; i < L->part_count; i++)
		if (L->parts[i].material == material)
			return &L->parts[i];
	struct part *p = &L->parts[L->part_count++];
	memset(p, 0, sizeof *p);
	p->material = material;
	return p;
}

static bool is_triangles(const struct aiMesh *m)
{
	return (m->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) != 0;
}

/* Pass one: which part each drawn mesh goes to and how big the parts are. */
static int size_parts(struct loader *L, uint64_t max_triangles)
{
	uint64_t triangles = 0;
	if (!(L->parts = calloc(L->ai->mNumMaterials + 1, sizeof *L->parts)))
		return FAIL(L, AA_ERR_INTERNAL, "out of memory");
	for (int n = 0; n < L->node_count; n++) {
		const struct aiNode *node = L->nodes[n].node;
		for (unsigned k = 0; k < node->mNumMeshes; k++) {
			const struct aiMesh *m = L->ai->mMeshes[node->mMeshes[k]];
			if (!is_triangles(m))
				continue;
			struct part *p = part_for(L, m->mMaterialIndex);
			p->vertex_count += m->mNumVertices;
			for (unsigned f = 0; f < m->mNumFaces; f++)
				p->index_count += m->mFaces[f].mNumIndices == 3 ? 3 : 0;
			p->rigged |= m->mNumBones > 0 || L->nodes[n].moves;
			p->colors |= m->mColors[0] != NULL;
			triangles += m->mNumFaces;
			if ((uint64_t)p->vertex_count > UINT32_MAX / 4)
				return FAIL(L, AA_ERR_LIMIT, "has too many vertices");
		}
	}
	if (triangles == 0)
		return FAIL(L, AA_ERR_INVALID, "has no triangle meshes");
	if (triangles > max_triangles)
		return FAIL(L, AA_ERR_LIMIT, "has %llu triangles, over the limit of %llu", (unsigned long long)triangles,
			    (unsigned long long)max_triangles);
	return 0;
}

/* Up to four joints per vertex, the largest weights kept and renormalised. */
static bool add_weight(struct aa_skin_weights *w, int joint, float weight)
{
	int slot = -1;
	for (int k = 0; k < 4; k++)
		if (w->weights[k] == 0.0f) {
			slot = k;
			break;
		}
	bool dropped = false;
	if (slot < 0) {
		slot = 0;
		for (int k = 1; k < 4; k++)
			if (w->weights[k] < w->weights[slot])
				slot = k;
		if (w->weights[slot] >= weight)
			return true;
		dropped = true;
	}
	w->joints[slot] = (uint16_t)joint;
	w->weights[slot] = weight;
	return dropped;
}

/* Pass two: the vertices and indices of one source mesh appended to its part. */
static int append_mesh(struct loader *L, struct part *p, int n, const struct aiMesh *m, bool *dropped_weights)
{
	struct aa_mesh *out = &L->scene->meshes[p->mesh];
	const struct node_info *ni = &L->nodes[n];
	bool skinned = m->mNumBones > 0, moving = !skinned && ni->moves;
	bool baked = !skinned && !moving; /* node transform into the vertices; else the rig applies it */
	mat4 xf = baked ? ni->world : mat4_identity(), nxf;
	if (mat4_invert(xf, &nxf))
		return FAIL(L, AA_ERR_INVALID, "node '%s' has a singular transform", ni->node->mName.data);
	nxf = mat4_transpose(nxf);
	bool mirrored = det3(xf) < 0; /* glTF: a negative determinant turns the winding around */
	uint32_t first = out->vertex_count;
	int static_joint = -1;
	if (p->rigged && !skinned) { /* a rigid part of a rigged mesh follows its node, or stays put */
		static_joint = add_joint(L, moving ? n : -1, mat4_identity());
		if (static_joint < 0)
			return FAIL(L, AA_ERR_LIMIT, "has too many joints");
	}
	for (unsigned v = 0; v < m->mNumVertices; v++) {
		struct aa_vertex *o = &out->vertices[first + v];
		const struct aiVector3D *ap = &m->mVertices[v];
		vec3 pos = mat4_transform_point(xf, v3(ap->x, ap->y, ap->z));
		if (!(fabsf(pos.x) <= POSITION_MAX && fabsf(pos.y) <= POSITION_MAX && fabsf(pos.z) <= POSITION_MAX))
			return FAIL(L, AA_ERR_INVALID, "mesh '%s' vertex %u lands at (%g, %g, %g) under its node's transform: "
				    "positions must be within %g of the origin", m->mName.data, v, pos.x, pos.y, pos.z,
				    POSITION_MAX);
		o->position[0] = pos.x, o->position[1] = pos.y, o->position[2] = pos.z;
		/* GenSmoothNormals fills missing normals; a zero or broken one (degenerate faces) gets +y */
		vec3 nrm = m->mNormals ? v3(m->mNormals[v].x, m->mNormals[v].y, m->mNormals[v].z) : v3(0, 1, 0);
		nrm = normalized_or(mat4_transform_dir(nxf, nrm), v3(0, 1, 0));
		o->normal[0] = nrm.x, o->normal[1] = nrm.y, o->normal[2] = nrm.z;
		if (m->mTextureCoords[0] && isfinite(m->mTextureCoords[0][v].x) && isfinite(m->mTextureCoords[0][v].y)) {
			o->uv[0] = m->mTextureCoords[0][v].x;
			o->uv[1] = m->mTextureCoords[0][v].y;
		}
		for (int c = 0; c < 4; c++)
			o->color[c] = 1.0f;
		if (m->mColors[0]) {
			const struct aiColor4D *c = &m->mColors[0][v];
			float rgba[4] = {c->r, c->g, c->b, c->a};
			for (int k = 0; k < 4; k++)
				o->color[k] = isfinite(rgba[k]) ? fminf(fmaxf(rgba[k], 0.0f), 1.0f) : 1.0f;
		}
		/* w = 0 marks "none in the file": generated later if the material has a normal map */
		if (m->mTangents && m->mBitangents) {
			/* assimp gives the bitangent; glTF's w is its side: bitangent = w * normal x tangent */
			vec3 t = v3(m->mTangents[v].x, m->mTangents[v].y, m->mTangents[v].z);
			vec3 b = v3(m->mBitangents[v].x, m->mBitangents[v].y, m->mBitangents[v].z);
			vec3 n0 = m->mNormals ? v3(m->mNormals[v].x, m->mNormals[v].y, m->mNormals[v].z) : v3(0, 1, 0);
			float w = v3_dot(v3_cross(n0, t), b) < 0 ? -1.0f : 1.0f;
			t = normalized_or(mat4_transform_dir(xf, t), v3(1, 0, 0));
			o->tangent[0] = t.x, o->tangent[1] = t.y, o->tangent[2] = t.z;
			o->tangent[3] = mirrored ? -w : w;
		}
		if (p->rigged && !skinned)
			out->skin[first + v] = (struct aa_skin_weights){{(uint16_t)static_joint, 0, 0, 0}, {1, 0, 0, 0}};
	}
	if (skinned) {
		for (unsigned b = 0; b < m->mNumBones; b++) {
			const struct aiBone *bone = m->mBones[b];
			int node = find_node(L, bone->mName.data);
			if (node < 0)
				return FAIL(L, AA_ERR_INVALID, "mesh '%s' is skinned to a joint '%s' that is not a node",
					    m->mName.data, bone->mName.data);
			int joint = add_joint(L, node, from_ai(&bone->mOffsetMatrix));
			if (joint < 0)
				return FAIL(L, AA_ERR_LIMIT, "has too many joints");
			for (unsigned w = 0; w < bone->mNumWeights; w++) {
				const struct aiVertexWeight *vw = &bone->mWeights[w];
				if (vw->mVertexId >= m->mNumVertices || !(vw->mWeight > 0.0f) || !isfinite(vw->mWeight))
					continue;
				*dropped_weights |= add_weight(&out->skin[first + vw->mVertexId], joint, vw->mWeight);
			}
		}
		for (unsigned v = 0; v < m->mNumVertices; v++) {
			struct aa_skin_weights *w = &out->skin[first + v];
			float sum = w->weights[0] + w->weights[1] + w->weights[2] + w->weights[3];
			if (sum > 0)
				for (int k = 0; k < 4; k++)
					w->weights[k] /= sum;
			else /* a vertex no joint holds stays where the mesh has it */
				*w = (struct aa_skin_weights){{(uint16_t)add_joint(L, -1, mat4_identity()), 0, 0, 0}, {1, 0, 0, 0}};
		}
	}
	out->vertex_count += m->mNumVertices;
	for (unsigned f = 0; f < m->mNumFaces; f++) {
		const struct aiFace *face = &m->mFaces[f];
		if (face->mNumIndices != 3)
			continue;
		out->indices[out->index_count++] = first + face->mIndices[0];
		out->indices[out->index_count++] = first + face->mIndices[mirrored ? 2 : 1];
		out->indices[out->index_count++] = first + face->mIndices[mirrored ? 1 : 2];
	}
	return 0;
}

/* Tangents for the vertices the file gives none (w = 0), from the texture coordinates (v down, as glTF):
 * +u on the surface, and the side of the bitangent, which points up the image (toward -v). Without a
 * normal map (generate false) they only get a valid placeholder. */
static void generate_tangents(struct aa_mesh *m, bool generate)
{
	if (!generate) {
		for (uint32_t v = 0; v < m->vertex_count; v++)
			if (m->vertices[v].tangent[3] == 0.0f)
				m->vertices[v].tangent[0] = m->vertices[v].tangent[3] = 1.0f;
		return;
	}
	vec3 *tu = calloc(m->vertex_count ? m->vertex_count : 1, 2 * sizeof(vec3));
	if (!tu)
		return;
	vec3 *tv = tu + m->vertex_count;
	for (uint32_t i = 0; i + 2 < m->index_count; i += 3) {
		const struct aa_vertex *a = &m->vertices[m->indices[i]], *b = &m->vertices[m->indices[i + 1]],
				       *c = &m->vertices[m->indices[i + 2]];
		vec3 e1 = v3(b->position[0] - a->position[0], b->position[1] - a->position[1], b->position[2] - a->position[2]);
		vec3 e2 = v3(c->position[0] - a->position[0], c->position[1] - a->position[1], c->position[2] - a->position[2]);
		float du1 = b->uv[0] - a->uv[0], dv1 = b->uv[1] - a->uv[1], du2 = c->uv[0] - a->uv[0], dv2 = c->uv[1] - a->uv[1];
		float det = du1 * dv2 - du2 * dv1;
		if (!(fabsf(det) > 1e-20f))
			continue;
		float r = 1.0f / det;
		vec3 dpdu = v3_scale(v3_sub(v3_scale(e1, dv2), v3_scale(e2, dv1)), r);
		vec3 dpdv = v3_scale(v3_sub(v3_scale(e2, du1), v3_scale(e1, du2)), r);
		for (int k = 0; k < 3; k++) {
			tu[m->indices[i + k]] = v3_add(tu[m->indices[i + k]], dpdu);
			tv[m->indices[i + k]] = v3_add(tv[m->indices[i + k]], dpdv);
		}
	}
	for (uint32_t v = 0; v < m->vertex_count; v++) {
		struct aa_vertex *x = &m->vertices[v];
		if (x->tangent[3] != 0.0f)
			continue;
		vec3 n = v3(x->normal[0], x->normal[1], x->normal[2]);
		vec3 t = v3_sub(tu[v], v3_scale(n, v3_dot(n, tu[v])));
		vec3 any = fabsf(n.x) < 0.9f ? v3(1, 0, 0) : v3(0, 1, 0);
		t = normalized_or(t, v3_normalize(v3_cross(any, n)));
		float w = v3_dot(v3_cross(n, t), v3_scale(tv[v], -1.0f)) < 0 ? -1.0f : 1.0f;
		x->tangent[0] = t.x, x->tangent[1] = t.y, x->tangent[2] = t.z, x->tangent[3] = w;
	}
	free(tu);
}

/* ---------------------------------------------------------------- animation clips */

static int build_rig(struct loader *L, int *rig_index)
{
	struct aa_scene *sc = L->scene;
	if (sc->rig_count >= AA_SCENE_MAX_ALL_MESHES)
		return FAIL(L, AA_ERR_LIMIT, "too many animated mesh files in one scene");
	struct aa_rig *grown = realloc(sc->rigs, (size_t)(sc->rig_count + 1) * sizeof *grown);
	if (!grown)
		return FAIL(L, AA_ERR_INTERNAL, "out of memory");
	sc->rigs = grown;
	struct aa_rig *rig = &sc->rigs[sc->rig_count++];
	memset(rig, 0, sizeof *rig);
	snprintf(rig->source, sizeof rig->source, "%s", L->shown);
	rig->node_count = L->node_count;
	rig->nodes = calloc((size_t)L->node_count, sizeof *rig->nodes);
	rig->joint_count = L->joint_count;
	rig->joint_node = L->joint_node, L->joint_node = NULL;
	rig->inverse_bind = L->joint_ibm, L->joint_ibm = NULL;
	if (!rig->nodes)
		return FAIL(L, AA_ERR_INTERNAL, "out of memory");
	for (int i = 0; i < L->node_count; i++) {
		struct aiVector3D scale, position;
		struct aiQuaternion rotation;
		aiDecomposeMatrix(&L->nodes[i].node->mTransformation, &scale, &rotation, &position);
		struct aa_rig_node *n = &rig->nodes[i];
		n->parent = L->nodes[i].parent;
		n->translation[0] = position.x, n->translation[1] = position.y, n->translation[2] = position.z;
		n->rotation[0] = rotation.x, n->rotation[1] = rotation.y, n->rotation[2] = rotation.z;
		n->rotation[3] = rotation.w;
		n->scale[0] = scale.x, n->scale[1] = scale.y, n->scale[2] = scale.z;
	}
	unsigned clips = L->ai->mNumAnimations;
	if (clips && !(rig->clips = calloc(clips, sizeof *rig->clips)))
		return FAIL(L, AA_ERR_INTERNAL, "out of memory");
	for (unsigned a = 0; a < clips; a++) {
		const struct aiAnimation *anim = L->ai->mAnimations[a];
		struct aa_rig_clip *clip = &rig->clips[rig->clip_count++];
		if (anim->mName.length)
			snprintf(clip->name, sizeof clip->name, "%.63s", anim->mName.data);
		else
			snprintf(clip->name, sizeof clip->name, "animation%u", a);
		double ticks = anim->mTicksPerSecond > 0 ? anim->mTicksPerSecond : 25.0; /* assimp's default */
		if (!(clip->channels = calloc((size_t)anim->mNumChannels * 3 + 1, sizeof *clip->channels)))
			return FAIL(L, AA_ERR_INTERNAL, "out of memory");
		for (unsigned c = 0; c < anim->mNumChannels; c++) {
			const struct aiNodeAnim *na = anim->mChannels[c];
			int node = find_node(L, na->mNodeName.data);
			if (node < 0)
				continue;
			for (int path = 0; path < 3; path++) {
				unsigned keys = path == 0 ? na->mNumPositionKeys : path == 1 ? na->mNumRotationKeys
											: na->mNumScalingKeys;
				if (!keys)
					continue;
				struct aa_rig_channel *ch = &clip->channels[clip->channel_count++];
				int width = path == 1 ? 4 : 3;
				ch->node = node;
				ch->path = path == 0 ? AA_CHANNEL_TRANSLATION : path == 1 ? AA_CHANNEL_ROTATION : AA_CHANNEL_SCALE;
				ch->key_count = (int)keys;
				ch->times = malloc(keys * sizeof *ch->times);
				ch->values = malloc(keys * (size_t)width * sizeof *ch->values);
				if (!ch->times || !ch->values)
					return FAIL(L, AA_ERR_INTERNAL, "out of memory");
				for (unsigned k = 0; k < keys; k++) {
					double time;
					float v[4];
					if (path == 1) {
						const struct aiQuatKey *q = &na->mRotationKeys[k];
						time = q->mTime;
						v[0] = q->mValue.x, v[1] = q->mValue.y, v[2] = q->mValue.z, v[3] = q->mValue.w;
					} else {
						const struct aiVectorKey *q = path == 0 ? &na->mPositionKeys[k] : &na->mScalingKeys[k];
						time = q->mTime;
						v[0] = q->mValue.x, v[1] = q->mValue.y, v[2] = q->mValue.z;
					}
					ch->times[k] = (float)(time / ticks);
					for (int e = 0; e < width; e++)
						if (!isfinite(v[e]) || fabsf(v[e]) > POSITION_MAX)
							return FAIL(L, AA_ERR_INVALID, "animation '%s' channel '%s' has a value that "
								    "is not a finite number within %g", clip->name,
								    na->mNodeName.data, POSITION_MAX);
					memcpy(ch->values + (size_t)k * width, v, (size_t)width * sizeof *v);
					if (!isfinite(ch->times[k]) || (k > 0 && ch->times[k] < ch->times[k - 1]))
						return FAIL(L, AA_ERR_INVALID, "animation '%s' channel '%s': key times must "
							    "increase", clip->name, na->mNodeName.data);
					if (ch->times[k] > clip->duration)
						clip->duration = ch->times[k];
				}
			}
		}
	}
	*rig_index = sc->rig_count - 1;
	return 0;
}

/* ---------------------------------------------------------------- the whole file */

static int add_mesh_slot(struct loader *L)
{
	struct aa_scene *sc = L->scene;
	if (sc->mesh_count >= AA_SCENE_MAX_ALL_MESHES)
		return FAIL(L, AA_ERR_LIMIT, "the scene has more than %d meshes with the parts of its mesh files (one "
			    "per material)", AA_SCENE_MAX_ALL_MESHES);
	struct aa_mesh *grown = realloc(sc->meshes, (size_t)(sc->mesh_count + 1) * sizeof *grown);
	if (!grown)
		return FAIL(L, AA_ERR_INTERNAL, "out of memory");
	sc->meshes = grown;
	memset(&sc->meshes[sc->mesh_count], 0, sizeof *sc->meshes);
	sc->meshes[sc->mesh_count].rig = -1;
	sc->meshes[sc->mesh_count].file_material = -1;
	return sc->mesh_count++;
}

static int build_parts(struct loader *L, int *first_part)
{
	struct aa_scene *sc = L->scene;
	bool dropped_weights = false;
	*first_part = -1;
	for (int i = 0; i < L->part_count; i++) {
		struct part *p = &L->parts[i];
		int slot = add_mesh_slot(L);
		if (slot < 0)
			return -1;
		if (*first_part < 0)
			*first_part = slot;
		struct aa_mesh *m = &sc->meshes[slot];
		const char *base = strrchr(L->shown, '/');
		snprintf(m->name, sizeof m->name, "%s%s%d", base ? base + 1 : L->shown, i ? "#" : "", i);
		if (!i)
			m->name[strlen(m->name) - 1] = '\0'; /* the first part carries the file's name alone */
		m->vertices = calloc(p->vertex_count ? p->vertex_count : 1, sizeof *m->vertices);
		m->indices = malloc((p->index_count ? p->index_count : 1) * sizeof *m->indices);
		if (p->rigged)
			m->skin = calloc(p->vertex_count ? p->vertex_count : 1, sizeof *m->skin);
		if (!m->vertices || !m->indices || (p->rigged && !m->skin))
			return FAIL(L, AA_ERR_INTERNAL, "out of memory");
		p->mesh = slot;
	}
	for (int n = 0; n < L->node_count; n++) {
		const struct aiNode *node = L->nodes[n].node;
		for (unsigned k = 0; k < node->mNumMeshes; k++) {
			const struct aiMesh *mesh = L->ai->mMeshes[node->mMeshes[k]];
			if (is_triangles(mesh) && append_mesh(L, part_for(L, mesh->mMaterialIndex), n, mesh, &dropped_weights))
				return -1;
		}
	}
	if (dropped_weights)
		aa_scene_warn(sc, "%s: some vertices have more than 4 joints: the 4 largest weights are kept", L->shown);
	sc->meshes[*first_part].part_count = L->part_count;
	return 0;
}

/* assimp's I/O system: every file it opens (the mesh, and what the mesh names: .mtl, .bin, ...) is opened
 * through aa_file_open_regular, so that a FIFO or a device it meets is refused instead of blocking. */
static size_t ai_read(struct aiFile *f, char *buf, size_t size, size_t count)
{
	return fread(buf, size, count, (FILE *)f->UserData);
}

static size_t ai_write(struct aiFile *f, const char *buf, size_t size, size_t count)
{
	(void)f; (void)buf; (void)size; (void)count;
	return 0;
}

static size_t ai_tell(struct aiFile *f)
{
	long at = ftell((FILE *)f->UserData);
	return at < 0 ? 0 : (size_t)at;
}

static size_t ai_size(struct aiFile *f)
{
	struct stat st;
	return fstat(fileno((FILE *)f->UserData), &st) == 0 ? (size_t)st.st_size : 0;
}

static aiReturn ai_seek(struct aiFile *f, size_t offset, enum aiOrigin origin)
{
	int whence = origin == aiOrigin_SET ? SEEK_SET : origin == aiOrigin_CUR ? SEEK_CUR : SEEK_END;
	return fseek((FILE *)f->UserData, (long)offset, whence) == 0 ? aiReturn_SUCCESS : aiReturn_FAILURE;
}

static void ai_flush(struct aiFile *f)
{
	(void)f;
}

static struct aiFile *ai_open(struct aiFileIO *io, const char *path, const char *mode)
{
	(void)io;
	if (strchr(mode, 'w') || strchr(mode, 'a') || strchr(mode, '+'))
		return NULL; /* reading only */
	FILE *fp = aa_file_fopen_regular(path, "", NULL);
	struct aiFile *f = fp ? calloc(1, sizeof *f) : NULL;
	if (!f) {
		if (fp)
			fclose(fp);
		return NULL;
	}
	*f = (struct aiFile){.ReadProc = ai_read, .WriteProc = ai_write, .TellProc = ai_tell, .FileSizeProc = ai_size,
			     .SeekProc = ai_seek, .FlushProc = ai_flush, .UserData = (aiUserData)fp};
	return f;
}

static void ai_close(struct aiFileIO *io, struct aiFile *f)
{
	(void)io;
	if (f) {
		fclose((FILE *)f->UserData);
		free(f);
	}
}

static struct aiFileIO ai_files = {.OpenProc = ai_open, .CloseProc = ai_close};

int aa_mesh_file_load(struct sj *s, struct aa_scene *scene, const char *path, const char *shown,
		      const char *base_dir, const struct aa_mesh_file_options *options, uint64_t max_triangles)
{
	struct loader L = {.s = s, .scene = scene, .path = path, .shown = shown, .base_dir = base_dir,
			   .options = options};
	struct stat st;
	struct aa_error oerr = {0};
	int fd = aa_file_open_regular(path, "", &oerr); /* never blocks on a FIFO */
	if (fd < 0 && oerr.code == AA_ERR_INVALID)
		return sj_fail(s, AA_ERR_INVALID, "mesh file '%s' is not a regular file (a FIFO, socket or device)", shown);
	if (fd < 0 || fstat(fd, &st) != 0) {
		if (fd >= 0)
			close(fd);
		return sj_fail(s, AA_ERR_NOT_FOUND, "mesh file '%s' not found", shown);
	}
	close(fd);
	if ((uint64_t)st.st_size > AA_MESH_FILE_MAX_BYTES)
		return sj_fail(s, AA_ERR_LIMIT, "mesh file '%s' is %lld bytes, over the limit of %u", shown,
			       (long long)st.st_size, (unsigned)AA_MESH_FILE_MAX_BYTES);
	for (int i = 0; i < scene->texture_count; i++)
		L.texture_bytes += aa_texture_bytes(scene->textures[i].width, scene->textures[i].height);
	L.gltf = aa_gltf_file_is_gltf(path);
	int first_part = -1, rc = 0;
	if (L.gltf)
		rc = aa_gltf_check(s, scene, path, shown, base_dir, &L.gltf_info);
	else /* OBJ, OFF, PLY, STL: read by aalab first (mesh_text_check.c); any other format is refused */
		rc = aa_mesh_text_check_file(s, scene, path, shown, base_dir, options->missing_warn);
	if (rc == 0 && !(L.ai = aiImportFileEx(path, 0, &ai_files)))
		rc = import_error(&L);
	if (rc == 0)
		rc = check_raw(&L);
	/* FlipUVs puts v = 0 at the top of the image, as glTF and aalab's textures have it */
	/* The file is read again with the post-processing, not post-processed in place: when
	 * aiApplyPostProcessing fails, assimp 5.2 crashes freeing the scene (fuzz_mesh), while a failing
	 * aiImportFile returns NULL. The checks above ran on the raw import. */
	if (rc == 0) {
		aiReleaseImport(L.ai);
		if (!(L.ai = aiImportFileEx(path, aiProcess_Triangulate | aiProcess_SortByPType | aiProcess_GenSmoothNormals |
							aiProcess_JoinIdenticalVertices | aiProcess_FlipUVs, &ai_files)))
			rc = import_error(&L);
	}
	if (rc == 0)
		rc = build_nodes(&L) || size_parts(&L, max_triangles) || build_parts(&L, &first_part);
	bool rigged = false;
	for (int i = 0; rc == 0 && i < L.part_count; i++)
		rigged |= L.parts[i].rigged;
	int rig = -1;
	if (rc == 0 && rigged)
		rc = build_rig(&L, &rig);
	for (int i = 0; rc == 0 && i < L.part_count; i++) {
		struct part *p = &L.parts[i];
		struct aa_mesh *m = &scene->meshes[p->mesh];
		m->rig = p->rigged ? rig : -1;
		int material = -1;
		if (options->materials && !aa_mesh_file_is_default_material(&L, p->material)) {
			rc = aa_mesh_file_add_material(&L, p->material, &material);
			if (rc == 0) {
				struct aa_material *mat = &scene->materials[material];
				mat->vertex_color = p->colors;
			}
		}
		generate_tangents(m, material >= 0 && scene->materials[material].maps[AA_MAP_NORMAL] >= 0);
		m->file_material = material;
		aa_mesh_compute_bounds(m);
	}
	if (L.ai)
		aiReleaseImport(L.ai);
	aa_gltf_info_free(&L.gltf_info);
	free(L.nodes);
	free(L.parts);
	free(L.joint_node);
	free(L.joint_ibm);
	return rc ? -1 : first_part;
}
