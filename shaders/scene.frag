#version 450
#extension GL_GOOGLE_include_directive : require
// Forward shading: base colour times pattern or texture, Lambert plus optional Blinn-Phong specular,
// directional and point lights, one shadow-mapped directional light. Output is linear colour.
#include "common.glsl"
#include "shading.glsl"
#include "shading_point.glsl"

layout(constant_id = 0) const bool ALPHA_TEST = false;

layout(location = 0) in vec3 in_world;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;
layout(location = 3) in vec3 in_barycentric; // virtual samples only (virtual_sample.geom)
layout(location = 8) in vec4 in_tangent;
layout(location = 9) in vec4 in_color;
layout(location = 10) in vec4 in_shadow; // shadow_coordinates(): light space, view depth

layout(location = 0) out vec4 out_color;

void main()
{
	// MSAA targets (hardware or virtual samples) shade and alpha-test once per pixel and triangle, at the
	// shading point; texture gradients stay those of the pixel (a moved uv has none that mean anything).
	vec3 world = in_world, normal = in_normal;
	vec4 shadow = in_shadow;
	vec2 uv = in_uv, uv_dx = dFdx(in_uv), uv_dy = dFdy(in_uv);
	vec4 tangent = in_tangent, vertex_color = in_color;
	ShadingPoint sp = shading_point(in_barycentric);
	if (SHADING_POINT_MODE != SHADING_POINT_FRAGMENT) {
		world = at_shading_point(in_world, sp.offset);
		shadow = at_shading_point(in_shadow, sp.offset);
		normal = at_shading_point(in_normal, sp.offset);
		uv = at_shading_point(in_uv, sp.offset);
		uv_gradients_at(in_uv, sp.centre, uv_dx, uv_dy);
		if (MATERIAL_NORMAL_MAP)
			tangent = at_shading_point(in_tangent, sp.offset);
		if (MATERIAL_VERTEX_COLOR)
			vertex_color = at_shading_point(in_color, sp.offset);
	}
	Material m = material;
	vec4 base = surface_color_vertex(m, uv, uv_dx, uv_dy, vertex_color);
	gl_SampleMask[0] = -1; // always written: an output left unwritten would be undefined
	if (ALPHA_TEST) {
		if (!ALPHA_TO_COVERAGE && base.a < m.shading.z)
			discard;
		if (ALPHA_TO_COVERAGE && SHADING_POINT_MODE != SHADING_POINT_HARDWARE &&
		    surface_color_vertex(m, in_uv, uv_dx, uv_dy, in_color).a < m.shading.z)
			discard; // this rasterisation is its own sample: alpha where it lies
		if (ALPHA_TO_COVERAGE && SHADING_POINT_MODE == SHADING_POINT_HARDWARE) {
			uint kept = 0u; // alpha read at each sample, at the pixel's mip level (its gradients)
			for (int i = 0; i < PATTERN_SAMPLES; i++) {
				vec2 d = hardware_sample_offset(i);
				vec4 color_i = MATERIAL_VERTEX_COLOR ? at_shading_point(in_color, d) : in_color;
				if (surface_color_vertex(m, at_shading_point(in_uv, d), uv_dx, uv_dy, color_i).a >= m.shading.z)
					kept |= 1u << i;
			}
			if (kept == 0u)
				discard;
			gl_SampleMask[0] = int(kept);
		}
	}
	Surface s = Surface(world, shadow, normal, tangent, uv, uv_dx, uv_dy, gl_FrontFacing);
	out_color = vec4(shade(m, base, s), MATERIAL_BLEND ? base.a : 1.0);
}
