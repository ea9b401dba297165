#version 450
// Virtual MSAA samples of the scene pass: passes scene.vert's attributes through and adds the
// fragment's barycentric coordinates, from which scene.frag finds
// which other samples of the pixel the triangle covers (shading_point.glsl).
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;

layout(location = 0) in vec3 in_world[];
layout(location = 1) in vec3 in_normal[];
layout(location = 2) in vec2 in_uv[];
layout(location = 8) in vec4 in_tangent[];
layout(location = 9) in vec4 in_color[];
layout(location = 10) in vec4 in_shadow[];

layout(location = 0) out vec3 out_world;
layout(location = 1) out vec3 out_normal;
layout(location = 2) out vec2 out_uv;
layout(location = 8) out vec4 out_tangent; // passed through: normal maps, vertex colours
layout(location = 9) out vec4 out_color;
layout(location = 10) out vec4 out_shadow;
layout(location = 3) out vec3 out_barycentric;

void main()
{
	for (int v = 0; v < 3; v++) {
		gl_Position = gl_in[v].gl_Position;
		out_world = in_world[v];
		out_normal = in_normal[v];
		out_uv = in_uv[v];
		out_tangent = in_tangent[v];
		out_color = in_color[v];
		out_shadow = in_shadow[v];
		out_barycentric = vec3(v == 0, v == 1, v == 2);
		EmitVertex();
	}
	EndPrimitive();
}
