#version 450
#extension GL_GOOGLE_include_directive : require
// Shadow map of alpha cut-out materials: discarded texels cast no shadow.
#include "common.glsl"

layout(location = 0) in vec2 in_uv;

void main()
{
	Material m = material;
	float a = m.base_color.a;
	// explicit gradients: see surface_color_grad in shading.glsl (helper lanes read the material as zero)
	vec2 uv_dx = dFdx(in_uv), uv_dy = dFdy(in_uv);
	if (uint(m.color2.w) == PATTERN_TEXTURE)
		a *= textureGrad(material_texture, in_uv * m.pattern.xy, uv_dx * m.pattern.xy, uv_dy * m.pattern.xy).a;
	if (a < m.shading.z)
		discard;
}
