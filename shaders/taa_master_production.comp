#version 450
#extension GL_GOOGLE_include_directive : require
// TAA resolve as engines ship it with seed 001's Master TAA box, for `taa-sobel` (preset=production, the
// default): see taa_converge.glsl.
#define MASTER_TAA 1
#define PRODUCTION 1
#include "taa_converge.glsl"
