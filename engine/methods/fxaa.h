/* What the two FXAA methods share (fxaa.c, fxaa_cs.c): the parameter table, FXAA 3.11's quality presets
 * as specialization constants of shaders/fxaa_common.glsl, and the push constants of its passes. */
#ifndef AA_FXAA_H
#define AA_FXAA_H

#include <stdint.h>

#include <vulkan/vulkan.h>

#include "types/method.h"

#define AA_FXAA_PARAM_COUNT 4
#define AA_FXAA_MAX_STEPS 12
extern const struct aa_param_def aa_fxaa_params[AA_FXAA_PARAM_COUNT];

/* Push constants `FxaaPush` of shaders/fxaa_common.glsl. */
struct aa_fxaa_push {
	float subpix;
	float edge_threshold;
	float edge_threshold_min;
	float unused;
};

/* Specialization constants: 0 the preset's step count, 1..12 its step sizes, 13 the compute variant's
 * queue direction (ignored by shaders that do not declare it). info points into the struct: initialise
 * it in place and do not copy it. */
struct aa_fxaa_spec_data {
	int32_t step_count;
	float steps[AA_FXAA_MAX_STEPS];
	VkBool32 horizontal;
};
struct aa_fxaa_spec {
	struct aa_fxaa_spec_data data;
	VkSpecializationMapEntry entries[AA_FXAA_MAX_STEPS + 2];
	VkSpecializationInfo info;
};

/* Fills spec for the preset in p (a value of the `preset` parameter) and push from p. */
void aa_fxaa_spec_init(struct aa_fxaa_spec *spec, const struct aa_method_params *p, bool horizontal);
void aa_fxaa_push_init(struct aa_fxaa_push *push, const struct aa_method_params *p);
/* "preset 12: 5 search steps (1, 1.5, 2, 4, 12 px)" for path_taken. */
void aa_fxaa_describe(const struct aa_method_params *p, char *out, size_t size);

#endif
