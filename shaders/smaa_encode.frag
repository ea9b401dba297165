#version 450
// SMAA, before pass 1: the scene's linear colour encoded to sRGB in an RGBA8 target, with the Rec. 709
// luma of the encoded values in alpha. SMAA's edge thresholds are for gamma-encoded 8-bit input (an sRGB
// back buffer read through a UNORM view); encoding once here keeps the pow out of the edge pass, which
// reads up to seven neighbours. The blend pass still reads the linear colour. The second target gets the
// linear colour as it is: the blend pass draws only where its mask lets it, into this copy. With
// REPROJECT (T2x, 4x) the copy's alpha is the velocity's length as the reference's blend pass packs it,
// sqrt(5 |velocity in UV units|), for the temporal resolve's weight.
layout(constant_id = 0) const bool REPROJECT = false;
layout(set = 0, binding = 0) uniform sampler2D scene; // linear RGBA16F
layout(set = 0, binding = 1) uniform sampler2D velocity_tex; // REPROJECT: RG16F, pixels
layout(location = 0) out vec4 out_encoded;
layout(location = 1) out vec4 out_linear;

void main()
{
	ivec2 p = ivec2(gl_FragCoord.xy);
	vec4 linear = texelFetch(scene, p, 0);
	vec3 c = clamp(linear.rgb, 0.0, 1.0);
	vec3 s = mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308)));
	out_encoded = vec4(s, dot(s, vec3(0.2126, 0.7152, 0.0722)));
	if (REPROJECT) {
		vec2 v = texelFetch(velocity_tex, p, 0).rg / vec2(textureSize(scene, 0));
		linear.a = sqrt(5.0 * length(v));
	}
	out_linear = linear;
}
