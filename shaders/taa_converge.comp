#version 450
#extension GL_GOOGLE_include_directive : require
// TAA resolve that converges, for `taa` (preset=converge): see taa_converge.glsl.
#define MASTER_TAA 0
#define RANGE_FORMAT rgba16f
#include "taa_converge.glsl"
