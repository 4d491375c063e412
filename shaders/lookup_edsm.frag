#version 450 core
// Edge distance shadow map lookup (001, Kenzel, Sect. 4.2.2). Comparison
// filtering of the depth map (2 x 2 bilinear, hardware) says whether the sample
// is fully lit (1), fully shadowed (0) or near a silhouette (in between); there
// the signed edge distance is reconstructed by bilinear interpolation of the
// distance map (Sect. 3.1.1: exact for one straight edge) and its sign decides:
// positive = the occluder's side = shadow. Where one of the four texels holds no
// edge (cleared to a huge value) the comparison result stands, rounded.
uniform mat4 u_light_matrix;
uniform sampler2DShadow u_shadow_map;  // GL_LINEAR: 2 x 2 comparison filter
uniform sampler2D u_distance_map;      // R32F signed distance in texels

float shadow_visibility(vec3 world, vec3 normal) {
  vec4 c = u_light_matrix * vec4(world, 1.0);
  if (c.w <= 0.0) return 1.0;
  vec3 p = c.xyz / c.w * 0.5 + 0.5;
  if (any(lessThan(p, vec3(0.0))) || any(greaterThan(p, vec3(1.0)))) return 1.0;
  float v = textureLod(u_shadow_map, p, 0.0);
  if (v <= 0.0 || v >= 1.0) return v;
  ivec2 size = textureSize(u_distance_map, 0);
  vec2 tc = p.xy * vec2(size) - 0.5;
  ivec2 i = ivec2(floor(tc));
  vec2 f = tc - floor(tc);
  float d[4];
  for (int k = 0; k < 4; ++k) {
    d[k] = texelFetch(u_distance_map, clamp(i + ivec2(k & 1, k >> 1), ivec2(0), size - 1), 0).r;
    if (abs(d[k]) > 1.0e6) return v >= 0.5 ? 1.0 : 0.0;
  }
  float dist = mix(mix(d[0], d[1], f.x), mix(d[2], d[3], f.x), f.y);
  return dist > 0.0 ? 0.0 : 1.0;
}
