#version 450 core
// Edge distance shadow map lookup (001, Kenzel, Sect. 4.2.2). The depth
// comparisons of the 2 x 2 texel footprint (textureGather on the comparison
// sampler) say whether the sample is fully lit, fully shadowed or near a
// silhouette (the filtered comparison strictly between 0 and 1); there the
// signed edge distance is reconstructed by bilinear interpolation of the
// distance map (Sect. 3.1.1: exact for one straight edge) and its sign decides:
// positive = the occluder's side = shadow. Two fallbacks to the nearest
// texel's comparison (a simple shadow map's answer) are kept for the thesis's
// Sect. 5.2 failure cases, each measured (geombench, 640x480):
//  - two of the four texels hold no edge, or an edge whose side disagrees with
//    their own comparison (crossing shadows, a receiver's outline and a
//    caster's edge in one texel: Sect. 5.2): too little to reconstruct. One
//    such texel is replaced by the plane through the other three (below): on
//    jenga error_cast 0.648 / 0.272 / 0.086% at 512 / 1024 / 2048 with the
//    nearest texel's comparison for it too, 0.355 / 0.138 / 0.034% with the
//    plane (ssm 1.680 / 0.630 / 0.203%); without any such check jenga@512 was
//    5.60% (before the depth-resolved priority);
//  - the receiver is not behind the stored edges (1e-4 window depth): its own
//    outline, where the comparison is partial from its slope alone. Without it
//    jenga@512 0.62% (with it 0.65%), default@512 0.006% (0.014%), but the
//    wide-depth alley@1024 8.2% against 2.7% with it (ssm 3.4%): kept.
vec4 face_clip(vec3 world, out int layer);  // lookup_faces.frag: the face and its clip position
uniform sampler2DArrayShadow u_shadow_map;  // comparison sampler, gathered; a layer per face
uniform sampler2DArray u_distance_map;      // RG32F: signed distance in texels, edge depth

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
  if (all(equal(g, vec4(g.x)))) return g.x;  // fully lit or fully shadowed
  float d[4];
  float edge_depth = 0.0;
  vec4 lit = vec4(g.w, g.z, g.x, g.y);  // footprint order (0,0) (1,0) (0,1) (1,1)
  int odd = -1, odd_count = 0;
  for (int k = 0; k < 4; ++k) {
    vec2 t = texelFetch(u_distance_map, ivec3(clamp(i + ivec2(k & 1, k >> 1), ivec2(0), size - 1), layer), 0).rg;
    bool bad = abs(t.r) > 1.0e6 || (t.r <= 0.0) != (lit[k] > 0.5);
    d[k] = t.r;
    if (bad) {
      odd = k, ++odd_count;
    } else {
      edge_depth = max(edge_depth, t.g);
    }
  }
  if (odd_count > 1) return nearest;
  if (p.z <= edge_depth + 1.0e-4) return nearest;  // the receiver's own outline
  // Each texel's side of its edge must agree with its own depth comparison
  // (crossing shadows: a texel on an edge's lit side may be shadowed by another
  // occluder; a receiver's outline and a caster's edge in one texel). One texel
  // that does not, or holds no edge, takes the value of the plane through the
  // other three: a straight edge's signed distance is linear, so three texels
  // give it whole (a 2 x 2 footprint has one more sample than a line needs).
  if (odd >= 0) d[odd] = d[odd ^ 1] + d[odd ^ 2] - d[odd ^ 3];
  float dist = mix(mix(d[0], d[1], f.x), mix(d[2], d[3], f.x), f.y);
  return dist > 0.0 ? 0.0 : 1.0;
}
