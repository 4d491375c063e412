#version 450 core
// Depth-only pass (shadow maps; camera depth of shadow volumes): world positions
// through one matrix. v_position (the local-frame position) feeds depth_linear.frag.
//
// GL state for a shadow map with depth.frag (render/src/shadow_map.cpp): a
// depth texture target (GL_DEPTH_COMPONENT24/32F, compare mode
// GL_COMPARE_REF_TO_TEXTURE, GL_LEQUAL, read as sampler2DShadow), cleared to 1;
// glEnable(GL_DEPTH_CLAMP) so casters in front of the light's near plane still
// occlude; glEnable(GL_POLYGON_OFFSET_FILL) with glPolygonOffset(k, 4.0), the
// slope-scaled bias (Kenzel 2013, Sect. 1.1.2; Arneson, Sect. 3.1): k = 1.5 for
// a single nearest lookup, more for a filter whose taps reach further (the
// viewer's 3 x 3 PCF: 3.5). Casters are drawn both sides (culling off).
layout(location = 0) in vec3 a_position;
uniform mat4 u_matrix;
out vec3 v_position;
void main() {
  v_position = a_position;
  gl_Position = u_matrix * vec4(a_position, 1.0);
}
