#version 450 core
// Inspection overlay lines (boundary, non-manifold, inconsistent edges, the
// edges of degenerate faces, the focus body), world positions through the
// camera; inspect.geom widens each into a screen-space quad.
layout(location = 0) in vec3 a_position;
uniform mat4 u_matrix;
void main() { gl_Position = u_matrix * vec4(a_position, 1.0); }
