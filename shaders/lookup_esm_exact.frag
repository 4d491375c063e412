#version 450 core
// esm-exact's lookup (render/src/esm.cpp; the paper's own lookup is esm's,
// lookup_esm.frag). The edge map holds, per texel, the signed distance in
// texels to the silhouette edge that won the depth-resolved priority
// (esm_exact_edges.frag; positive on the occluder's side) and that edge's
// light depth. The 2 x 2 depth comparisons (depth_plane.frag: the receiver's
// plane against the map at each texel's centre, the test ssm makes)
// decide fully lit and fully shadowed footprints; otherwise the bilinear
// distance decides, its zero (the 50% point) on the true edge: a straight
// edge's signed distance is linear, so bilinear interpolation reproduces it
// (Bujnak 2004, Sect. 3.1). Where it cannot decide, ssm's own test (the
// nearest texel's comparison, the same map) does, so the edges only remove
// ssm's errors:
//  - no texel's edge in front of the receiver (its stored depth kInFront
//    nearer the light than the receiver's plane at the texel's centre): no
//    edge data for this receiver;
//  - a texel with no edge, or whose side of its edge disagrees
//    with its own comparison (crossing shadows; a receiver's outline and a
//    caster's edge in one texel);
//  - a receiver not behind the stored edges (its own outline);
//  - four distances that are not those of one straight edge (one_line).
// The same map: a point light's six faces are ssm's (silhouette_faces.cpp).
// The in-front rule, measured against the bilinear distance there (geombench,
// 640x480, 1 frame, wrong pixels at 512 / 1024 / 2048 / 4096; ssm in
// brackets, with its slope-scaled bias): without it jenga cast 658/257/62/36
// (3658/1371/443/202), quake3 visible 111/10/10/17 (344/165/34/0); with it,
// kInFront 2e-5: jenga 658/252/60/15, quake3 2/0/0/0. kInFront 2e-6: jenga 20
// at 4096; 5e-5: scan visible 214 at 512 (ssm 200).
vec4 face_clip(vec3 world, out int layer);  // lookup_faces.frag: the face and its clip position
mat4 face_matrix(int layer);
vec3 receiver_slope(mat4 m, vec3 world, vec3 normal, vec2 size, vec3 depth_gradient);  // depth_plane.frag
float nearest_lit(int layer, vec3 p, vec3 g);
vec4 footprint_lit(int layer, vec3 p, vec3 g, out ivec2 base, out vec2 f);
uniform sampler2DArray u_edge_map;  // RG32F: signed distance in texels, edge depth

const float kInFront = 2.0e-5;  // window depth: an edge this far in front of the receiver (its plane) can shadow it
const float kLineTolerance = 0.05;  // texels: one_line's allowance for the stored distances' rounding
const float kNearest = 0.7072;  // texels: the farthest the nearest texel's centre lies from the sample
const float kPlaneMax = 1.0e-3;  // the receiver plane's reach in window depth (grazing receivers)

// Whether four signed distances at the footprint's texel centres, (0,0) (1,0)
// (0,1) (1,1), in texels, are those of one straight edge: linear (no cross
// term) with a unit gradient. Edges closer than two texels (Kenzel 2013,
// Sect. 5.2) leave texels holding different edges, which fail this.
bool one_line(float d0, float d1, float d2, float d3) {
  const vec2 g = vec2(d1 - d0 + d3 - d2, d2 - d0 + d3 - d1) * 0.5;
  return abs(d0 - d1 - d2 + d3) < kLineTolerance && abs(length(g) - 1.0) < kLineTolerance;
}

// The edge's answer at signed distance `dist` (texels, positive on the
// occluder's side), where it can overrule ssm's: the nearest texel's centre
// lies within 0.707 texel of the sample, so a straight edge makes the two
// differ only within that distance of the sample. Not kept: leaving a band
// of 0.27 texel around the stored line to ssm (one segment's line carried up
// to the quads' reach misplaces a finely tessellated curved silhouette, the
// rippled sphere at 256, by a fraction of a texel): heavy@256 2037 wrong
// pixels against ssm's 2038 (2077 without), but it gave up most of the gains
// where a texel covers many pixels (geombench 640x480: wide-depth@2048 102
// against 21, ssm 102; colonnade@256 3558 against 1587, ssm 3671).
float decide(float dist, float ssm) {
  const float edge = dist > 0.0 ? 0.0 : 1.0;
  return edge == ssm || abs(dist) <= kNearest ? edge : ssm;
}

float shadow_visibility(vec3 world, vec3 normal) {
  int layer;
  vec4 c = face_clip(world, layer);
  if (c.w <= 0.0) return 1.0;
  vec3 p = c.xyz / c.w * 0.5 + 0.5;
  if (any(lessThan(p, vec3(0.0))) || any(greaterThan(p, vec3(1.0)))) return 1.0;
  ivec2 size = textureSize(u_edge_map, 0).xy;
  // The receiver's plane in the map: window depth per texel.
  const vec3 grad = receiver_slope(face_matrix(layer), world, normal, vec2(size), vec3(0.0));
  ivec2 i;
  vec2 f;
  const vec4 lit = footprint_lit(layer, p, grad, i, f);  // (0,0) (1,0) (0,1) (1,1)
  if (all(equal(lit, vec4(lit.x)))) return lit.x;
  const float ssm = nearest_lit(layer, p, grad);  // ssm's test, where the edges cannot decide
  float d[4];
  float edge_depth = 0.0;
  int odd_count = 0, front = 0;
  for (int k = 0; k < 4; ++k) {
    vec2 t = texelFetch(u_edge_map, ivec3(clamp(i + ivec2(k & 1, k >> 1), ivec2(0), size - 1), layer), 0).rg;
    d[k] = t.r;
    // The receiver's depth at the texel's centre, on its plane: is the edge in front of it?
    float z_at = p.z + clamp(dot(grad.xy, vec2(k & 1, k >> 1) - f), -kPlaneMax, kPlaneMax);
    front += abs(t.r) <= 1.0e6 && t.g + kInFront <= z_at ? 1 : 0;
    if (abs(t.r) > 1.0e6 || (t.r <= 0.0) != (lit[k] > 0.5)) {
      ++odd_count;
    } else {
      edge_depth = max(edge_depth, t.g);
    }
  }
  if (front == 0) return ssm;                      // no edge in front of the receiver
  if (odd_count > 0) return ssm;                   // crossing edges, or too little edge data
  if (p.z <= edge_depth + 1.0e-4) return ssm;      // the receiver's own outline
  if (!one_line(d[0], d[1], d[2], d[3])) return ssm;  // two edges within the footprint
  float dist = mix(mix(d[0], d[1], f.x), mix(d[2], d[3], f.x), f.y);
  return decide(dist, ssm);
}
