#version 450
// Box filter down by an integer factor: each output pixel averages the factor x factor block of the
// supersampled image that covers it (linear colour, so the average is physically meaningful).
layout(set = 0, binding = 0) uniform sampler2D source;
layout(push_constant) uniform Push { int factor; } push;
layout(location = 0) out vec4 out_color;

void main()
{
	ivec2 base = ivec2(gl_FragCoord.xy) * push.factor;
	vec4 sum = vec4(0.0);
	for (int y = 0; y < push.factor; y++)
		for (int x = 0; x < push.factor; x++)
			sum += texelFetch(source, base + ivec2(x, y), 0);
	out_color = sum / float(push.factor * push.factor);
}
