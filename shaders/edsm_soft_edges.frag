#version 450 core
// edsm-soft's distance-map pass (soft.cpp): edsm_edges.frag with the quad's
// own half width (edsm_soft_edges.geom) and one priority scale for all quads
// (u_max_half_width), so that the depth test compares quads of any width, and
// the occlusion test made where the edge lies, not at the sample: the 3 x 3
// texels around the edge's point nearest the sample. A round occluder's front
// (a pipe, a sphere) stands in front of its own silhouette, so a test at the
// sample would kill the edge over the occluder itself, where the umbra half of
// its penumbra lies, and that half would take the hard answer once it spans
// more than a texel (crossed pipes, light-fraction error at 512 / 1024 / 2048:
// 0.0019 / 0.0031 / 0.0040 tested at the sample, 0.0015 / 0.0014 / 0.0014
// where the edge lies; tests/test_gl_soft_round_occluder.cpp).
// Otherwise as in edsm_edges.frag:
// Edge distance shadow map (Kenzel 2013), distance-map pass, per sample:
//  - the signed distance to the edge's line in texels (r) and the edge's light
//    depth at the sample (g) are written to the RG32F map;
//  - corner priority (eq. 3.8, its spherical form near a corner vertex): the
//    distance to the edge within its span, the distance to the corner vertex
//    beyond it, written as fragment depth; the depth test keeps the sample of
//    smallest priority where quads overlap (Sect. 4.2.1);
//  - occluded edges are killed against the light's depth map (Sect. 4.2.1):
//    the edge's own depth is compared with the farthest depth of the 3 x 3
//    texels around it (a silhouette's own surface is steep there).
flat in vec3 f_line;
flat in vec4 f_segment;
flat in vec2 f_depth;
uniform float u_map_size;
uniform float u_max_half_width;
flat in float f_half_width;
uniform sampler2D u_depth;  // the light's depth map, read without comparison
layout(location = 0) out vec2 o_edge;

void main() {
  vec2 p = gl_FragCoord.xy / u_map_size * 2.0 - 1.0;
  vec2 A = f_segment.xy, ab = f_segment.zw - f_segment.xy;
  float len2 = dot(ab, ab);
  float t = len2 > 0.0 ? clamp(dot(p - A, ab) / len2, 0.0, 1.0) : 0.0;
  float texels = u_map_size * 0.5;
  float priority = length(p - (A + t * ab)) * texels;
  if (priority > 2.0 * f_half_width) discard;
  float z_edge = mix(f_depth.x, f_depth.y, t) * 0.5 + 0.5;
  // The edge's visibility, where the edge lies (its point nearest the sample).
  float z_far = 0.0;
  ivec2 c = ivec2(floor(((A + t * ab) * 0.5 + 0.5) * u_map_size)), top = ivec2(u_map_size) - 1;
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) z_far = max(z_far, texelFetch(u_depth, clamp(c + ivec2(x, y), ivec2(0), top), 0).r);
  if (z_edge > z_far + 1e-5) discard;
  o_edge = vec2((dot(f_line.xy, p) + f_line.z) * texels, z_edge);
  gl_FragDepth = priority / (2.0 * u_max_half_width + 1.0);
}
