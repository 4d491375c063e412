#version 450 core
// Extended shadow map lookup (000, Bujnak, Sect. 3.2 and 4.2). The depth map is
// compared per texel (bilinear comparison filter over the 2 x 2 footprint):
// fully lit or fully shadowed stands. Near a boundary, where all four texels
// hold silhouette information and the receiver lies behind the stored edge
// depth, the encoded edge distance is interpolated bilinearly and sent through
// the transfer function with its guard zone (Fig. 6): values under 0.25 (on the
// occluder's side, down to a quad's inner end) are shadow, then a linear ramp
// through 0.5 at the edge (0.33) to fully lit at 0.41 (a third of a texel out).
uniform mat4 u_light_matrix;
uniform sampler2DShadow u_shadow_map;  // GL_LINEAR comparison
uniform sampler2D u_edge_map;          // r encoded distance, b edge depth, a mask

float transfer(float e) {
  if (e < 0.25) return 0.0;  // guard zone
  return clamp((e - 0.25) / 0.16, 0.0, 1.0);
}

float shadow_visibility(vec3 world, vec3 normal) {
  vec4 c = u_light_matrix * vec4(world, 1.0);
  if (c.w <= 0.0) return 1.0;
  vec3 p = c.xyz / c.w * 0.5 + 0.5;
  if (any(lessThan(p, vec3(0.0))) || any(greaterThan(p, vec3(1.0)))) return 1.0;
  float v = textureLod(u_shadow_map, p, 0.0);
  if (v <= 0.0 || v >= 1.0) return v;
  ivec2 size = textureSize(u_edge_map, 0);
  vec2 tc = p.xy * vec2(size) - 0.5;
  ivec2 i = ivec2(floor(tc));
  vec2 f = tc - floor(tc);
  float e[4];
  float edge_depth = 0.0;
  for (int k = 0; k < 4; ++k) {
    vec4 t = texelFetch(u_edge_map, clamp(i + ivec2(k & 1, k >> 1), ivec2(0), size - 1), 0);
    if (t.a == 0.0) return v >= 0.5 ? 1.0 : 0.0;
    e[k] = t.r;
    edge_depth = max(edge_depth, t.b);
  }
  if (p.z < edge_depth) return v >= 0.5 ? 1.0 : 0.0;  // the receiver is in front of the edges
  return transfer(mix(mix(e[0], e[1], f.x), mix(e[2], e[3], f.x), f.y));
}
