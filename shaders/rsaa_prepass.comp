#version 450
#extension GL_GOOGLE_include_directive : require
// RSAA pre-pass, once per geometric subsample: the subsample's difference from the pixel centre (SADP or
// depth), stored as a half float in its slot of the per-pixel differences (two subsamples per channel).
// Background rules (the paper's Listing 2): background centre vs foreground subsample 1, background vs
// background 0, foreground centre vs background subsample "big". Authentication mode 2 reclassifies a
// subsample as similar (0) when it differs more from the nearest outside pixel than from the centre.
#include "rsaa_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2D centre_position; // RGBA32F world position, w 0 = background
layout(set = 0, binding = 1) uniform sampler2D centre_normal;
layout(set = 0, binding = 2) uniform sampler2D sample_position;
layout(set = 0, binding = 3) uniform sampler2D sample_normal;
layout(set = 0, binding = 4, rgba32ui) uniform uimage2D differences;

layout(push_constant) uniform Push {
	vec4 camera;      // xyz: camera position (depth measure)
	vec4 forward;     // xyz: view direction (depth measure)
	ivec4 sample_id;  // x: subsample index, y: similarity, z: authentication mode
	ivec4 neighbour;  // xy: the outside pixel nearest to this subsample
} pc;

void main()
{
	ivec2 p = ivec2(gl_GlobalInvocationID.xy);
	ivec2 size = imageSize(differences);
	if (any(greaterThanEqual(p, size)))
		return;
	vec4 cp = texelFetch(centre_position, p, 0), sp = texelFetch(sample_position, p, 0);
	vec3 cn = texelFetch(centre_normal, p, 0).xyz, sn = texelFetch(sample_normal, p, 0).xyz;
	float d;
	if (cp.w < 0.5) {
		d = sp.w < 0.5 ? 0.0 : 1.0;
	} else if (sp.w < 0.5) {
		d = RSAA_BACKGROUND_DIFF;
	} else {
		d = rsaa_diff(pc.sample_id.y, cp.xyz, cn, sp.xyz, sn, pc.camera.xyz, pc.forward.xyz);
		ivec2 q = p + pc.neighbour.xy;
		if (pc.sample_id.z == 2 && d > 0.2 && all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size))) {
			vec4 op = texelFetch(centre_position, q, 0);
			if (op.w > 0.5) {
				vec3 on = texelFetch(centre_normal, q, 0).xyz;
				float so = rsaa_diff(pc.sample_id.y, op.xyz, on, sp.xyz, sn, pc.camera.xyz,
						     pc.forward.xyz);
				if (so > d)
					d = 0.0;
			}
		}
	}
	if (!(d >= 0.0 && d <= RSAA_BACKGROUND_DIFF)) // NaN positions from the scene: no evidence
		d = 0.0;
	int i = pc.sample_id.x;
	uvec4 slots = i == 0 ? uvec4(0) : imageLoad(differences, p);
	vec2 pair = unpackHalf2x16(slots[i >> 1]);
	pair[i & 1] = d;
	slots[i >> 1] = packHalf2x16(pair);
	imageStore(differences, p, slots);
}
