#version 450 core
// Soft shadows from edge distance (Kenzel 2013, Sect. 6 and Fig. 6.1; Bujnak 2004, Sect. 3.2):
// the edge distance shadow map's signed distance, reconstructed by one bilinear
// interpolation as in lookup_edsm.frag, becomes a light fraction through the
// kernel of a disc light (soft_light.frag): the distance in units of the
// penumbra's half width, estimated from the receiver's distance behind the
// stored edge. No further filtering. The edge map reaches as far from each
// silhouette as the widest penumbra of the frame (soft.cpp); where one of the
// four texels holds no edge, or the receiver is not behind the edges, or a
// texel's side of its edge disagrees with its depth comparison (crossing
// shadows), the four texels' comparisons decide, bilinearly weighted (a 2 x 2
// percentage-closer filter): one texel's comparison alone lit single pixels
// inside the rippled sphere's terminator bands, where no map resolves the
// tiny self-shadows (geombench heavy at 1024: light-fraction error 0.0117
// with the nearest texel, 0.0101 so, below the hard edsm's 0.0109; behind
// 0.0516 -> 0.0478; pipes, default and quake3 a little lower too).
// Each texel's comparison is ssm's receiver-plane test (depth_plane.frag): the
// receiver's plane carried to the texel's centre against the stored depth,
// read through the comparison sampler at that exact centre (nearest filter).
uniform mat4 u_light_matrix;
uniform sampler2DShadow u_shadow_map;  // comparison sampler, nearest
uniform sampler2D u_distance_map;      // RG32F: signed distance in texels, edge depth

float penumbra_texels(float zo, float zr);
float disc_fraction(float x);
vec3 receiver_slope(mat4 m, vec3 world, vec3 normal, vec2 size, vec3 depth_gradient);
float plane_depth(ivec2 texel, vec2 tc, float z, vec3 s);
float compared(float z);

float texel_lit_2d(ivec2 t, vec2 tc, float z, vec3 g, ivec2 size) {
  const ivec2 c = clamp(t, ivec2(0), size - 1);
  return texture(u_shadow_map, vec3((vec2(c) + 0.5) / vec2(size), compared(plane_depth(c, tc, z, g))));
}

float shadow_visibility(vec3 world, vec3 normal) {
  vec4 c = u_light_matrix * vec4(world, 1.0);
  if (c.w <= 0.0) return 1.0;
  vec3 p = c.xyz / c.w * 0.5 + 0.5;
  if (any(lessThan(p, vec3(0.0))) || any(greaterThan(p, vec3(1.0)))) return 1.0;
  ivec2 size = textureSize(u_distance_map, 0);
  const vec3 slope = receiver_slope(u_light_matrix, world, normal, vec2(size), vec3(0.0));
  const vec2 sample_tc = p.xy * vec2(size);
  vec2 tc = sample_tc - 0.5;
  ivec2 i = ivec2(floor(tc));
  vec2 f = tc - floor(tc);
  vec4 lit;  // footprint order (0,0) (1,0) (0,1) (1,1)
  for (int k = 0; k < 4; ++k) lit[k] = texel_lit_2d(i + ivec2(k & 1, k >> 1), sample_tc, p.z, slope, size);
  float footprint = mix(mix(lit[0], lit[1], f.x), mix(lit[2], lit[3], f.x), f.y);
  float d[4];
  float edge_depth = 0.0;
  for (int k = 0; k < 4; ++k) {
    vec2 t = texelFetch(u_distance_map, clamp(i + ivec2(k & 1, k >> 1), ivec2(0), size - 1), 0).rg;
    if (abs(t.r) > 1.0e6) return footprint;
    d[k] = t.r;
    edge_depth = max(edge_depth, t.g);
  }
  if (p.z <= edge_depth + 1.0e-4) return footprint;
  for (int k = 0; k < 4; ++k)
    if ((d[k] <= 0.0) != (lit[k] > 0.5)) return footprint;
  float dist = mix(mix(d[0], d[1], f.x), mix(d[2], d[3], f.x), f.y);
  float h = penumbra_texels(edge_depth, p.z);
  if (h < 0.5) return dist > 0.0 ? 0.0 : 1.0;  // narrower than the map resolves: the hard edge
  return disc_fraction(dist / h);
}
