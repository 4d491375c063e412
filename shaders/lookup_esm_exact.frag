#version 450 core
// esm-exact's lookup (render/src/esm.cpp; the paper's own lookup is esm's,
// lookup_esm.frag). The edge map holds, per texel, the signed distance in
// texels to the silhouette edge that won the depth-resolved priority
// (esm_exact_edges.frag; positive on the occluder's side) and that edge's
// light depth. The 2 x 2 depth comparisons (gathered) decide fully lit and
// fully shadowed footprints; otherwise the bilinear distance decides, its zero
// (the 50% point) on the true edge: a straight edge's signed distance is
// linear, so bilinear interpolation reproduces it (Bujnak 2004, Sect. 3.1).
//  - no texel's edge in front of the receiver (its stored depth kInFront
//    nearer the light than the receiver's plane at the texel's centre, the
//    receiver's window depth carried along its screen-derivative slope):
//    lit, as lookup_edsm.frag's step 1 (the comparisons differ from the
//    receiver's own slope or outline alone);
//  - a texel with no edge, or whose side of its edge disagrees with its own
//    comparison (crossing shadows; a receiver's outline and a caster's edge in
//    one texel), takes the plane through the other three;
//  - two such texels, or a receiver not behind the stored edges (its own
//    outline): the bilinearly filtered comparison's 50% point (the same
//    boundary rule as the edge's, on the depth comparisons), compared 3e-5 *
//    cos(incidence) of window depth nearer the light. The extra bias: on the
//    default scene's block tower the face under a block is lit up to the
//    joint, and its texels there hold the block above, within a few 1e-5;
//    geombench error_cast pixels at 512 / 1024 / 2048 without it, with 2e-5,
//    3e-5 and 5e-5 (times the cosine): default 18/13/8, 2/0/0, 1/0/0, 1/0/0
//    (ssm 1/0/0); quake3 45/36/15, 3/3/5, 3/3/0, 1/1/0 (ssm 16/0/0); scan
//    0/0/0, 0/0/0, 0/0/0, 3/0/0 (ssm 1/0/0: light leaks at the bunny's
//    contact with the ground). The fallback itself, measured against
//    the nearest texel's comparison (geombench, 640x480, 1 frame, error_cast at
//    512 / 1024): jenga 0.460 / 0.152% -> 0.305 / 0.119%, default 0.015 /
//    0.008% -> 0.008 / 0.006%, scan@512 0.001% -> 0.000%, wide-depth 1.51 /
//    1.34% -> 1.51 / 1.28%; the footprint's most lit texel instead (any lit
//    texel lights) gave jenga 0.184% and default 0.006 / 0.002%, but scan@512
//    error_visible 0.122% against ssm's 0.092% (its terminators leak).
// The in-front rule (the first case), measured (geombench, 640x480, 1 frame,
// wrong pixels at 512 / 1024 / 2048 / 4096; ssm in brackets): without it
// jenga cast 658/257/62/36 (3658/1371/443/202), quake3 visible 111/10/10/17
// (344/165/34/0), default cast 1/0/0/0 (1/0/0/0) and visible at 4096 6 (0),
// scan visible 152/56/20/9 (200/66/47/48); with it, kInFront 2e-5: jenga
// 658/252/60/15, quake3 2/0/0/0, default cast 0/0/0/0, visible at 4096 4,
// scan 163/56/23/15. kInFront 2e-6: default cast 1 at 512, jenga 20 at 4096;
// 3e-5: scan@512 1 cast pixel (ssm 1), default visible at 4096 2; 5e-5: scan
// visible 214 at 512 (ssm 200). Edges not in front also counted as odd
// texels (taking the plane or the filtered comparison): jenga 558/250/78/19;
// the 1e-4 test below replaced by the in-front rule per texel: jenga
// 666/267/84/16. Both not kept.
vec4 face_clip(vec3 world, out int layer);  // lookup_faces.frag: the face and its clip position
uniform sampler2DArrayShadow u_shadow_map;  // comparison sampler, gathered; a layer per face
uniform sampler2DArray u_edge_map;          // RG32F: signed distance in texels, edge depth
uniform vec4 u_light;                       // shade.frag's light: for the receiver's facing

const float kInFront = 2.0e-5;  // window depth: an edge this far in front of the receiver (its plane) can shadow it
const float kPlaneMax = 1.0e-3;  // the receiver plane's reach in window depth (grazing receivers)

float shadow_visibility(vec3 world, vec3 normal) {
  int layer;
  vec4 c = face_clip(world, layer);
  vec3 p = c.xyz / c.w * 0.5 + 0.5;
  ivec2 size = textureSize(u_edge_map, 0).xy;
  vec2 tc = p.xy * vec2(size) - 0.5;
  // The receiver's plane in the map: window depth per texel, from the screen derivatives.
  mat2 J = mat2(dFdx(tc), dFdy(tc));
  vec2 dz = vec2(dFdx(p.z), dFdy(p.z));
  vec2 grad = abs(determinant(J)) > 1.0e-12 ? dz * inverse(J) : vec2(0.0);
  if (c.w <= 0.0) return 1.0;
  if (any(lessThan(p, vec3(0.0))) || any(greaterThan(p, vec3(1.0)))) return 1.0;
  ivec2 i = ivec2(floor(tc));
  vec2 f = tc - floor(tc);
  // The comparisons of the 2 x 2 footprint (gather order: (0,1) (1,1) (1,0) (0,0)).
  vec4 g = textureGather(u_shadow_map, vec3(p.xy, float(layer)), p.z);
  if (all(equal(g, vec4(g.x)))) return g.x;
  float d[4];
  float edge_depth = 0.0;
  vec4 lit = vec4(g.w, g.z, g.x, g.y);  // footprint order (0,0) (1,0) (0,1) (1,1)
  int odd = -1, odd_count = 0, front = 0;
  for (int k = 0; k < 4; ++k) {
    vec2 t = texelFetch(u_edge_map, ivec3(clamp(i + ivec2(k & 1, k >> 1), ivec2(0), size - 1), layer), 0).rg;
    d[k] = t.r;
    // The receiver's depth at the texel's centre, on its plane: is the edge in front of it?
    float z_at = p.z + clamp(dot(grad, vec2(k & 1, k >> 1) - f), -kPlaneMax, kPlaneMax);
    front += abs(t.r) <= 1.0e6 && t.g + kInFront <= z_at ? 1 : 0;
    if (abs(t.r) > 1.0e6 || (t.r <= 0.0) != (lit[k] > 0.5)) {
      odd = k, ++odd_count;
    } else {
      edge_depth = max(edge_depth, t.g);
    }
  }
  float facing = max(dot(normalize(normal), normalize(u_light.xyz - world * u_light.w)), 0.0);
  vec4 gb = textureGather(u_shadow_map, vec3(p.xy, float(layer)), p.z - 3e-5 * facing);
  vec4 lb = vec4(gb.w, gb.z, gb.x, gb.y);
  float filtered = mix(mix(lb[0], lb[1], f.x), mix(lb[2], lb[3], f.x), f.y) >= 0.5 ? 1.0 : 0.0;
  if (front == 0) return 1.0;  // no edge in front of the receiver: lit
  if (odd_count > 1) return filtered;
  if (p.z <= edge_depth + 1.0e-4) return filtered;  // the receiver's own outline
  if (odd >= 0) d[odd] = d[odd ^ 1] + d[odd ^ 2] - d[odd ^ 3];
  float dist = mix(mix(d[0], d[1], f.x), mix(d[2], d[3], f.x), f.y);
  return dist > 0.0 ? 0.0 : 1.0;
}
