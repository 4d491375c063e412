#version 450 core
// Edge distance shadow map lookup (001, Kenzel, Sect. 4.2.2) with two edges
// per texel (Sect. 6.1's future work; shaders/edsm_edges.frag). The depth
// comparisons of the 2 x 2 texel footprint (textureGather on the comparison
// sampler) say whether the sample is fully lit, fully shadowed or near a
// silhouette (the filtered comparison strictly between 0 and 1). There each
// footprint texel's edges are lines (distance from the texel's centre and
// normal angle), evaluated exactly at the sample: for one straight edge this
// is the thesis's bilinear reconstruction (a straight edge's distance is
// linear); where the texels hold different edges (Sect. 5.2: corners, edges
// closer than two texels) the thesis proposes interpolating and testing each
// edge separately and combining the results, e.g. by a logical AND. Here the
// combination is chosen by the footprint's own comparisons: inside all the
// lines (AND: a convex corner) or inside any (OR: two occluders, a concave
// corner), whichever agrees with the four texels' depth comparisons.
// Only edges in front of the receiver take part (an edge at the receiver's
// depth is its own outline and casts nothing on it).
vec4 face_clip(vec3 world, out int layer);  // lookup_faces.frag: the face and its clip position
uniform sampler2DArrayShadow u_shadow_map;  // comparison sampler, gathered; a layer per face
uniform usampler2DArray u_distance_map;     // RGBA32UI: (line, depth) x 2 per texel

const float kPi = 3.14159265358979;
const float kInFront = 3e-6;  // window depth: an edge this far in front of the receiver can shadow it

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
  if (all(equal(g, vec4(g.x)))) return g.x;  // fully lit or fully shadowed @1
  vec4 lit = vec4(g.w, g.z, g.x, g.y);       // footprint order (0,0) (1,0) (0,1) (1,1)
  // The lines in front of the receiver, each evaluated at the four texel
  // centres (offsets (0,0) (1,0) (0,1) (1,1) in texels) and at the sample (f).
  vec4 and_c = vec4(1.0e9), or_c = vec4(-1.0e9);
  float and_p = 1.0e9, or_p = -1.0e9;
  int lines = 0, behind = 0;
  float own_p = 1.0e9;
  vec4 own_c = vec4(1.0e9);
  for (int k = 0; k < 4; ++k) {
    ivec2 o = ivec2(k & 1, k >> 1);
    uvec4 t = texelFetch(u_distance_map, ivec3(clamp(i + o, ivec2(0), size - 1), layer), 0);
    for (int e = 0; e < 2; ++e) {
      uint bits = e == 0 ? t.y : t.w;
      if (bits == 0xFFFFFFFFu) continue;
      vec2 l = unpackUnorm2x16(e == 0 ? t.x : t.z);
      float d = (l.x - 0.5) * 16.0, a = (l.y - 0.5) * 2.0 * kPi;
      vec2 n = vec2(cos(a), sin(a));
      vec2 origin = vec2(o);
      if (uintBitsToFloat(bits) + kInFront > p.z) {  // the receiver's own outline, or behind it
        ++behind;
        own_p = min(own_p, d + dot(n, f - origin));
        own_c = min(own_c, d + vec4(dot(n, vec2(0, 0) - origin), dot(n, vec2(1, 0) - origin), dot(n, vec2(0, 1) - origin),
                                    dot(n, vec2(1, 1) - origin)));
        continue;
      }
      vec4 at_c = d + vec4(dot(n, vec2(0, 0) - origin), dot(n, vec2(1, 0) - origin), dot(n, vec2(0, 1) - origin),
                           dot(n, vec2(1, 1) - origin));
      float at_p = d + dot(n, f - origin);
      and_c = min(and_c, at_c), or_c = max(or_c, at_c);
      and_p = min(and_p, at_p), or_p = max(or_p, at_p);
      ++lines;
    }
  }
  if (lines == 0 && behind == 0) return 1.0;  // @2
  if (lines == 0 && own_p < 0.0) return 1.0;  // @6
  if (lines == 0) {
    bool inside_lit = true;
    for (int k = 0; k < 4; ++k) inside_lit = inside_lit && (own_c[k] <= 0.0 || lit[k] > 0.5);
    return inside_lit ? 1.0 : 1.0;  // @7
  }
  bvec4 shadowed = lessThan(lit, vec4(0.5));
  bvec4 and_in = greaterThan(and_c, vec4(0.0)), or_in = greaterThan(or_c, vec4(0.0));
  int and_miss = 0, or_miss = 0;
  for (int k = 0; k < 4; ++k) {
    and_miss += and_in[k] != shadowed[k] ? 1 : 0;
    or_miss += or_in[k] != shadowed[k] ? 1 : 0;
  }
  if (and_miss <= or_miss && and_miss <= 1) return and_p > 0.0 ? 0.0 : 1.0;  // @3
  if (or_miss <= 1) return or_p > 0.0 ? 0.0 : 1.0;  // @4
  return nearest;  // @5
}
