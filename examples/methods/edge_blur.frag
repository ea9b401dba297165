// edge-blur: where the local contrast is high, blend the pixel toward the mean of its four neighbours.
// A single-pass spatial filter, written against docs/user-methods.md only: `colour` is the frame's
// linear colour, `params` the method file's parameters, aa_write() the pass's output.
void main()
{
	ivec2 p = aa_pixel;
	vec3 c = texelFetch(colour, p, 0).rgb;
	vec3 n = texelFetch(colour, aa_clamp_pixel(p + ivec2(0, -1)), 0).rgb;
	vec3 s = texelFetch(colour, aa_clamp_pixel(p + ivec2(0, 1)), 0).rgb;
	vec3 w = texelFetch(colour, aa_clamp_pixel(p + ivec2(-1, 0)), 0).rgb;
	vec3 e = texelFetch(colour, aa_clamp_pixel(p + ivec2(1, 0)), 0).rgb;
	// contrast of the encoded (sRGB) luma, as an eye sees it: linear values would hide edges in the darks
	float l = aa_luma(aa_to_srgb(c)), ln = aa_luma(aa_to_srgb(n)), ls = aa_luma(aa_to_srgb(s));
	float lw = aa_luma(aa_to_srgb(w)), le = aa_luma(aa_to_srgb(e));
	float contrast = max(max(max(ln, ls), max(lw, le)), l) - min(min(min(ln, ls), min(lw, le)), l);
	float weight = params.strength * smoothstep(params.threshold, 2.0 * params.threshold, contrast);
	vec3 mean = 0.25 * (n + s + w + e);
	aa_write(vec4(mix(c, mean, weight), 1.0));
}
