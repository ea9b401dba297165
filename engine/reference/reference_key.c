/* The key of a stored reference frame (reference_key.h): one SHA-256 per part, and the key over the
 * parts. Each part hashes the bytes that decide it, and says in words what it is. */
#include <math.h>
#include <string.h>

#include <assimp/version.h>
#include <png.h>

#include "reference/reference_key.h"
#include "render/renderer.h"
#include "util/sha256.h"
#include "reference_code.h" /* AA_REFERENCE_CODE_SHA256: generated from the sources (local.mk) */

struct part {
	struct aa_sha256 h;
	struct aa_reference_key_part *out;
};

static struct part begin(struct aa_reference_key *key, const char *name)
{
	struct part p = {.out = &key->parts[key->part_count++]};
	p.out->name = name;
	aa_sha256_init(&p.h);
	aa_sha256_update(&p.h, name, strlen(name) + 1);
	return p;
}

static void bytes(struct part *p, const void *data, size_t size)
{
	aa_sha256_update(&p->h, data, size);
}

static void text(struct part *p, const char *s)
{
	bytes(p, s ? s : "", strlen(s ? s : "") + 1);
}

static void end(struct part *p)
{
	aa_sha256_final(&p->h, p->out->sha256);
}

static void scene_part(struct aa_reference_key *key, const struct aa_reference_key_inputs *in)
{
	struct part p = begin(key, "scene");
	bytes(&p, in->scene_sha256, 32);
	char hex[65];
	aa_sha256_digest_hex(in->scene_sha256, hex);
	snprintf(p.out->value, sizeof p.out->value, "scene file and %d file%s it loads: sha256 %.16s", in->scene_files,
		 in->scene_files == 1 ? "" : "s", hex);
	end(&p);
}

static void camera_part(struct aa_reference_key *key, const struct aa_reference_key_inputs *in)
{
	struct part p = begin(key, "camera");
	const struct aa_camera *c = &in->camera;
	int32_t projection = (int32_t)c->projection;
	bytes(&p, c->origin, sizeof c->origin);
	float v[13] = {c->position.x, c->position.y, c->position.z, c->target.x, c->target.y, c->target.z,
		       c->up.x, c->up.y, c->up.z, c->fov_y_degrees, c->ortho_height, c->near_plane, c->far_plane};
	bytes(&p, v, sizeof v);
	bytes(&p, &projection, sizeof projection);
	snprintf(p.out->value, sizeof p.out->value, "at (%.4g, %.4g, %.4g) towards (%.4g, %.4g, %.4g), %s %.4g",
		 c->origin[0] + c->position.x, c->origin[1] + c->position.y, c->origin[2] + c->position.z,
		 c->origin[0] + c->target.x, c->origin[1] + c->target.y, c->origin[2] + c->target.z,
		 c->projection == AA_PROJECTION_ORTHOGRAPHIC ? "height" : "fov", c->projection ==
		 AA_PROJECTION_ORTHOGRAPHIC ? c->ortho_height : c->fov_y_degrees);
	end(&p);
}

static void time_part(struct aa_reference_key *key, const struct aa_reference_key_inputs *in)
{
	struct part p = begin(key, "time");
	bytes(&p, &in->time, sizeof in->time);
	snprintf(p.out->value, sizeof p.out->value, "%.17g s", in->time);
	end(&p);
}

static void size_part(struct aa_reference_key *key, const struct aa_reference_key_inputs *in)
{
	struct part p = begin(key, "size");
	int32_t v[2] = {in->width, in->height};
	bytes(&p, v, sizeof v);
	snprintf(p.out->value, sizeof p.out->value, "%dx%d", in->width, in->height);
	end(&p);
}

static void samples_part(struct aa_reference_key *key, const struct aa_reference_key_inputs *in)
{
	struct part p = begin(key, "samples");
	text(&p, in->auto_samples ? "auto" : "fixed");
	int32_t count = in->level_count;
	bytes(&p, &count, sizeof count);
	char list[120] = "";
	for (int i = 0; i < in->level_count; i++) {
		int32_t n = in->levels[i];
		bytes(&p, &n, sizeof n);
		size_t len = strlen(list);
		snprintf(list + len, sizeof list - len, "%s%d", i ? ", " : "", in->levels[i]);
	}
	if (in->auto_samples)
		snprintf(p.out->value, sizeof p.out->value, "auto, the sum of levels %s", list);
	else
		snprintf(p.out->value, sizeof p.out->value, "%d (sums of %s)", in->level_count ?
			 in->levels[in->level_count - 1] : 0, list);
	end(&p);
}

static void pattern_part(struct aa_reference_key *key, const struct aa_reference_key_inputs *in)
{
	struct part p = begin(key, "pattern");
	text(&p, in->pattern);
	/* the positions themselves: a changed sequence under the same name changes the key too */
	const int n = in->level_count ? in->levels[in->level_count - 1] : 0;
	if (in->offsets && n > 0)
		bytes(&p, in->offsets, (size_t)n * sizeof in->offsets[0]);
	snprintf(p.out->value, sizeof p.out->value, "%s, %d positions", in->pattern ? in->pattern : "", n);
	end(&p);
}

static void batch_part(struct aa_reference_key *key, const struct aa_reference_key_inputs *in)
{
	struct part p = begin(key, "accumulation");
	int32_t batch = in->batch;
	bytes(&p, &batch, sizeof batch);
	snprintf(p.out->value, sizeof p.out->value, "float sum, %d render%s per summing pass", in->batch,
		 in->batch == 1 ? "" : "s");
	end(&p);
}

static void alpha_part(struct aa_reference_key *key, const struct aa_reference_key_inputs *in)
{
	struct part p = begin(key, "alpha-rule");
	text(&p, in->alpha_rule);
	snprintf(p.out->value, sizeof p.out->value, "%s", in->alpha_rule ? in->alpha_rule : "");
	end(&p);
}

static void lod_part(struct aa_reference_key *key, const struct aa_reference_key_inputs *in)
{
	struct part p = begin(key, "lod-bias");
	bytes(&p, &in->lod_bias, sizeof in->lod_bias);
	snprintf(p.out->value, sizeof p.out->value, "%.9g mip levels", in->lod_bias);
	end(&p);
}

static void shaders_part(struct aa_reference_key *key, const struct aa_reference_key_inputs *in)
{
	struct part p = begin(key, "shaders");
	bytes(&p, in->shaders_sha256, 32);
	char hex[65];
	aa_sha256_digest_hex(in->shaders_sha256, hex);
	snprintf(p.out->value, sizeof p.out->value, "SPIR-V and specialization of %d pipelines: sha256 %.16s",
		 in->shader_pipelines, hex);
	end(&p);
}

static void code_part(struct aa_reference_key *key, const struct aa_reference_key_inputs *in)
{
	struct part p = begin(key, "code");
	text(&p, in->code);
	snprintf(p.out->value, sizeof p.out->value, "%s", in->code ? in->code : "");
	end(&p);
}

static void device_part(struct aa_reference_key *key, const struct aa_reference_key_inputs *in)
{
	struct part p = begin(key, "device");
	uint32_t ids[2] = {in->vendor_id, in->device_id};
	bytes(&p, ids, sizeof ids);
	text(&p, in->device_name);
	snprintf(p.out->value, sizeof p.out->value, "%s (vendor 0x%04x, device 0x%04x)",
		 in->device_name ? in->device_name : "", in->vendor_id, in->device_id);
	end(&p);
}

static void driver_part(struct aa_reference_key *key, const struct aa_reference_key_inputs *in)
{
	struct part p = begin(key, "driver");
	uint32_t versions[2] = {in->driver_version, in->api_version};
	bytes(&p, versions, sizeof versions);
	text(&p, in->driver_build);
	static const uint8_t none[16];
	bytes(&p, in->pipeline_cache_uuid ? in->pipeline_cache_uuid : none, 16);
	snprintf(p.out->value, sizeof p.out->value, "%s, version 0x%x, Vulkan %u.%u.%u",
		 in->driver_build && in->driver_build[0] ? in->driver_build : "(no name)", in->driver_version,
		 VK_API_VERSION_MAJOR(in->api_version), VK_API_VERSION_MINOR(in->api_version),
		 VK_API_VERSION_PATCH(in->api_version));
	end(&p);
}

void aa_reference_key_make(const struct aa_reference_key_inputs *in, struct aa_reference_key *key)
{
	memset(key, 0, sizeof *key);
	scene_part(key, in);
	camera_part(key, in);
	time_part(key, in);
	size_part(key, in);
	samples_part(key, in);
	pattern_part(key, in);
	batch_part(key, in);
	alpha_part(key, in);
	lod_part(key, in);
	shaders_part(key, in);
	code_part(key, in);
	device_part(key, in);
	driver_part(key, in);
	struct aa_sha256 h;
	aa_sha256_init(&h);
	aa_sha256_update(&h, "aalab reference key 1", 22);
	for (int i = 0; i < key->part_count; i++)
		aa_sha256_update(&h, key->parts[i].sha256, 32);
	aa_sha256_final(&h, key->sha256);
	aa_sha256_digest_hex(key->sha256, key->hex);
}

const char *aa_reference_code_version(void)
{
	static char version[160];
	if (!version[0])
		snprintf(version, sizeof version, "sources sha256 %.16s, assimp %u.%u.%u, libpng %s",
			 AA_REFERENCE_CODE_SHA256, aiGetVersionMajor(), aiGetVersionMinor(), aiGetVersionRevision(),
			 png_get_libpng_ver(NULL));
	return version;
}

/* Every pipeline a reference draws with: the scene pass's for each material class of its target kind, the
 * shadow map's, and the summing passes'. */
static void shaders_digest(const struct aa_reference *ref, uint8_t out[32], int *count)
{
	const struct aa_renderer *r = ref->r;
	struct aa_sha256 h;
	aa_sha256_init(&h);
	*count = 0;
	const struct aa_gpu_pipeline *list[2 * AA_MAX_MATERIAL_CLASSES + 4];
	int n = 0;
	const struct aa_scene_variant *v = &r->variants[ref->sum.targets[0].variant];
	for (int c = 0; c < r->material_class_count; c++) {
		list[n++] = &v->opaque[c];
		list[n++] = &v->cutout[c];
	}
	list[n++] = &r->shadow_pipeline;
	list[n++] = &r->shadow_cutout_pipeline;
	list[n++] = &ref->sum.add[0].pipeline;
	list[n++] = &ref->sum.add[1].pipeline;
	for (int i = 0; i < n; i++) {
		if (!list[i]->pipeline)
			continue;
		aa_sha256_update(&h, &i, sizeof i);
		aa_sha256_update(&h, list[i]->code_sha256, 32);
		(*count)++;
	}
	aa_sha256_final(&h, out);
}

bool aa_reference_key_inputs_of(const struct aa_reference *ref, const struct aa_frame_ctx *ctx,
				const char *pattern, struct aa_reference_key_inputs *in)
{
	const struct aa_renderer *r = ref->r;
	const struct aa_gpu *gpu = r->gpu;
	memset(in, 0, sizeof *in);
	in->scene_known = r->scene->content_known;
	memcpy(in->scene_sha256, r->scene->content_sha256, 32);
	in->scene_files = r->scene->source_count;
	in->camera = ctx->camera;
	in->time = ctx->time;
	in->width = r->width;
	in->height = r->height;
	in->pattern = pattern;
	in->offsets = (const float (*)[2])ref->offsets;
	in->batch = ref->sum.batch;
	in->alpha_rule = AA_REFERENCE_ALPHA_RULE;
	in->lod_bias = ref->lod_bias;
	shaders_digest(ref, in->shaders_sha256, &in->shader_pipelines);
	in->code = aa_reference_code_version();
	in->vendor_id = gpu->properties.vendorID;
	in->device_id = gpu->properties.deviceID;
	in->device_name = gpu->properties.deviceName;
	in->pipeline_cache_uuid = gpu->properties.pipelineCacheUUID;
	in->driver_version = gpu->properties.driverVersion;
	in->api_version = gpu->properties.apiVersion;
	in->driver_build = gpu->driver_build;
	return in->scene_known;
}

void aa_reference_key_levels(struct aa_reference_key_inputs *in, const struct aa_reference *ref, bool auto_samples,
			     int n)
{
	in->auto_samples = auto_samples;
	in->level_count = 0;
	if (!auto_samples) {
		in->levels[in->level_count++] = ref->samples / 2;
		in->levels[in->level_count++] = ref->samples;
		return;
	}
	int level = ref->samples < AA_REFERENCE_AUTO_START ? ref->samples : AA_REFERENCE_AUTO_START;
	in->levels[in->level_count++] = level / 2; /* the first level's entry holds its N/2 too */
	for (;;) {
		in->levels[in->level_count++] = level;
		if (level >= n || level >= ref->samples || in->level_count == AA_REFERENCE_KEY_MAX_LEVELS)
			break;
		level = 2 * level <= ref->samples ? 2 * level : ref->samples;
	}
}

void aa_reference_key_print(const struct aa_reference_key *key, FILE *out)
{
	for (int i = 0; i < key->part_count; i++) {
		char hex[65];
		aa_sha256_digest_hex(key->parts[i].sha256, hex);
		fprintf(out, "  %-13s %.12s  %s\n", key->parts[i].name, hex, key->parts[i].value);
	}
	fprintf(out, "  %-13s %.12s  (sha256 %s)\n", "key", key->hex, key->hex);
}
