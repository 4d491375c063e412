#version 450 core
// Extended shadow map lookup (000, Bujnak, Sect. 3.2 and 4.2). The depth map is
// compared per texel, point filtered, over the 2 x 2 footprint (textureGather
// on the comparison sampler): fully lit or fully shadowed stands; otherwise the
// nearest texel's comparison stands unless, where all four texels
// hold silhouette information consistent with their comparisons and the
// receiver lies behind the stored edge depth, the encoded edge distance is interpolated bilinearly and sent through
// the transfer function with its guard zone (Fig. 6): values under 0.25 (on the
// occluder's side, down to a quad's inner end) are shadow, then a linear ramp
// through 0.5 at the edge (0.33) to fully lit at 0.41 (a third of a texel out).
vec4 face_clip(vec3 world, out int layer);  // lookup_faces.frag: the face and its clip position
uniform sampler2DArrayShadow u_shadow_map;  // comparison sampler, gathered; a layer per face
uniform sampler2DArray u_edge_map;          // r encoded distance, b edge depth, a mask

float transfer(float e) {
  if (e < 0.25) return 0.0;  // guard zone
  return clamp((e - 0.25) / 0.16, 0.0, 1.0);
}

float shadow_visibility(vec3 world, vec3 normal) {
  int layer;
  vec4 c = face_clip(world, layer);
  if (c.w <= 0.0) return 1.0;
  vec3 p = c.xyz / c.w * 0.5 + 0.5;
  if (any(lessThan(p, vec3(0.0))) || any(greaterThan(p, vec3(1.0)))) return 1.0;
  ivec2 size = textureSize(u_edge_map, 0).xy;
  vec2 tc = p.xy * vec2(size) - 0.5;
  ivec2 i = ivec2(floor(tc));
  vec2 f = tc - floor(tc);
  // The comparisons of the 2 x 2 footprint (gather order: (0,1) (1,1) (1,0) (0,0)).
  vec4 g = textureGather(u_shadow_map, vec3(p.xy, float(layer)), p.z);
  float nearest = f.y < 0.5 ? (f.x < 0.5 ? g.w : g.z) : (f.x < 0.5 ? g.x : g.y);
  if (all(equal(g, vec4(g.x)))) return g.x;  // fully lit or fully shadowed
  float e[4];
  float edge_depth = 0.0;
  for (int k = 0; k < 4; ++k) {
    vec4 t = texelFetch(u_edge_map, ivec3(clamp(i + ivec2(k & 1, k >> 1), ivec2(0), size - 1), layer), 0);
    if (t.a == 0.0) return nearest;
    e[k] = t.r;
    edge_depth = max(edge_depth, t.b);
  }
  if (p.z < edge_depth) return nearest;  // the receiver is in front of the edges
  // The edges must explain the footprint: each texel's side of the edge (its
  // value against 0.33) agrees with its own depth comparison. Where another
  // occluder shadows a texel on an edge's lit side (crossing shadows), the
  // edge does not say where the boundary is: the nearest comparison stands.
  vec4 lit = vec4(g.w, g.z, g.x, g.y);  // footprint order (0,0) (1,0) (0,1) (1,1)
  for (int k = 0; k < 4; ++k)
    if ((e[k] >= 0.33) != (lit[k] > 0.5)) return nearest;
  return transfer(mix(mix(e[0], e[1], f.x), mix(e[2], e[3], f.x), f.y));
}
