#version 450
#extension GL_GOOGLE_include_directive : require
// Forward shading: base colour times pattern or texture, Lambert plus optional Blinn-Phong specular,
// directional and point lights, one shadow-mapped directional light. Output is linear colour.
#include "common.glsl"
#include "shading.glsl"

layout(constant_id = 0) const bool ALPHA_TEST = false;
// Virtual MSAA samples: the geometry is jittered to a sample position, but shading is evaluated at the
// pixel centre (attributes extrapolated by the jitter), once per pixel and triangle as MSAA does.
layout(constant_id = 1) const bool SHADE_AT_PIXEL_CENTRE = false;

layout(location = 0) in vec3 in_world;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;

layout(location = 0) out vec4 out_color;

void main()
{
	vec3 world = in_world, normal = in_normal;
	vec2 uv = in_uv;
	if (SHADE_AT_PIXEL_CENTRE) {
		vec2 offset = draw.jitter_ndc * frame.frame_size.xy * 0.5;
		world = at_offset(in_world, offset);
		normal = at_offset(in_normal, offset);
		uv = at_offset(in_uv, offset);
	}
	Material m = materials[draw.material];
	vec4 base = surface_color(m, uv);
	if (ALPHA_TEST && base.a < m.shading.z)
		discard;
	out_color = vec4(shade(m, base, world, normal, gl_FrontFacing), 1.0);
}
