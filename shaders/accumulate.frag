#version 450
// Accumulation: adds one jittered render, times a weight, into the float target (blend ONE+ONE). The
// reference uses weight 1 and divides at readback; virtual MSAA samples use 1/N.
layout(set = 0, binding = 0) uniform sampler2D source;
layout(push_constant) uniform Push { float weight; } push;
layout(location = 0) out vec4 out_color;

void main()
{
	out_color = texelFetch(source, ivec2(gl_FragCoord.xy), 0) * push.weight;
}
