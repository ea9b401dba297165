#version 450
// CMAA2 pass 3, the deferred blend: each pixel that received blends from pass 2 becomes their mean; the
// others keep the scene colour.
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2D scene; // linear RGBA16F
layout(std430, set = 0, binding = 1) readonly buffer Accumulation {
	uvec4 slot[];
} acc;
layout(set = 0, binding = 2, rgba16f) uniform writeonly image2D out_colour;

const float FIXED_ONE = 4096.0; // as shaders/cmaa2_shapes.comp

void main()
{
	ivec2 p = ivec2(gl_GlobalInvocationID.xy);
	ivec2 size = textureSize(scene, 0);
	if (any(greaterThanEqual(p, size)))
		return;
	uvec4 s = acc.slot[p.y * size.x + p.x];
	vec4 c = texelFetch(scene, p, 0);
	if (s.w != 0u)
		c.rgb = vec3(s.xyz) / (FIXED_ONE * float(s.w));
	imageStore(out_colour, p, vec4(c.rgb, 1.0));
}
