// simple-taa, pass 2 (a compute pass): a light unsharp mask over the resolved image. One invocation per
// pixel (aa_pixel); invocations beyond the frame's edge never reach main.
void main()
{
	ivec2 p = aa_pixel;
	vec3 c = texelFetch(resolve, p, 0).rgb;
	vec3 blur = 0.25 * (texelFetch(resolve, aa_clamp_pixel(p + ivec2(1, 0)), 0).rgb +
			    texelFetch(resolve, aa_clamp_pixel(p + ivec2(-1, 0)), 0).rgb +
			    texelFetch(resolve, aa_clamp_pixel(p + ivec2(0, 1)), 0).rgb +
			    texelFetch(resolve, aa_clamp_pixel(p + ivec2(0, -1)), 0).rgb);
	aa_write(vec4(max(c + params.sharpen * (c - blur), vec3(0.0)), 1.0));
}
