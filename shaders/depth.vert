#version 450 core
// Depth-only pass (shadow maps; camera depth of shadow volumes): world positions
// through one matrix. v_position (the local-frame position) feeds depth_linear.frag.
layout(location = 0) in vec3 a_position;
uniform mat4 u_matrix;
out vec3 v_position;
void main() {
  v_position = a_position;
  gl_Position = u_matrix * vec4(a_position, 1.0);
}
