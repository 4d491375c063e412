#version 450 core
// The camera pass of every technique: world-space triangles with their face
// normal (the scene buffers are already in world space).
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
uniform mat4 u_view_proj;  // camera projection (infinite far plane) * look-at
uniform mat4 u_view;       // look-at alone, for the view depth
out vec3 v_world;
out vec3 v_normal;
out float v_view_depth;
void main() {
  v_world = a_position;
  v_normal = a_normal;
  v_view_depth = -(u_view * vec4(a_position, 1.0)).z;
  gl_Position = u_view_proj * vec4(a_position, 1.0);
}
