#version 450
// The rasterizer's floor (engine/methods/floor.c): every fragment of the scene writes one constant colour,
// so the pass costs rasterisation, the depth test and the target's stores, and no shading.
layout(location = 0) out vec4 out_color;

void main()
{
	out_color = vec4(0.5, 0.5, 0.5, 1.0);
}
