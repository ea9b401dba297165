/* The key of a stored reference frame (docs/reference-cache.md): the SHA-256 of
 * everything that decides its pixels, made of named parts so that a user can see why a lookup missed
 * (aalab run --explain-key). Methods are not part of it. */
#ifndef AA_REFERENCE_KEY_H
#define AA_REFERENCE_KEY_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "reference/reference.h"

/* What a key is made of, gathered from a job's frame (aa_reference_key_inputs_of) or set by tests. */
#define AA_REFERENCE_KEY_MAX_LEVELS 16
struct aa_reference_key_inputs {
	bool scene_known;             /* false: a scene built in code, or a file changed while loading */
	uint8_t scene_sha256[32];     /* scene text and every file the load read (aa_scene_sources_digest) */
	int scene_files;
	struct aa_camera camera;      /* as resolved for the frame */
	double time;                  /* seconds: animation */
	int width, height;
	bool auto_samples;            /* reference.samples "auto": an entry per level reached */
	int levels[AA_REFERENCE_KEY_MAX_LEVELS]; /* the sums an entry holds: fixed N: N/2 and N; auto: the
						   * levels from the first to this entry's (8, 16, ...) */
	int level_count;
	const char *pattern;          /* the results' name of the sample positions */
	const float (*offsets)[2];    /* the positions themselves, as many as the last level */
	int batch;                    /* renders added to the sum per summing pass (the order of additions) */
	const char *alpha_rule;
	float lod_bias;
	uint8_t shaders_sha256[32];   /* every pipeline the reference draws with (SPIR-V + specialization) */
	int shader_pipelines;
	const char *code;             /* the digest of the C that decides pixels, and library versions */
	uint32_t vendor_id, device_id;
	const char *device_name;
	const uint8_t *pipeline_cache_uuid; /* 16 bytes: the driver build */
	uint32_t driver_version, api_version;
	const char *driver_build;      /* the driver's name and build */
};

#define AA_REFERENCE_KEY_PARTS 13
struct aa_reference_key_part {
	const char *name;
	uint8_t sha256[32];
	char value[200];              /* what the part is, in words */
};
struct aa_reference_key {
	int part_count;
	struct aa_reference_key_part parts[AA_REFERENCE_KEY_PARTS];
	uint8_t sha256[32];
	char hex[65];
};

void aa_reference_key_make(const struct aa_reference_key_inputs *in, struct aa_reference_key *key);

/* The inputs of the current frame of a job (ref created, aa_renderer_set_frame done): levels are left
 * empty (aa_reference_key_levels sets them). False when the scene cannot be keyed (content unknown). */
struct aa_frame_ctx;
bool aa_reference_key_inputs_of(const struct aa_reference *ref, const struct aa_frame_ctx *ctx,
				const char *pattern, struct aa_reference_key_inputs *in);
/* in->levels: a fixed reference of ref->samples (N/2 and N), or an auto reference's levels up to n. */
void aa_reference_key_levels(struct aa_reference_key_inputs *in, const struct aa_reference *ref, bool auto_samples,
			     int n);
/* The digest of the C that decides a reference's pixels, as 64 hex digits and the library versions. */
const char *aa_reference_code_version(void);

/* Prints the key's parts, one a line: "  name  sha256-prefix  value". */
void aa_reference_key_print(const struct aa_reference_key *key, FILE *out);

#endif
