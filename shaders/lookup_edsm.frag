#version 450 core
// Edge distance shadow map lookup (Kenzel 2013, Sect. 4.2.2) with two edges
// per texel, the thesis's own remedy for Sect. 5.2 (Sect. 6.1: "more than one
// channel to store the distance to more than one edge"; the map is
// shaders/edsm_edges.frag: per texel the two nearest edges as lines, distance
// from the texel's centre and normal angle, with their light depths).
// Where ssm's own comparisons of the 2 x 2 texel footprint (depth_plane.frag:
// the receiver's plane at each texel's centre; ssm's nearest texel is one of
// the four) agree, their answer is ssm's and stands. Otherwise the depth
// comparisons of the footprint at the sample's depth (textureGather on the
// comparison sampler, against the map drawn with the slope-scaled offset the
// edge pass needs) say whether the sample is fully lit, fully shadowed or near
// a silhouette (the comparisons differ). There:
//  1. Only edges in front of the receiver take part (kInFront): an edge at the
//     receiver's depth is its own outline and casts nothing on it. No such
//     edge in any of the four texels: no occluder's silhouette crosses the
//     footprint, the comparisons differ from the receiver's own outline or a
//     crease alone: lit.
//  2. Each texel's first edge in front gives its signed distance at the texel's
//     centre; where all four agree in side with their own comparisons the
//     bilinear interpolation decides (Sect. 3.1.1: exact for one straight
//     edge), unless a texel holds a second line in front (two edges within a
//     texel, Sect. 5.2). A texel that disagrees, or holds no edge in front,
//     goes to step 3.
//  3. Otherwise (Sect. 5.2: corners, edges closer than 2 texels) the thesis
//     proposes testing each edge separately and combining the results, e.g.
//     by a logical AND. Every line in front (up to 8) is evaluated exactly at
//     the sample and at the four texel centres: inside all of them (AND: a
//     convex corner, a strip) or inside any (OR: two occluders, a concave
//     corner), whichever agrees with all four of the footprint's comparisons
//     (AND first).
//  4. Neither (Sect. 5.2: the reconstruction cannot decide): ssm's own test.
// Wherever the edges cannot decide (a texel whose side disagrees with its
// comparison, two lines in one texel, lines that explain the footprint only
// with a miss), the answer is exactly ssm's: the same map
// (ssm draws it with the same offset, shadow_map.cpp's kMapSlope) and the
// same receiver-plane test of the nearest texel (depth_plane.frag), so the
// edges only remove ssm's errors (tests/test_gl_edge_map_law.cpp).
// Measured (geombench, 640x480, error_cast in % of the class; ssm 1.680 /
// 0.630 / 0.204 on jenga at 512 / 1024 / 2048): the earlier one-edge lookup
// (bilinear distance, plane for one odd texel, nearest comparison for two or
// for a receiver not behind the edges) 0.355 / 0.138 / 0.034; two edges with
// steps 1 and 3 only (no bilinear step, nearest comparison as the last
// resort) 0.976 / 0.142 / 0.032; with step 2 0.320 at 512; the last resort
// lit instead of nearest 0.240 / - / 0.006, a bilinear vote of each texel's
// own line (step 4) 0.245 / 0.057 / 0.006; the OR without the one-miss allowance 0.156 at 512 but scan's cast
// error 0.0054% against ssm's 0.0008%; the nearest-texel conditions 0.164 /
// 0.058 / 0.006; with the edge priority's depth weight 0.85 (edsm_edges.frag)
// 0.120 / 0.055 / 0.006. (Those allowed one texel disagreeing with the
// line, in step 2 taking the plane through the other three, and voted in
// step 4; allowing them broke the law of never being worse than ssm on
// random frames at maps of 40-96 texels.) ssm's footprint first (geombench,
// 640x480, 1 frame, wrong pixels at 256 / 512 / 1024; ssm in brackets): jenga
// 655 / 191 / 181 -> 235 / 168 / 181 (226 / 173 / 356); scan 515 / 193 / 62 ->
// 590 / 232 / 91 (652 / 251 / 108); heavy 1608 / 385 / 124 -> 1922 / 565 / 214
// (2038 / 684 / 276); the random frames of tests/test_gl_edge_map_law.cpp within
// ssm + 2 pixels on 359 of 360 (354 without). The whole footprint from ssm's
// comparisons, the gather dropped, put heavy and scan above ssm (heavy@1024 282
// against 276). Tried and not kept: a strip test for fully lit or
// fully shadowed footprints (a thin occluder or gap between texel centres:
// jenga 0.125 against 0.120); kInFront 1e-4 / 1e-5 / 0 (scan@2048
// error_visible 0.028 / 0.011 / 0.003%, jenga the same; 2e-6 gives 0.005%).
vec4 face_clip(vec3 world, out int layer);  // lookup_faces.frag: the face and its clip position
mat4 face_matrix(int layer);
vec3 receiver_slope(mat4 m, vec3 world, vec3 normal, vec2 size, vec3 depth_gradient);  // depth_plane.frag
float nearest_lit(int layer, vec3 p, vec3 g);
vec4 footprint_lit(int layer, vec3 p, vec3 g, out ivec2 base, out vec2 f);
uniform sampler2DArrayShadow u_shadow_map;  // comparison sampler, gathered; a layer per face
uniform usampler2DArray u_distance_map;  // RGBA32UI: (line, depth bits) x 2 per texel

const float kPi = 3.14159265358979;
const float kInFront = 2.0e-6;  // window depth: an edge this far in front of the receiver can shadow it

float shadow_visibility(vec3 world, vec3 normal) {
  int layer;
  vec4 c = face_clip(world, layer);
  if (c.w <= 0.0) return 1.0;
  vec3 p = c.xyz / c.w * 0.5 + 0.5;
  if (any(lessThan(p, vec3(0.0))) || any(greaterThan(p, vec3(1.0)))) return 1.0;
  ivec2 size = textureSize(u_distance_map, 0).xy;
  const vec3 slope = receiver_slope(face_matrix(layer), world, normal, vec2(size), vec3(0.0));
  vec2 tc = p.xy * vec2(size) - 0.5;
  ivec2 i = ivec2(floor(tc));
  vec2 f = tc - floor(tc);
  // The comparisons of the 2 x 2 footprint (gather order: (0,1) (1,1) (1,0) (0,0)).
  vec4 g = textureGather(u_shadow_map, vec3(p.xy, float(layer)), p.z);
  const vec4 lit = vec4(g.w, g.z, g.x, g.y);  // footprint order (0,0) (1,0) (0,1) (1,1)
  ivec2 plane_base;
  vec2 plane_f;
  const vec4 plane_lit = footprint_lit(layer, p, slope, plane_base, plane_f);  // ssm's comparisons
  if (all(equal(plane_lit, vec4(plane_lit.x)))) return plane_lit.x;  // ssm's answer, the four agreeing
  if (all(equal(lit, vec4(lit.x)))) return lit.x;  // fully lit or fully shadowed
  const float ssm = nearest_lit(layer, p, slope);           // ssm's test, where the edges cannot decide
  // The lines in front of the receiver, evaluated at the four texel centres
  // (offsets (0,0) (1,0) (0,1) (1,1) in texels) and at the sample (f).
  vec4 and_c = vec4(1.0e9), or_c = vec4(-1.0e9);
  float and_p = 1.0e9, or_p = -1.0e9;
  float d[4];  // each texel's first line in front: its distance at the texel's centre
  int odd_count = 0, lines = 0, pairs = 0;
  for (int k = 0; k < 4; ++k) {
    ivec2 o = ivec2(k & 1, k >> 1);
    uvec4 t = texelFetch(u_distance_map, ivec3(clamp(i + o, ivec2(0), size - 1), layer), 0);
    d[k] = 1.0e9;
    for (int e = 0; e < 2; ++e) {
      uint bits = e == 0 ? t.y : t.w;
      if (bits == 0xFFFFFFFFu || uintBitsToFloat(bits) + kInFront > p.z) continue;  // none, or not in front
      vec2 l = unpackUnorm2x16(e == 0 ? t.x : t.z);
      float dist = (l.x - 0.5) * 16.0, a = (l.y - 0.5) * 2.0 * kPi;
      vec2 n = vec2(cos(a), sin(a)), origin = vec2(o);
      vec4 at_c = dist + vec4(dot(n, -origin), dot(n, vec2(1, 0) - origin), dot(n, vec2(0, 1) - origin),
                              dot(n, vec2(1, 1) - origin));
      float at_p = dist + dot(n, f - origin);
      and_c = min(and_c, at_c), or_c = max(or_c, at_c);
      and_p = min(and_p, at_p), or_p = max(or_p, at_p);
      if (d[k] == 1.0e9) d[k] = dist; else ++pairs;
      ++lines;
    }
    if (d[k] == 1.0e9 || (d[k] <= 0.0) != (lit[k] > 0.5)) ++odd_count;
  }
  if (lines == 0) return 1.0;  // 1. no occluder's edge in front of the receiver
  if (odd_count == 0 && pairs == 0) {  // 2. one straight edge
    float dist = mix(mix(d[0], d[1], f.x), mix(d[2], d[3], f.x), f.y);
    return dist > 0.0 ? 0.0 : 1.0;
  }
  // 3. The lines combined, AND or OR, as the footprint's comparisons say.
  bvec4 shadowed = lessThan(lit, vec4(0.5));
  bvec4 and_in = greaterThan(and_c, vec4(0.0)), or_in = greaterThan(or_c, vec4(0.0));
  int and_miss = 0, or_miss = 0;
  for (int k = 0; k < 4; ++k) {
    and_miss += and_in[k] != shadowed[k] ? 1 : 0;
    or_miss += or_in[k] != shadowed[k] ? 1 : 0;
  }
  if (and_miss == 0)
    return and_p > 0.0 ? 0.0 : 1.0;
  if (or_miss == 0) return or_p > 0.0 ? 0.0 : 1.0;
  return ssm;  // 4. the reconstruction cannot decide
}
