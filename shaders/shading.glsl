// Surface colour and lighting shared by the scene passes (scene.frag, gbaa.frag).
// Needs common.glsl included first.

// Texture LOD bias of the target: the reference's N samples per pixel each stand for 1/N of the pixel,
// so they read a mip level finer by log2(sqrt(N)); otherwise it would converge to trilinear blur.
layout(constant_id = 2) const float TEXTURE_LOD_BIAS = 0.0;

// What one pipeline compiles in, set per material class and scene by renderer.c (scene_variant). llvmpipe
// runs both sides of every branch under a mask, so a path a material or the scene's lights do not take
// is removed when the pipeline is created instead of being computed and masked off per fragment.
layout(constant_id = 22) const uint MATERIAL_PATTERN = PATTERN_NONE; // the material's pattern
layout(constant_id = 23) const bool MATERIAL_IS_UNLIT = false;       // flags & MATERIAL_UNLIT
layout(constant_id = 24) const bool MATERIAL_HAS_SPECULAR = false;   // specular > 0
layout(constant_id = 25) const int LIGHT_COUNT = 0;                  // frame.counts.x
layout(constant_id = 26) const uint POINT_LIGHTS = 0u;               // bit i: light i is a point light
layout(constant_id = 27) const int SHADOW_LIGHT = -1;                // the light using the shadow map, or -1
// Materials from mesh files (docs/scene-format.md, "Materials from mesh files"): each feature a material
// class has is compiled in, and nothing of it otherwise.
layout(constant_id = 28) const bool MATERIAL_METAL_ROUGH = false;    // glTF metallic-roughness (GGX) shading
layout(constant_id = 29) const bool MATERIAL_VERTEX_COLOR = false;   // base colour times COLOR_0
layout(constant_id = 30) const bool MATERIAL_NORMAL_MAP = false;
layout(constant_id = 31) const int MATERIAL_EMISSIVE = 0;            // 0 none, 1 a colour, 2 a colour x texture
layout(constant_id = 32) const bool MATERIAL_METAL_ROUGH_MAP = false;
layout(constant_id = 33) const bool MATERIAL_OCCLUSION_MAP = false;
layout(constant_id = 34) const bool MATERIAL_UV_TRANSFORM = false;   // KHR_texture_transform on some map
layout(constant_id = 35) const bool MATERIAL_BLEND = false;          // the output keeps the surface's alpha

#define MAP_BASE 0
#define MAP_EMISSIVE 1
#define MAP_NORMAL 2
#define MAP_METAL_ROUGH 3
#define MAP_OCCLUSION 4
layout(set = 0, binding = 5) uniform sampler2D emissive_texture;   // sRGB
layout(set = 0, binding = 6) uniform sampler2D normal_texture;     // the rest are data (UNORM)
layout(set = 0, binding = 7) uniform sampler2D metal_rough_texture;
layout(set = 0, binding = 8) uniform sampler2D occlusion_texture;

// A map's texture coordinates and their gradients under its KHR_texture_transform (the identity without).
vec2 map_uv(Material m, int map, vec2 uv)
{
	return vec2(dot(m.uv_rows[2 * map].xyz, vec3(uv, 1.0)), dot(m.uv_rows[2 * map + 1].xyz, vec3(uv, 1.0)));
}

vec2 map_gradient(Material m, int map, vec2 d)
{
	return vec2(dot(m.uv_rows[2 * map].xy, d), dot(m.uv_rows[2 * map + 1].xy, d));
}

// A data map sampled with its transform and the pixel's gradients (the LOD bias of the target applied).
vec4 sample_map(sampler2D map_texture, Material m, int map, vec2 uv, vec2 uv_dx, vec2 uv_dy)
{
	float bias = exp2(TEXTURE_LOD_BIAS);
	if (!MATERIAL_UV_TRANSFORM)
		return textureGrad(map_texture, uv, uv_dx * bias, uv_dy * bias);
	return textureGrad(map_texture, map_uv(m, map, uv), map_gradient(m, map, uv_dx) * bias,
			   map_gradient(m, map, uv_dy) * bias);
}

// Texture gradients are passed in, not taken from the scaled coordinate inside the branch below: lavapipe
// (Mesa 22.3) read the storage-buffer material as zero in helper lanes (it is a uniform block now), so
// the implicit derivative of `uv * m.pattern.xy` across a triangle's edge was huge and edge pixels took the coarsest mip (the bright
// one-pixel rims on hard-edges' sign). Gradients of the interpolated uv are right in every lane; virtual
// samples also pass the pixel centre's gradients when uv itself is moved to a shading point.
vec4 surface_color_grad(Material m, vec2 uv, vec2 uv_dx, vec2 uv_dy)
{
	vec4 c = m.base_color;
	if (MATERIAL_PATTERN == PATTERN_CHECKER) {
		vec2 cell = floor(uv * m.pattern.xy);
		if (mod(cell.x + cell.y, 2.0) >= 1.0)
			c.rgb = m.color2.rgb;
	} else if (MATERIAL_PATTERN == PATTERN_STRIPES) {
		if (fract(uv.x * m.pattern.x) < m.pattern.z)
			c.rgb = m.color2.rgb;
	} else if (MATERIAL_PATTERN == PATTERN_TEXTURE && MATERIAL_UV_TRANSFORM) {
		float bias = exp2(TEXTURE_LOD_BIAS);
		c *= textureGrad(material_texture, map_uv(m, MAP_BASE, uv), map_gradient(m, MAP_BASE, uv_dx) * bias,
				 map_gradient(m, MAP_BASE, uv_dy) * bias);
	} else if (MATERIAL_PATTERN == PATTERN_TEXTURE) {
		// the LOD bias as a gradient scale: the same level, since the level is log2 of the gradient
		vec2 scale = m.pattern.xy * exp2(TEXTURE_LOD_BIAS);
		c *= textureGrad(material_texture, uv * m.pattern.xy, uv_dx * scale, uv_dy * scale); // sRGB view
	}
	return c;
}

// The base colour with the mesh's vertex colour, when the material uses it (alpha too: glTF's rule).
vec4 surface_color_vertex(Material m, vec2 uv, vec2 uv_dx, vec2 uv_dy, vec4 vertex_color)
{
	vec4 c = surface_color_grad(m, uv, uv_dx, uv_dy);
	return MATERIAL_VERTEX_COLOR ? c * vertex_color : c;
}

vec4 surface_color(Material m, vec2 uv)
{
	return surface_color_grad(m, uv, dFdx(uv), dFdy(uv));
}

float shadow_visibility(vec4 shadow, float ndotl)
{
	// The cascade of this point's view depth; its scale and offset picked by selects, not by an index that
	// varies per fragment (which llvmpipe gathers per lane, docs/architecture.md). The splits increase, so
	// each test past a split overrides the ones before. Only what differs between cascades is selected:
	// x and y share one scale, and the half-texel uv margin (scale.w) is the same for all.
	vec3 light = shadow.xyz;
	bool past1 = shadow.w > frame.shadow_splits.x, past2 = shadow.w > frame.shadow_splits.y,
	     past3 = shadow.w > frame.shadow_splits.z;
	vec2 scale = past1 ? frame.shadow_cascade_scale[1].xz : frame.shadow_cascade_scale[0].xz;
	vec4 offset = past1 ? frame.shadow_cascade_offset[1] : frame.shadow_cascade_offset[0];
	scale = past2 ? frame.shadow_cascade_scale[2].xz : scale;
	offset = past2 ? frame.shadow_cascade_offset[2] : offset;
	scale = past3 ? frame.shadow_cascade_scale[3].xz : scale;
	offset = past3 ? frame.shadow_cascade_offset[3] : offset;
	vec3 ndc = light * scale.xxy + offset.xyz;
	vec2 uv = ndc.xy * 0.5 + 0.5;
	// reversed-Z: the stored depth is the closest occluder (largest); a slope-scaled bias of about a
	// texel's depth keeps surfaces from shadowing themselves. Beyond the casters' depth range the
	// reference depth clamps, so a receiver farther from the light than every caster is still shadowed.
	float bias = offset.w * (1.0 + 3.0 * (1.0 - ndotl));
	float reference = clamp(ndc.z + bias, 0.0, 1.0);
	// The cascade's quarter of the atlas, kept half a texel inside so filtering never reads a neighbour.
	vec2 tile = vec2((past1 && !past2) || past3 ? 0.5 : 0.0, past2 ? 0.5 : 0.0); // cascade i: (i & 1, i >> 1) / 2
	float margin = frame.shadow_cascade_scale[0].w;
	vec2 atlas = tile + clamp(uv, vec2(margin), vec2(1.0 - margin)) * 0.5;
	// One mip level, the same filter when magnified or minified: an explicit LOD is the same lookup
	// without the derivatives and LOD selection an implicit one computes per fragment. The lookup is
	// made for every fragment and outside points are selected away after it, not branched around:
	// llvmpipe samples in divergent control flow far more slowly (docs/architecture.md).
	float lit = textureLod(shadow_map, vec3(atlas, reference), 0.0);
	bool outside = any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)));
	return outside ? 1.0 : lit;
}

// glTF metallic-roughness (the specification's appendix B): GGX distribution, height-correlated Smith
// visibility, Schlick Fresnel, Lambert diffuse of (1 - F) c_diff. Times pi, so that a white rough
// dielectric lit head-on is as bright as the scene materials' Lambert (lights are in those units).
vec3 brdf_metal_rough(vec3 diffuse, vec3 f0, float alpha, vec3 n, vec3 l, vec3 v, float ndotl)
{
	vec3 h = normalize(l + v);
	float ndotv = max(dot(n, v), 1e-4), ndoth = max(dot(n, h), 0.0), vdoth = max(dot(v, h), 0.0);
	vec3 fresnel = f0 + (1.0 - f0) * pow(1.0 - vdoth, 5.0);
	float a2 = alpha * alpha;
	float d = ndoth * ndoth * (a2 - 1.0) + 1.0;
	float distribution = a2 / max(3.14159265 * d * d, 1e-8);
	float visibility = 0.5 / max(ndotl * sqrt(ndotv * ndotv * (1.0 - a2) + a2) +
				     ndotv * sqrt(ndotl * ndotl * (1.0 - a2) + a2), 1e-8);
	return (1.0 - fresnel) * diffuse + 3.14159265 * fresnel * distribution * visibility;
}

// What a metallic-roughness surface needs besides the lights: its diffuse colour, F0 and GGX alpha.
struct MetalRough {
	vec3 diffuse, f0;
	float alpha;
};

// What light i adds to a surface point. i is a constant at every call (shade), so the light is read at
// constant offsets of the frame block and only its own type's path is compiled in.
vec3 light_contribution(int i, vec3 base, vec3 world, vec4 shadow, vec3 n, vec3 v, float specular,
			float shininess, MetalRough mr)
{
	Light light = frame.lights[i];
	vec3 l;
	vec3 radiance = light.color_range.rgb;
	if ((POINT_LIGHTS & (1u << i)) == 0u) {
		l = -normalize(light.position_type.xyz);
	} else {
		vec3 d = light.position_type.xyz - world;
		float dist2 = max(dot(d, d), 1e-4);
		l = d * inversesqrt(dist2);
		radiance /= dist2;
		float range = light.color_range.w;
		if (range > 0.0) {
			float f = clamp(1.0 - dist2 / (range * range), 0.0, 1.0);
			radiance *= f * f;
		}
	}
	float ndotl = max(dot(n, l), 0.0);
	float vis = i == SHADOW_LIGHT ? shadow_visibility(shadow, ndotl) : 1.0; // before any branch: see there
	if (ndotl <= 0.0)
		return vec3(0.0);
	vec3 lit = base * ndotl;
	if (MATERIAL_METAL_ROUGH)
		lit = brdf_metal_rough(mr.diffuse, mr.f0, mr.alpha, n, l, v, ndotl) * ndotl;
	if (MATERIAL_HAS_SPECULAR && !MATERIAL_METAL_ROUGH) {
		vec3 h = normalize(l + v);
		// normalised Blinn-Phong so rough and smooth surfaces reflect similar energy
		lit += specular * (shininess + 8.0) / 25.13274 * pow(max(dot(n, h), 0.0), shininess) * ndotl;
	}
	return vis * radiance * lit;
}

// Stability tests poison a sparse pattern of pixels with NaN and +Inf: nothing downstream may keep them.
// Applied to the finished colour rather than as an early return, which would put all the shading after
// it in divergent control flow.
vec3 poisoned(vec3 color)
{
	int k = (int(gl_FragCoord.x) + 3 * int(gl_FragCoord.y)) % 11;
	vec3 poison = vec3(uintBitsToFloat(k == 0 ? 0x7fc00000u : 0x7f800000u)); // NaN, +Inf
	return frame.counts.z != 0 && (k == 0 || k == 5) ? poison : color;
}

// What the fragment shaders know of a surface point besides its base colour.
struct Surface {
	vec3 world;           // interpolated, world space
	vec4 shadow;          // shadow_coordinates(world), interpolated from the vertices
	vec3 normal;          // interpolated, world space
	vec4 tangent;         // world space xyz; w: handedness (normal maps)
	vec2 uv, uv_dx, uv_dy;
	bool front_facing;
};

// Lit linear colour of a surface point; base is the surface colour (alpha handled by the caller).
vec3 shade(Material m, vec4 base, Surface s)
{
	vec3 emitted = vec3(0.0);
	if (MATERIAL_EMISSIVE == 1)
		emitted = m.emissive.rgb;
	if (MATERIAL_EMISSIVE == 2)
		emitted = m.emissive.rgb * sample_map(emissive_texture, m, MAP_EMISSIVE, s.uv, s.uv_dx, s.uv_dy).rgb;
	if (MATERIAL_IS_UNLIT)
		return poisoned(base.rgb);
	vec3 world = s.world;
	vec3 n = normalize(s.normal);
	if (!s.front_facing)
		n = -n; // two-sided: thin blinds and wires are seen from both sides
	if (MATERIAL_NORMAL_MAP) {
		// the tangent frame of the face seen: a back face turns it around with its normal
		vec3 t = s.tangent.xyz - n * dot(n, s.tangent.xyz);
		t = (s.front_facing ? 1.0 : -1.0) * t * inversesqrt(max(dot(t, t), 1e-20));
		vec3 b = cross(n, t) * s.tangent.w;
		vec3 tn = sample_map(normal_texture, m, MAP_NORMAL, s.uv, s.uv_dx, s.uv_dy).xyz * 2.0 - 1.0;
		tn.xy *= m.maps.x;
		n = normalize(mat3(t, b, n) * tn);
	}
	vec3 v = normalize(-world); // world is relative to the eye
	vec3 color = frame.ambient.rgb * base.rgb;
	float specular = m.shading.x;
	float shininess = mix(512.0, 4.0, clamp(m.shading.y, 0.0, 1.0));
	MetalRough mr = MetalRough(vec3(0.0), vec3(0.0), 1.0);
	float occlusion = 1.0;
	if (MATERIAL_OCCLUSION_MAP)
		occlusion = 1.0 + m.maps.y * (sample_map(occlusion_texture, m, MAP_OCCLUSION, s.uv, s.uv_dx, s.uv_dy).r - 1.0);
	if (MATERIAL_METAL_ROUGH) {
		float metallic = m.emissive.w, roughness = m.shading.y;
		if (MATERIAL_METAL_ROUGH_MAP) {
			vec4 t = sample_map(metal_rough_texture, m, MAP_METAL_ROUGH, s.uv, s.uv_dx, s.uv_dy);
			roughness *= t.g;
			metallic *= t.b;
		}
		roughness = clamp(roughness, 0.03, 1.0); // a perfect mirror of point lights is a NaN
		mr = MetalRough(base.rgb * (1.0 - metallic), mix(vec3(0.04), base.rgb, metallic), roughness * roughness);
		// ambient light without an environment: the diffuse colour plus F0, for the specular part
		color = frame.ambient.rgb * (mr.diffuse + mr.f0);
	}
	color *= occlusion;
	// Unrolled by hand: with a loop up to LIGHT_COUNT, Mesa 22.3 kept the loop and indexed the lights
	// per fragment (the scene pass ~1.6x slower). Lights with no contribution add exactly 0.
#define ADD_LIGHT(i) if (i < LIGHT_COUNT) color += light_contribution(i, base.rgb, world, s.shadow, n, v, specular, shininess, mr);
	ADD_LIGHT(0) ADD_LIGHT(1) ADD_LIGHT(2) ADD_LIGHT(3) ADD_LIGHT(4) ADD_LIGHT(5) ADD_LIGHT(6) ADD_LIGHT(7)
#undef ADD_LIGHT
	return poisoned(color + emitted);
}
