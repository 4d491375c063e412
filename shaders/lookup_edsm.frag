#version 450 core
// Edge distance shadow map lookup (001, Kenzel, Sect. 4.2.2) with two edges
// per texel (Sect. 6.1's future work; shaders/edsm_edges.frag).
vec4 face_clip(vec3 world, out int layer);  // lookup_faces.frag: the face and its clip position
uniform sampler2DArrayShadow u_shadow_map;  // comparison sampler, gathered; a layer per face
uniform usampler2DArray u_distance_map;     // RGBA32UI: (line, depth) x 2 per texel

const float kPi = 3.14159265358979;
const float kInFront = 1.0e-5;  // window depth: an edge this far in front of the receiver can shadow it
#define MODE 1
#define SLIVER 0
#define FALLBACK 2
#define OR_MISS 1
#define AND_MISS 1

float shadow_visibility(vec3 world, vec3 normal) {
  int layer;
  vec4 c = face_clip(world, layer);
  if (c.w <= 0.0) return 1.0;
  vec3 p = c.xyz / c.w * 0.5 + 0.5;
  if (any(lessThan(p, vec3(0.0))) || any(greaterThan(p, vec3(1.0)))) return 1.0;
  ivec2 size = textureSize(u_distance_map, 0).xy;
  vec2 tc = p.xy * vec2(size) - 0.5;
  ivec2 i = ivec2(floor(tc));
  vec2 f = tc - floor(tc);
  // The comparisons of the 2 x 2 footprint (gather order: (0,1) (1,1) (1,0) (0,0)).
  vec4 g = textureGather(u_shadow_map, vec3(p.xy, float(layer)), p.z);
  float nearest = f.y < 0.5 ? (f.x < 0.5 ? g.w : g.z) : (f.x < 0.5 ? g.x : g.y);
  bool same = all(equal(g, vec4(g.x)));
#if SLIVER == 0
  if (same) return g.x;  // fully lit or fully shadowed @1
#endif
  vec4 lit = vec4(g.w, g.z, g.x, g.y);       // footprint order (0,0) (1,0) (0,1) (1,1)
  // Per texel: its lines in front of the receiver, evaluated at the four texel
  // centres (offsets (0,0) (1,0) (0,1) (1,1) in texels) and at the sample (f).
  vec4 and_c = vec4(1.0e9), or_c = vec4(-1.0e9);
  float and_p = 1.0e9, or_p = -1.0e9;
  float d[4];          // the texel's first line in front: its distance at the texel's centre
  vec4 dp = vec4(1.0e9);  // and at the sample
  int odd = -1, odd_count = 0, lines = 0;
  for (int k = 0; k < 4; ++k) {
    ivec2 o = ivec2(k & 1, k >> 1);
    uvec4 t = texelFetch(u_distance_map, ivec3(clamp(i + o, ivec2(0), size - 1), layer), 0);
    d[k] = 1.0e9;
    for (int e = 0; e < 2; ++e) {
      uint bits = e == 0 ? t.y : t.w;
      if (bits == 0xFFFFFFFFu || uintBitsToFloat(bits) + kInFront > p.z) continue;  // none, or the receiver's own outline
      vec2 l = unpackUnorm2x16(e == 0 ? t.x : t.z);
      float dist = (l.x - 0.5) * 16.0, a = (l.y - 0.5) * 2.0 * kPi;
      vec2 n = vec2(cos(a), sin(a));
      vec2 origin = vec2(o);
      vec4 at_c = dist + vec4(dot(n, -origin), dot(n, vec2(1, 0) - origin), dot(n, vec2(0, 1) - origin),
                              dot(n, vec2(1, 1) - origin));
      float at_p = dist + dot(n, f - origin);
      and_c = min(and_c, at_c), or_c = max(or_c, at_c);
      and_p = min(and_p, at_p), or_p = max(or_p, at_p);
      if (d[k] == 1.0e9) d[k] = dist, dp[k] = at_p;
      ++lines;
    }
    if (d[k] == 1.0e9 || (d[k] <= 0.0) != (lit[k] > 0.5)) odd = k, ++odd_count;
  }
#if SLIVER == 1
  if (same) {
    if (lines > 0 && g.x > 0.5 && all(lessThanEqual(or_c, vec4(0.0))) && and_p > 0.0) return 0.0;  // @7
    if (lines > 0 && g.x < 0.5 && all(greaterThan(or_c, vec4(0.0))) && or_p <= 0.0) return 1.0;  // @7
    return g.x;  // @1
  }
#endif
  // No edge in front of the receiver: the comparisons differ from its own
  // slope or outline alone.
  if (lines == 0) return 1.0;  // @2
#if MODE == 1
  int kn0 = (f.x < 0.5 ? 0 : 1) + (f.y < 0.5 ? 0 : 2);
  if (odd_count == 0 || (odd_count == 1 && odd != kn0)) {
    if (odd >= 0) d[odd] = d[odd ^ 1] + d[odd ^ 2] - d[odd ^ 3];
    float dist = mix(mix(d[0], d[1], f.x), mix(d[2], d[3], f.x), f.y);
    return dist > 0.0 ? 0.0 : 1.0;  // @3
  }
#endif
  bvec4 shadowed = lessThan(lit, vec4(0.5));
  bvec4 and_in = greaterThan(and_c, vec4(0.0)), or_in = greaterThan(or_c, vec4(0.0));
  int and_miss = 0, or_miss = 0;
  int kn = (f.x < 0.5 ? 0 : 1) + (f.y < 0.5 ? 0 : 2);  // the nearest texel
  for (int k = 0; k < 4; ++k) {
    and_miss += and_in[k] != shadowed[k] ? 1 : 0;
    or_miss += or_in[k] != shadowed[k] ? 1 : 0;
  }
  if (and_miss <= or_miss && (and_miss == 0 || (and_miss <= AND_MISS && and_in[kn] == shadowed[kn]))) return and_p > 0.0 ? 0.0 : 1.0;  // @4
  if (or_miss == 0 || (or_miss <= OR_MISS && or_in[kn] == shadowed[kn])) return or_p > 0.0 ? 0.0 : 1.0;  // @5
#if FALLBACK == 0
  return nearest;  // @6
#elif FALLBACK == 1
  return 1.0;  // @6
#else
  vec4 v = mix(lit, vec4(lessThanEqual(dp, vec4(0.0))), vec4(lessThan(dp, vec4(1.0e8))));
  float w = mix(mix(v.x, v.y, f.x), mix(v.z, v.w, f.x), f.y);
  return w >= 0.5 ? 1.0 : 0.0;  // @6
#endif
}
