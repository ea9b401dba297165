// Surface colour and lighting shared by the scene passes (scene.frag, gbaa.frag).
// Needs common.glsl included first.

// Texture LOD bias of the target: the reference's N samples per pixel each stand for 1/N of the pixel,
// so they read a mip level finer by log2(sqrt(N)); otherwise it would converge to trilinear blur.
layout(constant_id = 2) const float TEXTURE_LOD_BIAS = 0.0;

// Texture gradients are passed in, not taken from the scaled coordinate inside the branch below: lavapipe
// (Mesa 22.3) reads the storage-buffer material as zero in helper lanes, so the implicit derivative of
// `uv * m.pattern.xy` across a triangle's edge was huge and edge pixels took the coarsest mip (the bright
// one-pixel rims on hard-edges' sign). Gradients of the interpolated uv are right in every lane; virtual
// samples also pass the pixel centre's gradients when uv itself is moved to a shading point.
vec4 surface_color_grad(Material m, vec2 uv, vec2 uv_dx, vec2 uv_dy)
{
	uint pattern = uint(m.color2.w);
	vec4 c = m.base_color;
	if (pattern == PATTERN_CHECKER) {
		vec2 cell = floor(uv * m.pattern.xy);
		if (mod(cell.x + cell.y, 2.0) >= 1.0)
			c.rgb = m.color2.rgb;
	} else if (pattern == PATTERN_STRIPES) {
		if (fract(uv.x * m.pattern.x) < m.pattern.z)
			c.rgb = m.color2.rgb;
	} else if (pattern == PATTERN_TEXTURE) {
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
	if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))))
		return 1.0;
	// reversed-Z: the stored depth is the closest occluder (largest); a slope-scaled bias keeps
	// surfaces from shadowing themselves.
	float bias = 0.0005 + 0.002 * (1.0 - ndotl);
	return texture(shadow_map, vec3(uv, ndc.z + bias));
}

// Lit linear colour of a surface point; base is the surface colour (alpha handled by the caller).
vec3 shade(Material m, vec4 base, vec3 world, vec3 normal, bool front_facing)
{
	// Stability tests poison a sparse pattern of pixels with NaN and +Inf: nothing downstream may keep them.
	if (frame.counts.z != 0) {
		ivec2 p = ivec2(gl_FragCoord.xy);
		if ((p.x + 3 * p.y) % 11 == 0)
			return vec3(uintBitsToFloat(0x7fc00000u)); // NaN
		if ((p.x + 3 * p.y) % 11 == 5)
			return vec3(uintBitsToFloat(0x7f800000u)); // +Inf
	}
	uint flags = uint(m.shading.w);
	if ((flags & MATERIAL_UNLIT) != 0u)
		return base.rgb;
	vec3 n = normalize(normal);
	if (!front_facing)
		n = -n; // two-sided: thin blinds and wires are seen from both sides
	vec3 v = normalize(frame.camera_position.xyz - world);
	vec3 color = frame.ambient.rgb * base.rgb;
	float specular = m.shading.x;
	float shininess = mix(512.0, 4.0, clamp(m.shading.y, 0.0, 1.0));
	for (int i = 0; i < frame.counts.x; i++) {
		Light light = frame.lights[i];
		vec3 l;
		vec3 radiance = light.color_range.rgb;
		if (light.position_type.w < 0.5) {
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
		if (ndotl <= 0.0)
			continue;
		float vis = 1.0;
		if (light.shadow.x > 0.5 && frame.counts.y != 0)
			vis = shadow_visibility(world, ndotl);
		vec3 lit = base.rgb * ndotl;
		if (specular > 0.0) {
			vec3 h = normalize(l + v);
			// normalised Blinn-Phong so rough and smooth surfaces reflect similar energy
			lit += specular * (shininess + 8.0) / 25.13274 * pow(max(dot(n, h), 0.0), shininess) * ndotl;
		}
		color += vis * radiance * lit;
	}
	return color;
}
