#version 450 core
// Omnidirectional shadow map (Gerasimov 2004, Sect. 12.3): world positions to the geometry
// shader, which renders all six faces in one pass.
layout(location = 0) in vec3 a_position;
out vec3 g_world;
void main() {
  g_world = a_position;
  gl_Position = vec4(a_position, 1.0);
}
