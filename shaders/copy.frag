#version 450
// Full-screen copy: the bandwidth floor other passes are compared with.
layout(set = 0, binding = 0) uniform sampler2D source;
layout(location = 0) out vec4 out_color;

void main()
{
	out_color = texelFetch(source, ivec2(gl_FragCoord.xy), 0);
}
