#version 450 core
// edsm-soft's distance-map pass (render/src/soft.cpp): welded vertices (input
// coordinates) to the light's clip space, and as they are for the geometry
// shader's penumbra reach (edsm_soft_edges.geom); the adjacency index buffer
// as in edsm_edges.vert (geom/adjacency.h).
layout(location = 0) in vec3 a_position;
uniform mat4 u_matrix;  // input coordinates -> the light's clip space
out vec4 g_clip;
out vec3 g_world;
void main() {
  g_world = a_position;
  g_clip = u_matrix * vec4(a_position, 1.0);
  gl_Position = g_clip;
}
