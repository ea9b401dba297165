// Shared declarations of the scene passes: the per-frame uniform block, materials and push constants.
// Must match struct aa_frame_uniforms / aa_material_gpu / aa_draw_push in engine/renderer.h.

#define MAX_LIGHTS 8
#define MATERIAL_CUTOUT 1u
#define MATERIAL_UNLIT 2u
#define MATERIAL_VERTEX_COLOR_FLAG 4u
#define SHADOW_CASCADES 4
#define PATTERN_NONE 0u
#define PATTERN_CHECKER 1u
#define PATTERN_STRIPES 2u
#define PATTERN_TEXTURE 3u

struct Light {
	vec4 position_type;   // xyz: position (point) or travel direction (directional); w: 0 dir, 1 point
	vec4 color_range;     // rgb: colour * intensity; w: range (0 = none)
	vec4 shadow;          // x: 1 if this light uses the shadow map
};

layout(std140, set = 0, binding = 0) uniform Frame {
	mat4 view_proj;       // unjittered; jitter is added per draw after projection
	mat4 prev_view_proj;  // the previous frame's (for velocity); equal to view_proj after a cut
	mat4 shadow_view_proj;
	vec4 ambient;
	vec4 frame_size;      // xy: the frame's width and height in pixels
	vec4 camera_planes;   // x: near, y: far, z: 1 if orthographic
	ivec4 counts;         // x: light count, y: shadow map enabled, z: inject NaN/Inf (stability tests)
	Light lights[MAX_LIGHTS];
	// The shadow map: SHADOW_CASCADES orthographic maps in a 2x2 atlas, each fitted to a slice of the view
	// (engine/shadow_fit.c). A point's light-space position times a cascade's scale plus its offset is
	// that cascade's NDC; offset.w is its depth bias per unit of (1 - N.L) plus one.
	mat4 shadow_light_view;               // world -> light space (rotation: x, y across the light, z toward it)
	vec4 shadow_cascade_scale[SHADOW_CASCADES];
	vec4 shadow_cascade_offset[SHADOW_CASCADES];
	vec4 shadow_splits;                   // view depths where cascades 1, 2 and 3 begin
	vec4 camera_forward;                  // unit view direction: view depth = dot(p, forward), p eye-relative
} frame;

struct Material {
	vec4 base_color;
	vec4 color2;          // rgb; w: pattern
	vec4 pattern;         // xy: scale, z: stripe width
	vec4 shading;         // x: specular, y: roughness, z: alpha cutoff, w: flags
	vec4 emissive;        // rgb: emitted colour (strength applied); w: metallic
	vec4 maps;            // x: normal map scale, y: occlusion strength
	vec4 uv_rows[10];     // per map (base, emissive, normal, metal-rough, occlusion): uv' = (dot(r0, (u, v, 1)),
			      // dot(r1, (u, v, 1))), KHR_texture_transform (the base map's is its scale otherwise)
};

// The drawn object's material: the scene's materials are one buffer, bound per draw at the material's
// dynamic offset, so every field is read at a constant offset. llvmpipe then loads it once per draw; an
// array indexed by draw.material was gathered per fragment and lane, two thirds of the scene pass
// (docs/architecture.md, "The scene pass").
layout(std140, set = 0, binding = 1) uniform DrawMaterial {
	Material material;
};

layout(set = 0, binding = 2) uniform sampler2D material_texture;
layout(set = 0, binding = 3) uniform sampler2DShadow shadow_map;

// Previous frame's model matrix per object, indexed by object_id - 1 (for velocity).
layout(std430, set = 0, binding = 4) readonly buffer PreviousModels {
	mat4 prev_models[];
};

layout(push_constant) uniform Draw {
	mat4 model;
	vec4 normal_matrix[3];  // inverse-transpose of model's upper 3x3, as columns
	uint material;          // index into the scene's materials (the bound `material` is this one)
	uint object_id;
	vec2 jitter_ndc;        // sub-pixel jitter added after projection (clip.xy += jitter * clip.w)
} draw;

// A point's shadow coordinates: its position in the shadow light's space (xyz) and its view depth (w), which
// picks the cascade. Both are affine in the world position (an orthographic light), so the vertex shaders
// compute them and the rasterizer's interpolation is exact; per fragment they cost a mat4 and a dot
// product (docs/architecture.md, "The scene pass").
vec4 shadow_coordinates(vec3 world)
{
	return vec4((frame.shadow_light_view * vec4(world, 1.0)).xyz,
		    dot(world, frame.camera_forward.xyz));
}
