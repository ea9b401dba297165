#version 450
#extension GL_GOOGLE_include_directive : require
// RSAA resolve: the subsamples' differences -> two clusters (one k-means step: similar when d <= maxsim/2
// + 0.2, only if maxsim/2 > 0.2) -> the mask of similar subsamples -> one bilinear fetch of the 1-spp
// image at the trained offset for that mask. Authentication mode 1 halves the offset when the centre
// differs from the outside pixel nearest the furthest dissimilar subsample more than twice as much as
// from that subsample.
#include "rsaa_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2D colour;          // bilinear, clamp to edge
layout(set = 0, binding = 1, rgba32ui) uniform readonly uimage2D differences;
layout(set = 0, binding = 2) uniform sampler2D centre_position;
layout(set = 0, binding = 3) uniform sampler2D centre_normal;
layout(std430, set = 0, binding = 4) readonly buffer Table {
	vec4 subsample[8];  // xy: nearest outside pixel, z: squared distance from the centre
	vec2 offset[256];   // per mask, pixels, y down
} table;
layout(set = 0, binding = 5, rgba16f) uniform writeonly image2D result;

layout(push_constant) uniform Push {
	vec4 camera;
	vec4 forward;
	ivec4 config;       // x: subsamples, y: similarity, z: authentication mode
} pc;

const float THRESHOLD = 0.4;

void main()
{
	ivec2 p = ivec2(gl_GlobalInvocationID.xy);
	ivec2 size = imageSize(result);
	if (any(greaterThanEqual(p, size)))
		return;
	int n = pc.config.x;
	uvec4 slots = imageLoad(differences, p);
	float d[8];
	float maxsim = 0.0;
	for (int i = 0; i < n; i++) {
		d[i] = unpackHalf2x16(slots[i >> 1])[i & 1];
		maxsim = max(maxsim, d[i]);
	}
	vec4 c = texelFetch(colour, p, 0);
	if (maxsim * 0.5 > THRESHOLD * 0.5) {
		float limit = maxsim * 0.5 + THRESHOLD * 0.5;
		uint mask = 0u;
		int fs = 0;
		float far = -1.0;
		for (int i = 0; i < n; i++) {
			if (d[i] <= limit) {
				mask |= 1u << i;
			} else if (table.subsample[i].z >= far) { // furthest dissimilar (ties: higher index)
				far = table.subsample[i].z;
				fs = i;
			}
		}
		vec2 offset = table.offset[mask];
		if (pc.config.z == 1) {
			ivec2 q = clamp(p + ivec2(table.subsample[fs].xy), ivec2(0), size - 1);
			vec4 cp = texelFetch(centre_position, p, 0), op = texelFetch(centre_position, q, 0);
			if (cp.w > 0.5 && op.w > 0.5) {
				float co = rsaa_diff(pc.config.y, cp.xyz, texelFetch(centre_normal, p, 0).xyz, op.xyz,
						     texelFetch(centre_normal, q, 0).xyz, pc.camera.xyz, pc.forward.xyz);
				if (co - d[fs] > d[fs])
					offset *= 0.5;
			}
		}
		c = textureLod(colour, (vec2(p) + 0.5 + offset) / vec2(size), 0.0);
	}
	// a NaN or Inf from the scene must not leave the pass
	c.rgb = mix(vec3(0.0), c.rgb, lessThanEqual(abs(c.rgb), vec3(65000.0)));
	imageStore(result, p, vec4(c.rgb, 1.0));
}
