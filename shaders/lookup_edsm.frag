#version 450 core
// Edge distance shadow map lookup (001, Kenzel, Sect. 4.2.2). The depth
// comparisons of the 2 x 2 texel footprint (textureGather on the comparison
// sampler) say whether the sample is fully lit, fully shadowed or near a
// silhouette (the filtered comparison strictly between 0 and 1); there the
// signed edge distance is reconstructed by bilinear interpolation of the
// distance map (Sect. 3.1.1: exact for one straight edge) and its sign decides:
// positive = the occluder's side = shadow. Two fallbacks to the nearest texel's
// comparison (a simple shadow map's answer) are kept, measured (geombench,
// 640x480, jenga at 512, error_visible): where one of the four texels holds no
// edge (nothing to interpolate), and where a texel's side of its edge disagrees
// with its own comparison (crossing shadows, or a receiver's outline and a
// caster's edge in one texel: the thesis's Sect. 5.2 failure case): without it
// 5.60%, with it 1.24% (ssm 1.68%). The thesis has no receiver-in-front-of-edge
// guard and neither has this lookup any more (with it: 1.26%, default 0.015% vs 0.006%).
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
  for (int k = 0; k < 4; ++k) {
    vec2 t = texelFetch(u_distance_map, ivec3(clamp(i + ivec2(k & 1, k >> 1), ivec2(0), size - 1), layer), 0).rg;
    if (abs(t.r) > 1.0e6) return nearest;
    d[k] = t.r;
  }
  // Each texel's side of its edge must agree with its own depth comparison
  // (crossing shadows: a texel on an edge's lit side may be shadowed by another
  // occluder); otherwise the nearest comparison stands.
  vec4 lit = vec4(g.w, g.z, g.x, g.y);  // footprint order (0,0) (1,0) (0,1) (1,1)
  for (int k = 0; k < 4; ++k)
    if ((d[k] <= 0.0) != (lit[k] > 0.5)) return nearest;
  float dist = mix(mix(d[0], d[1], f.x), mix(d[2], d[3], f.x), f.y);
  return dist > 0.0 ? 0.0 : 1.0;
}
