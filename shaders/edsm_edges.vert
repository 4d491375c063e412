#version 450 core
// Edge distance shadow map (Kenzel 2013, Sect. 3.2 and 4.2.1), distance-map
// pass: welded vertices to light clip space; the geometry shader works on the
// adjacency index buffer (geom/adjacency.h, GL_TRIANGLES_ADJACENCY).
layout(location = 0) in vec3 a_position;
uniform mat4 u_matrix;  // world -> light clip
out vec4 g_clip;
void main() {
  g_clip = u_matrix * vec4(a_position, 1.0);
  gl_Position = g_clip;
}
