// simple-taa, pass 1: reproject the last frame's resolved image with this frame's velocity, clamp it to
// the 3x3 colour box of this (jittered) frame, and blend. `previous_resolve` is this pass's own output of
// the previous frame; aa_history_frames is 0 on the first frame and after a camera cut.
void main()
{
	ivec2 p = aa_pixel;
	vec3 c = texelFetch(colour, p, 0).rgb;
	vec3 lo = c, hi = c;
	for (int y = -1; y <= 1; y++)
		for (int x = -1; x <= 1; x++) {
			vec3 s = texelFetch(colour, aa_clamp_pixel(p + ivec2(x, y)), 0).rgb;
			lo = min(lo, s);
			hi = max(hi, s);
		}
	// velocity: pixels moved since the previous frame, so this point was at p - velocity then
	vec2 v = texelFetch(velocity, p, 0).xy;
	vec2 uv = (vec2(p) + 0.5 - v) * aa_size.zw;
	bool on_screen = all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0)));
	vec3 h = clamp(texture(previous_resolve, uv).rgb, lo, hi);
	// a running mean over the first frames, then exponential: converges without a long blur-in
	float feedback = min(params.feedback, float(aa_history_frames) / float(aa_history_frames + 1));
	if (!aa_history_valid || !on_screen)
		feedback = 0.0;
	aa_write(vec4(mix(c, h, feedback), 1.0));
}
