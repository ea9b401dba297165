#version 450
#extension GL_GOOGLE_include_directive : require
// TAA resolve, seed 001's "Master TAA" (Sobel, model IDs, depth pseudo-variances): see taa_resolve.glsl.
#define MASTER_TAA 1
#include "taa_resolve.glsl"
