#version 450
// SMAA T2x, S2x and 4x, the last pass: the mean of the frame's sample images (S2x, 4x: the reference adds
// the second sample with a constant blend factor of 0.5), then for the temporal modes the reference's
// temporal resolve with reprojection: the previous frame's output is read at the reprojected position
// (point sampled) and mixed in with weight 0.5, lowered towards 0 where the lengths of the two frames'
// velocities differ (alpha holds sqrt(5 |velocity in UV units|); SMAA_REPROJECTION_WEIGHT_SCALE 30).
// Colours are linear, as the reference's sRGB views make them; the output's alpha is 1.
layout(constant_id = 0) const int SAMPLES = 1;       // sample images per frame: 1 (T2x) or 2 (S2x, 4x)
layout(constant_id = 1) const bool TEMPORAL = false; // T2x, 4x
layout(set = 0, binding = 0) uniform sampler2D current0;
layout(set = 0, binding = 1) uniform sampler2D current1;
layout(set = 0, binding = 2) uniform sampler2D previous0; // TEMPORAL: the previous frame's sample images
layout(set = 0, binding = 3) uniform sampler2D previous1;
layout(set = 0, binding = 4) uniform sampler2D velocity_tex; // TEMPORAL: RG16F pixels; history at p - v
layout(push_constant) uniform Push {
	int history_valid; // 0 on the first frame and after a camera cut
} push;
layout(location = 0) out vec4 out_colour;

const float REPROJECTION_WEIGHT_SCALE = 30.0;

void main()
{
	ivec2 p = ivec2(gl_FragCoord.xy);
	vec4 current = texelFetch(current0, p, 0);
	if (SAMPLES == 2)
		current = 0.5 * (current + texelFetch(current1, p, 0));
	if (!TEMPORAL || push.history_valid == 0) {
		out_colour = vec4(current.rgb, 1.0);
		return;
	}
	ivec2 last = textureSize(current0, 0) - 1;
	vec2 v = texelFetch(velocity_tex, p, 0).rg;
	ivec2 q = clamp(ivec2(floor(gl_FragCoord.xy - v)), ivec2(0), last);
	vec4 previous = texelFetch(previous0, q, 0);
	if (SAMPLES == 2)
		previous = 0.5 * (previous + texelFetch(previous1, q, 0));
	float delta = abs(current.a * current.a - previous.a * previous.a) / 5.0;
	float weight = 0.5 * clamp(1.0 - sqrt(delta) * REPROJECTION_WEIGHT_SCALE, 0.0, 1.0);
	out_colour = vec4(mix(current.rgb, previous.rgb, weight), 1.0);
}
