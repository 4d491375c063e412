#version 450 core
// Extended-shadow-map silhouette quads (Bujnak 2004, Sect. 4.1, Figs. 3-5)
// from the static records of geom/esm_quads.h. The CPU reference is
// libgeom/src/extrude.cpp (esm_corners): the same math, in the same order.
//
// Draw: glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, quad_count), one
// instance per EsmQuad (stride 36, divisor 1). Corner gl_VertexID: 0 = p0 on
// side A, 1 = p1 on side A, 2 = p0 on side B, 3 = p1 on side B. A corner moves
// along q by +len when the light is in front of its side's plane, by -len/2
// when behind; len = u_extrude_scale * its clip-space w. Only silhouette edges
// (light in front of one side, behind the other) give a quad with area.
//
// GL state: face culling off (a quad's winding depends on the light's side),
// no depth or stencil test needed by the quads themselves; the render target
// and blending are the fragment shader's (esm_edges.frag: MAX blending on a
// float target). The light matrix is the shadow map's own, any projection.
//
// u_extrude_scale for any light matrix M = u_light_view_proj (perspective,
// orthographic, or warped: perspective shadow maps, LiSPSM): for quads t
// texels wide on an N-texel map,
//     u_extrude_scale = 2 t / (N s),
//     s = min(length(vec3(M[0][0], M[1][0], M[2][0])),
//             length(vec3(M[0][1], M[1][1], M[2][1])))
// (GLSL's M[column][row]: the x and y rows of M's upper 3 x 3), the least
// clip-space x or y that a unit length of the local frame can move at w = 1.
// Why it holds for every M: the corner moves by len = u_extrude_scale * w along
// the unit vector q, so its clip x moves by (M's x row . q) len and its
// normalized device x (clip / w) by u_extrude_scale (M's x row . q), whatever
// w is at the corner: the w factor cancels the perspective division, which is
// why the scale is per unit of w. Along the shorter row that is 2 t / N, t
// texels (2 / N of device coordinates per texel); no direction moves further
// than t times (longer row / shorter row) texels. M's w row also changes w by
// (M's w row . q) len, a relative change of order len / distance: second order
// for quads a few texels wide. render/src/light_fit.cpp projection_scale() is s.
//
// Uniforms:
//   mat4 u_light_view_proj    local frame (geom/face_planes.h) -> the shadow
//                             map's clip space
//   vec4 u_light              the light in the local frame: (x, y, z, 1) point,
//                             (x, y, z, 0) directional towards (x, y, z)
//   float u_extrude_scale     quad width per unit of clip w: 2 t / (N s), above
//   samplerBuffer u_planes    the quads' `planes`, an RGBA32F texture buffer
// Outputs:
//   v_side      +1 on the side whose plane faces the light, -0.5 on the other,
//               interpolated across the quad (0 on the edge itself)
//   v_edge      flat: the edge's endpoints in clip space (xy / w), for the
//               fragment's signed distance to the silhouette edge
//   v_edge_z    flat: their clip depths (z / w), for the edge's own light depth
//               at the fragment's foot on it (esm_exact_edges.frag)
layout(location = 0) in vec3 a_p0;
layout(location = 1) in vec3 a_p1;
layout(location = 2) in uint a_plane_a;
layout(location = 3) in uint a_plane_b;
layout(location = 4) in vec2 a_q;  // snorm16 x2, normalized: octahedral unit vector

uniform mat4 u_light_view_proj;
uniform vec4 u_light;
uniform float u_extrude_scale;
uniform samplerBuffer u_planes;

out float v_side;
flat out vec4 v_edge;
flat out vec2 v_edge_z;

const uint kFlip = 0x80000000u;

bool in_front(uint index) {
  vec4 p = texelFetch(u_planes, int(index & 0x7fffffffu));
  precise float s = p.x * u_light.x;
  s = s + p.y * u_light.y;
  s = s + p.z * u_light.z;
  s = s + p.w * u_light.w;
  return (s > 0.0) != ((index & kFlip) != 0u);
}

vec3 octahedral_decode(vec2 e) {
  e = max(e, vec2(-1.0));
  vec3 v = vec3(e.x, e.y, 1.0 - abs(e.x) - abs(e.y));
  if (v.z < 0.0) {
    vec2 o = v.xy;
    v.x = (1.0 - abs(o.y)) * (o.x >= 0.0 ? 1.0 : -1.0);
    v.y = (1.0 - abs(o.x)) * (o.y >= 0.0 ? 1.0 : -1.0);
  }
  return v / sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
}

void main() {
  int k = gl_VertexID;
  bool front = in_front(k < 2 ? a_plane_a : a_plane_b);
  vec3 p = (k & 1) == 0 ? a_p0 : a_p1;
  vec3 q = octahedral_decode(a_q);
  const mat4 m = u_light_view_proj;
  precise float w = m[0][3] * p.x;
  w = w + m[1][3] * p.y;
  w = w + m[2][3] * p.z;
  w = w + m[3][3];
  float len = u_extrude_scale * w;
  float offset = front ? len : -0.5 * len;
  v_side = front ? 1.0 : -0.5;
  vec4 e0 = m * vec4(a_p0, 1.0), e1 = m * vec4(a_p1, 1.0);
  v_edge = vec4(e0.xy / e0.w, e1.xy / e1.w);
  v_edge_z = vec2(e0.z / e0.w, e1.z / e1.w);
  gl_Position = m * vec4(p + q * offset, 1.0);
}
