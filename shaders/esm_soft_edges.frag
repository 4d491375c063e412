#version 450 core
// esm-soft's quad pass (render/src/esm_soft.cpp): esm_edges.frag's
// silhouette quads (esm_quad.vert, as wide as the frame's widest penumbra)
// with the edge distance kept in texels instead of the paper's 8-bit code,
// so that it reaches across a penumbra; MAX blending as in esm_edges.frag:
//   r  kOffset + d, d the signed distance to the edge in texels, positive on
//      the lit side (v_side > 0); MAX keeps the edge the sample is least inside
//   g  unused
//   b  edge depth (the edge's light window depth at the sample's foot on it):
//      MAX keeps the farthest edge
//   a  1: this texel holds silhouette information
// Edges hidden from the light are not written (Bujnak 2004, Sect. 3.1), as in esm_edges.frag.
in float v_side;
flat in vec4 v_edge;  // edge end points in the light's NDC
uniform float u_map_size;
uniform sampler2D u_depth;  // the light's depth map, without comparison
layout(location = 0) out vec4 o_edge;

const float kOffset = 1024.0;  // keeps every stored distance above the clear value 0

void main() {
  vec2 p = gl_FragCoord.xy / u_map_size * 2.0 - 1.0;
  vec2 a = v_edge.xy, ab = v_edge.zw - v_edge.xy;
  float len = length(ab);
  if (len <= 0.0) discard;
  float line = abs(ab.x * (p.y - a.y) - ab.y * (p.x - a.x)) / len;  // NDC distance to the edge's line
  float d = line * u_map_size * 0.5 * sign(v_side);
  // The edge's own depth at the sample's foot on it: the quad is planar, so
  // window depth is affine across it (its screen gradient); the quad's depth
  // itself drifts from the edge's as it is extruded along q, tens of texels here.
  vec2 foot = a + ab * (dot(p - a, ab) / (len * len));
  float z_edge = gl_FragCoord.z + dot(vec2(dFdx(gl_FragCoord.z), dFdy(gl_FragCoord.z)), (foot - p) * u_map_size * 0.5);
  float z_far = 0.0;
  ivec2 c = ivec2(gl_FragCoord.xy), top = ivec2(u_map_size) - 1;
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) z_far = max(z_far, texelFetch(u_depth, clamp(c + ivec2(x, y), ivec2(0), top), 0).r);
  if (z_edge > z_far + 1e-5) discard;
  // Nor where the surface the depth map holds is not behind the edge: the edge
  // casts no penumbra there, and with MAX its distance would hide another
  // edge's (a ground's own rim around the shadows on it).
  if (texelFetch(u_depth, c, 0).r <= z_edge + 1e-5) discard;
  o_edge = vec4(kOffset + d, 0.0, z_edge, 1.0);
}
