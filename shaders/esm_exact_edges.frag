#version 450 core
// esm-exact's quad pass (render/src/esm.cpp): Bujnak 2004's silhouette quads
// (esm_quad.vert: the degenerate quads with their bevel quads, Sect. 4.1)
// drawn WITH a depth test that resolves overlaps, instead of the paper's MAX
// blending of the encoded distance. Per sample, into an RG32F map cleared to
// 3e38 ("no edge"):
//   r  the signed distance to the edge's line in texels, positive on the
//      occluder's side (v_side < 0), unencoded: the lookup puts the boundary on
//      the true edge (its 50% point), with no 0.707-texel shift
//   g  the edge's own light window depth at the sample's foot on it
// Priority (written as fragment depth, the smallest kept): 0.95 of the edge's
// light depth, 0.05 of the distance to the edge segment (the corner vertex
// beyond its ends), as lookup_edsm.frag's distance map does (Kenzel 2013, eq. 3.8
// resolved with depth): where quads overlap the edge nearer the light wins, a
// caster's edge over a receiver's own outline. MAX blending keeps the edge the
// sample is least inside, which on jenga is the lower block's own outline.
// The weight of depth, measured (geombench jenga@512 error_cast pixels, 1
// frame): 0.8 1,496, 0.95 658, 0.99 1,387; 2048 and the other scenes the same.
// Edges hidden from the light are not written (Bujnak 2004, Sect. 3.1): the edge's
// depth against the farthest of the 3 x 3 depth-map texels around the sample
// (against the texel under the sample alone, as the paper's depth test does:
// the same within a pixel on jenga, default, scan, quake3 and duelling at 512
// and 2048, wide-depth@2048 error_cast 2.49% against 2.41%; not kept).
in float v_side;
flat in vec4 v_edge;    // edge end points in the light's NDC
flat in vec2 v_edge_z;  // their NDC depths
uniform float u_map_size;
uniform float u_reach;      // texels around the edge segment that are written
uniform sampler2D u_depth;  // the light's depth map, without comparison
layout(location = 0) out vec2 o_edge;

void main() {
  vec2 p = gl_FragCoord.xy / u_map_size * 2.0 - 1.0;
  vec2 a = v_edge.xy, ab = v_edge.zw - v_edge.xy;
  float len2 = dot(ab, ab);
  if (len2 <= 0.0) discard;
  float texels = u_map_size * 0.5;
  float t = clamp(dot(p - a, ab) / len2, 0.0, 1.0);
  float priority = length(p - (a + t * ab)) * texels;
  if (priority > u_reach) discard;
  float line = abs(ab.x * (p.y - a.y) - ab.y * (p.x - a.x)) * inversesqrt(len2);  // NDC distance to the line
  float d = v_side < 0.0 ? line * texels : -line * texels;
  float z_edge = clamp(mix(v_edge_z.x, v_edge_z.y, t) * 0.5 + 0.5, 0.0, 1.0);
  float z_far = 0.0;
  ivec2 c = ivec2(gl_FragCoord.xy), top = ivec2(u_map_size) - 1;
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) z_far = max(z_far, texelFetch(u_depth, clamp(c + ivec2(x, y), ivec2(0), top), 0).r);
  if (z_edge > z_far + 1e-5) discard;
  o_edge = vec2(d, z_edge);
  gl_FragDepth = 0.95 * z_edge + 0.05 * priority / (u_reach + 1.0);
}
