#version 450
#extension GL_GOOGLE_include_directive : require
// TAA resolve as engines ship it, for `taa` (preset=production, the default): see taa_converge.glsl.
#define MASTER_TAA 0
#define PRODUCTION 1
#include "taa_converge.glsl"
