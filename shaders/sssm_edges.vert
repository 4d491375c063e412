#version 450 core
// Shadow silhouette map (Sen, Cammarano and Hanrahan 2003; summarised in seed
// Kenzel 2013, Sect. 2): silhouette-map pass, welded vertices to light clip space; the
// geometry shader works on the adjacency index buffer (geom/adjacency.h).
layout(location = 0) in vec3 a_position;
uniform mat4 u_matrix;  // world -> light clip
out vec4 g_clip;
void main() {
  g_clip = u_matrix * vec4(a_position, 1.0);
  gl_Position = g_clip;
}
