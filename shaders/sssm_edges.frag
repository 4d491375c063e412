#version 450 core
// Shadow silhouette map (Sen et al. 2003), silhouette-map pass, per cell the
// quad covers: the cell's representative point on the silhouette, stored as
// its offset from the cell's centre (texels, in [-0.5, 0.5]^2; the map is
// cleared to 0, the default point at the centre). As in the paper: an end
// point of the segment (a silhouette vertex) lying in the cell is stored;
// otherwise the segment's crossings with the cell's two diagonals (their mean
// where it crosses both); a segment that crosses the cell without meeting a
// diagonal (it clips a corner) stores the middle of its part inside the cell.
// One point per cell: where several edges meet a cell the one nearest the light
// is kept (the depth test; Sen et al. keep the last one drawn, an order a
// rasterizer does not fix). Edges hidden from the light are not written: the
// edge's depth at the point is compared with the farthest of the 3 x 3 depth
// texels around it (as in edsm_edges.frag).
flat in vec4 f_segment;
flat in vec2 f_depth;
uniform float u_map_size;
uniform sampler2D u_depth;  // the light's depth map, read without comparison
layout(location = 0) out uvec2 o_point;

// The segment's crossing with the diagonal c + s d (|s| <= 0.5), as segment parameter; -1 when none.
float crossing(vec2 A, vec2 ab, vec2 c, vec2 d) {
  float den = ab.x * d.y - ab.y * d.x;  // cross(ab, d)
  if (den == 0.0) return -1.0;
  vec2 ac = c - A;
  float u = (ac.x * d.y - ac.y * d.x) / den;   // along the segment
  float s = (ac.x * ab.y - ac.y * ab.x) / den;  // along the diagonal
  return (u >= 0.0 && u <= 1.0 && abs(s) <= 0.5) ? u : -1.0;
}

void main() {
  vec2 c = gl_FragCoord.xy;  // the cell's centre
  vec2 A = f_segment.xy, B = f_segment.zw, ab = B - A;
  float u;
  if (all(lessThanEqual(abs(A - c), vec2(0.5)))) {
    u = 0.0;
  } else if (all(lessThanEqual(abs(B - c), vec2(0.5)))) {
    u = 1.0;
  } else {
    float u1 = crossing(A, ab, c, vec2(1.0, 1.0)), u2 = crossing(A, ab, c, vec2(1.0, -1.0));
    if (u1 < 0.0 && u2 < 0.0) {  // clipping a corner: the middle of the part inside the cell
      vec2 lo = (c - 0.5 - A) / ab, hi = (c + 0.5 - A) / ab;
      vec2 t0 = min(lo, hi), t1 = max(lo, hi);
      float a = max(max(t0.x, t0.y), 0.0), b = min(min(t1.x, t1.y), 1.0);
      if (!(a <= b)) discard;
      u = 0.5 * (a + b);
    } else {
      u = u1 < 0.0 ? u2 : u2 < 0.0 ? u1 : 0.5 * (u1 + u2);
    }
  }
  vec2 p = A + u * ab;
  float z_edge = mix(f_depth.x, f_depth.y, u);
  float z_far = 0.0;
  ivec2 t = ivec2(floor(p + 0.5)), top = ivec2(u_map_size) - 1;  // the depth texel under the point
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) z_far = max(z_far, texelFetch(u_depth, clamp(t + ivec2(x, y), ivec2(0), top), 0).r);
  if (z_edge > z_far + 1e-5) discard;
  // r: the offset, times 2 as two snorm16 (1 / 65534 texel); g: the edge depth's bits.
  o_point = uvec2(packSnorm2x16(clamp(2.0 * (p - c), vec2(-1.0), vec2(1.0))), floatBitsToUint(z_edge));
  gl_FragDepth = clamp(z_edge, 0.0, 1.0);
}
