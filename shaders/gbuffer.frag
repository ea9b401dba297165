#version 450
#extension GL_GOOGLE_include_directive : require
// G-buffer pass: the lit colour as scene.frag, plus what temporal and geometric methods read: velocity,
// model ID, world position, geometric normal, unlit luma and linear depth. Locations without an
// attachment in the render pass (VK_ATTACHMENT_UNUSED) are discarded, so one shader serves every mix.
#include "common.glsl"
#include "shading.glsl"
#include "shading_point.glsl"

layout(constant_id = 0) const bool ALPHA_TEST = false;
// RSAA's subsample passes: position, normal and velocity stay at the virtual sample (what its similarity
// test compares); only colour and the alpha test move to the pixel's shading point.
layout(constant_id = 1) const bool GEOMETRY_AT_SAMPLE = false;

layout(location = 0) in vec3 in_world;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;
layout(location = 3) in vec4 in_clip;
layout(location = 4) in vec4 in_prev_clip;
layout(location = 5) in vec3 in_barycentric; // virtual samples only
layout(location = 8) in vec4 in_tangent;
layout(location = 9) in vec4 in_color;
layout(location = 10) in vec4 in_shadow; // shadow_coordinates(): light space, view depth

layout(location = 0) out vec4 out_color;
layout(location = 1) out vec2 out_velocity;
layout(location = 2) out uint out_model_id;
layout(location = 3) out vec4 out_position;
layout(location = 4) out vec4 out_normal;
layout(location = 5) out vec2 out_surface;

void main()
{
	vec3 world = in_world, normal = in_normal;
	vec4 shadow = in_shadow;
	vec2 uv = in_uv, uv_dx = dFdx(in_uv), uv_dy = dFdy(in_uv);
	vec4 clip = in_clip, prev_clip = in_prev_clip;
	vec4 tangent = in_tangent, vertex_color = in_color;
	ShadingPoint sp = shading_point(in_barycentric);
	if (SHADING_POINT_MODE != SHADING_POINT_FRAGMENT) {
		uv = at_shading_point(in_uv, sp.offset);
		uv_gradients_at(in_uv, sp.centre, uv_dx, uv_dy);
		if (MATERIAL_VERTEX_COLOR)
			vertex_color = at_shading_point(in_color, sp.offset);
		if (MATERIAL_NORMAL_MAP && !GEOMETRY_AT_SAMPLE)
			tangent = at_shading_point(in_tangent, sp.offset);
		if (!GEOMETRY_AT_SAMPLE) {
			world = at_shading_point(in_world, sp.offset);
			shadow = at_shading_point(in_shadow, sp.offset);
			normal = at_shading_point(in_normal, sp.offset);
			clip = at_shading_point(in_clip, sp.offset);
			prev_clip = at_shading_point(in_prev_clip, sp.offset);
		}
	}
	Material m = material;
	vec4 base = surface_color_vertex(m, uv, uv_dx, uv_dy, vertex_color);
	if (ALPHA_TEST) {
		if (!ALPHA_TO_COVERAGE && base.a < m.shading.z)
			discard;
		// G-buffer targets are single-sample: a virtual sample keeps or drops itself, by alpha where it lies
		if (ALPHA_TO_COVERAGE && surface_color_vertex(m, in_uv, uv_dx, uv_dy, in_color).a < m.shading.z)
			discard;
	}
	Surface s = Surface(world, shadow, normal, tangent, uv, uv_dx, uv_dy, gl_FrontFacing);
	out_color = vec4(shade(m, base, s), MATERIAL_BLEND ? base.a : 1.0);
	// pixels moved since the previous frame; w floors keep points at the eye finite
	vec2 ndc = clip.xy / max(abs(clip.w), 1e-6);
	vec2 prev_ndc = prev_clip.xy / max(abs(prev_clip.w), 1e-6);
	vec2 velocity = (ndc - prev_ndc) * 0.5 * frame.frame_size.xy;
	out_velocity = prev_clip.w > 1e-6 ? clamp(velocity, vec2(-65000.0), vec2(65000.0)) : vec2(65000.0);
	out_model_id = draw.object_id;
	out_position = vec4(world, 1.0);
	// the triangle's own plane: world position is affine across it, so its derivatives span the plane
	vec3 geometric = cross(dFdx(in_world), dFdy(in_world));
	float len = length(geometric);
	out_normal = vec4(len > 0.0 ? geometric / len : normalize(in_normal), 1.0);
	if (dot(out_normal.xyz, world) > 0.0)
		out_normal.xyz = -out_normal.xyz; // face the camera, as the shading does
	float luma = dot(base.rgb, vec3(0.2126, 0.7152, 0.0722));
	// view-space distance along the view axis: clip.w in perspective; orthographic undoes its z mapping
	float near = frame.camera_planes.x, far = frame.camera_planes.y;
	float linear_depth = frame.camera_planes.z > 0.5 ? far - clip.z * (far - near) : clip.w;
	out_surface = vec2(luma, linear_depth);
}
