#version 450
#extension GL_GOOGLE_include_directive : require
// TAA resolve, seed 001's baseline ("Uncharted TAA"): see taa_resolve.glsl.
#define MASTER_TAA 0
#include "taa_resolve.glsl"
