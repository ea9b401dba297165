#version 450
#extension GL_GOOGLE_include_directive : require
// TAA resolve that converges with seed 001's Master TAA box, for `taa-sobel` (preset=converge): see
// taa_converge.glsl.
#define MASTER_TAA 1
#define RANGE_FORMAT rgba32f // taa-sobel keeps linear depth there
#include "taa_converge.glsl"
