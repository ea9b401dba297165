/* Skins and animation of mesh files, on the CPU: a rig's nodes posed at a clip's time, each joint's matrix
 * (its node's world matrix times its inverse bind matrix, as glTF 2.0 defines skinning) and the skinned
 * vertices of a mesh part. The renderer calls these once per frame for each moving part (and once more for
 * the previous frame, for velocity). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scene/scene.h"

void aa_rig_free(struct aa_rig *rig)
{
	if (!rig)
		return;
	for (int c = 0; c < rig->clip_count; c++) {
		for (int k = 0; k < rig->clips[c].channel_count; k++) {
			free(rig->clips[c].channels[k].times);
			free(rig->clips[c].channels[k].values);
		}
		free(rig->clips[c].channels);
	}
	free(rig->clips);
	free(rig->nodes);
	free(rig->joint_node);
	free(rig->inverse_bind);
	memset(rig, 0, sizeof *rig);
}

/* T * R * S from translation, unit quaternion (x, y, z, w) and scale; column-major. */
static mat4 trs_matrix(const float t[3], const float q[4], const float s[3])
{
	float x = q[0], y = q[1], z = q[2], w = q[3];
	mat4 m = mat4_identity();
	m.m[0] = (1 - 2 * (y * y + z * z)) * s[0];
	m.m[1] = (2 * (x * y + z * w)) * s[0];
	m.m[2] = (2 * (x * z - y * w)) * s[0];
	m.m[4] = (2 * (x * y - z * w)) * s[1];
	m.m[5] = (1 - 2 * (x * x + z * z)) * s[1];
	m.m[6] = (2 * (y * z + x * w)) * s[1];
	m.m[8] = (2 * (x * z + y * w)) * s[2];
	m.m[9] = (2 * (y * z - x * w)) * s[2];
	m.m[10] = (1 - 2 * (x * x + y * y)) * s[2];
	m.m[12] = t[0], m.m[13] = t[1], m.m[14] = t[2];
	return m;
}

/* A channel's value at time tau (seconds, already inside the clip): linear between keys, spherical for
 * rotations (the shorter way), held before the first key and after the last. */
static void sample_channel(const struct aa_rig_channel *c, double tau, float *out)
{
	int n = c->path == AA_CHANNEL_ROTATION ? 4 : 3;
	if (c->key_count == 1 || tau <= c->times[0]) {
		memcpy(out, c->values, (size_t)n * sizeof *out);
		return;
	}
	if (tau >= c->times[c->key_count - 1]) {
		memcpy(out, c->values + (size_t)(c->key_count - 1) * n, (size_t)n * sizeof *out);
		return;
	}
	int lo = 0, hi = c->key_count - 1; /* times[lo] <= tau < times[hi] */
	while (hi - lo > 1) {
		int mid = (lo + hi) / 2;
		if (c->times[mid] <= tau)
			lo = mid;
		else
			hi = mid;
	}
	double span = (double)c->times[hi] - c->times[lo];
	float f = span > 0 ? (float)((tau - c->times[lo]) / span) : 0.0f;
	const float *a = c->values + (size_t)lo * n, *b = c->values + (size_t)hi * n;
	if (n == 3) {
		for (int k = 0; k < 3; k++)
			out[k] = a[k] + (b[k] - a[k]) * f;
		return;
	}
	float d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3], sign = 1.0f;
	if (d < 0) {
		d = -d;
		sign = -1.0f;
	}
	float wa = 1.0f - f, wb = f;
	if (d < 0.9995f) {
		float angle = acosf(d), s = sinf(angle);
		wa = sinf((1.0f - f) * angle) / s;
		wb = sinf(f * angle) / s;
	}
	float len = 0;
	for (int k = 0; k < 4; k++) {
		out[k] = wa * a[k] + sign * wb * b[k];
		len += out[k] * out[k];
	}
	len = len > 0 ? 1.0f / sqrtf(len) : 1.0f;
	for (int k = 0; k < 4; k++)
		out[k] *= len;
}

void aa_rig_pose(const struct aa_rig *rig, const struct aa_pose *pose, double t, mat4 *joint_matrices)
{
	int n = rig->node_count;
	struct aa_rig_node *local = malloc((size_t)(n ? n : 1) * sizeof *local);
	mat4 *world = malloc((size_t)(n ? n : 1) * sizeof *world);
	if (!local || !world) { /* no pose without memory: the bind pose */
		for (int j = 0; j < rig->joint_count; j++)
			joint_matrices[j] = mat4_identity();
		free(local);
		free(world);
		return;
	}
	memcpy(local, rig->nodes, (size_t)n * sizeof *local);
	if (pose && pose->clip >= 0 && pose->clip < rig->clip_count) {
		const struct aa_rig_clip *clip = &rig->clips[pose->clip];
		double tau = pose->clip_time + pose->clip_speed * (isfinite(t) ? t : 0.0);
		/* clips loop (the end itself shows the last pose); reduced in double so long runs stay smooth */
		if (clip->duration > 0 && (tau > clip->duration || tau < 0)) {
			tau = fmod(tau, clip->duration);
			if (tau < 0)
				tau += clip->duration;
		}
		for (int k = 0; k < clip->channel_count; k++) {
			const struct aa_rig_channel *c = &clip->channels[k];
			if (c->node < 0 || c->node >= n || c->key_count < 1)
				continue;
			float *dst = c->path == AA_CHANNEL_TRANSLATION ? local[c->node].translation
				     : c->path == AA_CHANNEL_ROTATION  ? local[c->node].rotation
								       : local[c->node].scale;
			sample_channel(c, tau, dst);
		}
	}
	for (int i = 0; i < n; i++) { /* parents come before their children */
		mat4 m = trs_matrix(local[i].translation, local[i].rotation, local[i].scale);
		world[i] = local[i].parent >= 0 ? mat4_mul(world[local[i].parent], m) : m;
	}
	for (int j = 0; j < rig->joint_count; j++) {
		int node = rig->joint_node[j];
		joint_matrices[j] = node >= 0 && node < n ? mat4_mul(world[node], rig->inverse_bind[j]) : mat4_identity();
	}
	free(local);
	free(world);
}

void aa_mesh_skin(const struct aa_mesh *mesh, const mat4 *joint_matrices, struct aa_vertex *out)
{
	for (uint32_t v = 0; v < mesh->vertex_count; v++) {
		const struct aa_vertex *in = &mesh->vertices[v];
		const struct aa_skin_weights *sw = &mesh->skin[v];
		float m[16] = {0};
		for (int k = 0; k < 4; k++) {
			float w = sw->weights[k];
			if (w == 0.0f)
				continue;
			const float *j = joint_matrices[sw->joints[k]].m;
			for (int e = 0; e < 16; e++)
				m[e] += w * j[e];
		}
		const float *p = in->position, *nn = in->normal, *tt = in->tangent;
		out[v] = *in;
		for (int r = 0; r < 3; r++) {
			out[v].position[r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
			out[v].normal[r] = m[r] * nn[0] + m[4 + r] * nn[1] + m[8 + r] * nn[2];
			out[v].tangent[r] = m[r] * tt[0] + m[4 + r] * tt[1] + m[8 + r] * tt[2];
		}
		/* the blended matrix's own 3x3 for directions (exact for rigid joints), renormalised */
		for (int d = 0; d < 2; d++) {
			float *x = d ? out[v].tangent : out[v].normal;
			float len = sqrtf(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
			if (len > 1e-20f && isfinite(len))
				for (int k = 0; k < 3; k++)
					x[k] /= len;
			else
				memcpy(x, d ? in->tangent : in->normal, 3 * sizeof *x);
		}
	}
}
