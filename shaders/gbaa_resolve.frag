#version 450
// GBAA resolve: one bilinear fetch, shifted toward the neighbour across the edge by the uncovered share of
// the pixel. When this pixel's own geometry has no edge inside it (silhouettes: the edge belongs to the
// neighbour's triangle), the four neighbours are asked whether their edge cuts this pixel.
layout(set = 0, binding = 0) uniform sampler2D color;  // linear colour, bilinear sampler
layout(set = 0, binding = 1) uniform sampler2D edges;  // RG16F offsets, nearest
layout(location = 0) out vec4 out_color;

void main()
{
	ivec2 p = ivec2(gl_FragCoord.xy);
	ivec2 last = textureSize(edges, 0) - 1;
	vec2 offset = texelFetch(edges, p, 0).xy;
	if (min(abs(offset.x), abs(offset.y)) >= 0.5) {
		offset = vec2(0.5);
		float left = texelFetch(edges, clamp(p + ivec2(-1, 0), ivec2(0), last), 0).x;
		float right = texelFetch(edges, clamp(p + ivec2(1, 0), ivec2(0), last), 0).x;
		float up = texelFetch(edges, clamp(p + ivec2(0, -1), ivec2(0), last), 0).y;
		float down = texelFetch(edges, clamp(p + ivec2(0, 1), ivec2(0), last), 0).y;
		if (left >= 0.5 && left <= 1.0)
			offset.x = left - 1.0;
		if (right >= -1.0 && right <= -0.5)
			offset.x = right + 1.0;
		if (up >= 0.5 && up <= 1.0)
			offset.y = up - 1.0;
		if (down >= -1.0 && down <= -0.5)
			offset.y = down + 1.0;
	}
	vec2 half_step = vec2(offset.x >= 0.0 ? 0.5 : -0.5, offset.y >= 0.0 ? 0.5 : -0.5);
	vec2 shift = clamp(half_step - offset, vec2(-0.5), vec2(0.5));
	out_color = texture(color, (gl_FragCoord.xy + shift) / vec2(textureSize(color, 0)));
}
