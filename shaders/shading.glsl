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
	} else if (MATERIAL_PATTERN == PATTERN_TEXTURE) {
		// the LOD bias as a gradient scale: the same level, since the level is log2 of the gradient
		vec2 scale = m.pattern.xy * exp2(TEXTURE_LOD_BIAS);
		c *= textureGrad(material_texture, uv * m.pattern.xy, uv_dx * scale, uv_dy * scale); // sRGB view
	}
	return c;
}

vec4 surface_color(Material m, vec2 uv)
{
	return surface_color_grad(m, uv, dFdx(uv), dFdy(uv));
}

float shadow_visibility(vec3 world, float ndotl)
{
	vec4 p = frame.shadow_view_proj * vec4(world, 1.0);
	vec3 ndc = p.xyz / p.w;
	vec2 uv = ndc.xy * 0.5 + 0.5;
	// reversed-Z: the stored depth is the closest occluder (largest); a slope-scaled bias keeps
	// surfaces from shadowing themselves.
	float bias = 0.0005 + 0.002 * (1.0 - ndotl);
	// One mip level, the same filter when magnified or minified: an explicit LOD is the same lookup
	// without the derivatives and LOD selection an implicit one computes per fragment. The lookup is
	// made for every fragment and outside points are selected away after it, not branched around:
	// llvmpipe samples in divergent control flow far more slowly (docs/architecture.md).
	float lit = textureLod(shadow_map, vec3(uv, ndc.z + bias), 0.0);
	bool outside = any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)));
	return outside ? 1.0 : lit;
}

// What light i adds to a surface point. i is a constant at every call (shade), so the light is read at
// constant offsets of the frame block and only its own type's path is compiled in.
vec3 light_contribution(int i, vec3 base, vec3 world, vec3 n, vec3 v, float specular, float shininess)
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
	float vis = i == SHADOW_LIGHT ? shadow_visibility(world, ndotl) : 1.0; // before any branch: see there
	if (ndotl <= 0.0)
		return vec3(0.0);
	vec3 lit = base * ndotl;
	if (MATERIAL_HAS_SPECULAR) {
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

// Lit linear colour of a surface point; base is the surface colour (alpha handled by the caller).
vec3 shade(Material m, vec4 base, vec3 world, vec3 normal, bool front_facing)
{
	if (MATERIAL_IS_UNLIT)
		return poisoned(base.rgb);
	vec3 n = normalize(normal);
	if (!front_facing)
		n = -n; // two-sided: thin blinds and wires are seen from both sides
	vec3 v = normalize(frame.camera_position.xyz - world);
	vec3 color = frame.ambient.rgb * base.rgb;
	float specular = m.shading.x;
	float shininess = mix(512.0, 4.0, clamp(m.shading.y, 0.0, 1.0));
	// Unrolled by hand: with a loop up to LIGHT_COUNT, Mesa 22.3 kept the loop and indexed the lights
	// per fragment (the scene pass ~1.6x slower). Lights with no contribution add exactly 0.
#define ADD_LIGHT(i) if (i < LIGHT_COUNT) color += light_contribution(i, base.rgb, world, n, v, specular, shininess);
	ADD_LIGHT(0) ADD_LIGHT(1) ADD_LIGHT(2) ADD_LIGHT(3) ADD_LIGHT(4) ADD_LIGHT(5) ADD_LIGHT(6) ADD_LIGHT(7)
#undef ADD_LIGHT
	return poisoned(color);
}
