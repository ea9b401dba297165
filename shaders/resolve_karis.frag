#version 450
// ssaa's resolve with tonemapped_resolve=true: each output pixel averages the factor x factor block of the
// supersampled image with Karis' weights 1 / (1 + luma), i.e. in a tone-mapped space, so that one sample
// 1e4 times brighter than its neighbours counts about as much as an ordinary white one instead of turning
// the whole pixel white (and a dark edge in front of a bright background keeps its coverage).
layout(set = 0, binding = 0) uniform sampler2D source;
layout(push_constant) uniform Push { int factor; } push;
layout(location = 0) out vec4 out_color;

void main()
{
	ivec2 base = ivec2(gl_FragCoord.xy) * push.factor;
	vec4 sum = vec4(0.0);
	float weights = 0.0;
	for (int y = 0; y < push.factor; y++)
		for (int x = 0; x < push.factor; x++) {
			vec4 c = texelFetch(source, base + ivec2(x, y), 0);
			float w = 1.0 / (1.0 + max(dot(c.rgb, vec3(0.2126, 0.7152, 0.0722)), 0.0));
			sum += c * w;
			weights += w;
		}
	out_color = sum / weights;
}
