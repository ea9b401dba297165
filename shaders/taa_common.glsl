// Shared pieces of the TAA passes (seed 001): colour space, finite checks, the history clip, feedback.

vec3 rgb_to_ycocg(vec3 c)
{
	return vec3(0.25 * c.r + 0.5 * c.g + 0.25 * c.b, 0.5 * c.r - 0.5 * c.b, -0.25 * c.r + 0.5 * c.g - 0.25 * c.b);
}

vec3 ycocg_to_rgb(vec3 c)
{
	return vec3(c.x + c.y - c.z, c.x + c.z, c.x - c.y - c.z);
}

bool finite3(vec3 c)
{
	return !any(isnan(c)) && !any(isinf(c));
}

// Clips history h toward the point c inside the box [lo, hi] (INSIDE's clip_aabb, which seed 001
// builds on): a history colour outside the box is replaced by where the segment c->h leaves it.
// Clipping, not clamping, keeps the colour's hue instead of snapping it to a corner.
vec3 clip_toward(vec3 h, vec3 c, vec3 lo, vec3 hi)
{
	vec3 d = h - c;
	float t = 1.0;
	for (int i = 0; i < 3; i++) {
		if (d[i] > 1e-7)
			t = min(t, (hi[i] - c[i]) / d[i]);
		else if (d[i] < -1e-7)
			t = min(t, (lo[i] - c[i]) / d[i]);
	}
	return c + d * clamp(t, 0.0, 1.0);
}

// Feedback (weight of history) from the luminance difference, biased toward history: identical
// luminance gives feedback_max, very different luminance feedback_min.
float feedback(float y_current, float y_history, float feedback_min, float feedback_max)
{
	float diff = abs(y_current - y_history) / max(y_current, max(y_history, 0.2));
	float w = 1.0 - clamp(diff, 0.0, 1.0);
	return mix(feedback_min, feedback_max, w * w);
}

// A history position is usable when the velocity is valid and the position lies inside the image:
// off-screen reprojections are rejected, never clamped to the border.
bool history_position(vec2 pixel_centre, vec2 velocity, vec2 size, out vec2 uv)
{
	vec2 prev = pixel_centre - velocity;
	uv = prev / size;
	return all(lessThan(abs(velocity), vec2(60000.0))) && all(greaterThanEqual(prev, vec2(0.0))) &&
	       all(lessThan(prev, size));
}

#if MASTER_TAA
// seed 001's aliasedValue: model IDs, depth pseudo-variances of the current and the reprojected depth,
// and the stabilised Sobel image blended between its cross and 3x3 averages (one place for both resolves)
float master_aliased_value(sampler2D sobel, ivec2 p, ivec2 last, float model_average, float depth, float past_depth,
			   bool valid, float dmin, float dmax, float davg)
{
	float max_depth_distance = min(abs(dmin - davg), abs(dmax - davg));
	float dpv = 0.0, dtpv = 0.0;
	if (max_depth_distance >= 0.002) {
		dpv = pow(abs(depth - davg) / max_depth_distance, 2.0);
		if (valid)
			dtpv = pow(abs(past_depth - davg) / max_depth_distance, 4.0);
	}
	float s = texelFetch(sobel, p, 0).r, s3 = 0.0, sx = 0.0;
	for (int y = -1; y <= 1; y++)
		for (int x = -1; x <= 1; x++) {
			float e = texelFetch(sobel, clamp(p + ivec2(x, y), ivec2(0), last), 0).r;
			s3 += e;
			if (x == 0 || y == 0)
				sx += e;
		}
	float mix_value = clamp(model_average + s, 0.0, 1.0);
	float sobel_avg = mix(sx / 5.0, s3 / 9.0, mix_value);
	return clamp(sobel_avg + dpv + dtpv + model_average, 0.0, 1.0);
}
#endif
