#version 450
// msaa's resolve with tonemapped_resolve=true (hardware samples): Karis' weights 1 / (1 + luma) over the
// pixel's samples instead of the render pass's box resolve (shaders/resolve_karis.frag says why).
layout(set = 0, binding = 0) uniform sampler2DMS source;
layout(push_constant) uniform Push { int samples; } push;
layout(location = 0) out vec4 out_color;

void main()
{
	ivec2 p = ivec2(gl_FragCoord.xy);
	vec4 sum = vec4(0.0);
	float weights = 0.0;
	for (int i = 0; i < push.samples; i++) {
		vec4 c = texelFetch(source, p, i);
		float w = 1.0 / (1.0 + max(dot(c.rgb, vec3(0.2126, 0.7152, 0.0722)), 0.0));
		sum += c * w;
		weights += w;
	}
	out_color = sum / weights;
}
