#version 450
#extension GL_GOOGLE_include_directive : require
// Shadow map of alpha cut-out materials: discarded texels cast no shadow.
#include "common.glsl"

layout(location = 0) in vec2 in_uv;
layout(location = 1) in float in_alpha;

void main()
{
	Material m = material;
	float a = m.base_color.a;
	if ((uint(m.shading.w) & MATERIAL_VERTEX_COLOR_FLAG) != 0u)
		a *= in_alpha;
	// explicit gradients: see surface_color_grad in shading.glsl (helper lanes read the material as zero).
	// The base map's transform: its scale for scene materials, KHR_texture_transform for file materials.
	vec2 uv_dx = dFdx(in_uv), uv_dy = dFdy(in_uv);
	mat2 jacobian = mat2(m.uv_rows[0].x, m.uv_rows[1].x, m.uv_rows[0].y, m.uv_rows[1].y);
	vec2 uv = vec2(dot(m.uv_rows[0].xyz, vec3(in_uv, 1.0)), dot(m.uv_rows[1].xyz, vec3(in_uv, 1.0)));
	if (uint(m.color2.w) == PATTERN_TEXTURE)
		a *= textureGrad(material_texture, uv, jacobian * uv_dx, jacobian * uv_dy).a;
	if (a < m.shading.z)
		discard;
}
