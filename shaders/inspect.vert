#version 450 core
// Inspection overlay lines (boundary, non-manifold, inconsistent edges and the
// edges of degenerate faces), world positions through the camera.
layout(location = 0) in vec3 a_position;
uniform mat4 u_matrix;
void main() { gl_Position = u_matrix * vec4(a_position, 1.0); }
