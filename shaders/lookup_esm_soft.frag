#version 450 core
// esm-soft: soft shadows from the extended shadow map's edge distance, this
// project's own extension of 000 (render/src/esm_soft.cpp). From 000 Sect. 3.2:
// the point-filtered depth and edge depth as flags and the bilinearly
// interpolated edge distance; the paper's "one dp3" attenuation is the light's
// distance falloff, not a penumbra, and is not used. Here the distance
// in units of the penumbra's half width, estimated from the receiver's depth
// behind the nearest texel's edge depth (the occluder), gives the light
// fraction. On esm's light frames (lookup_faces.frag: a fitted frustum or six
// cube faces). Each texel's comparison is ssm's receiver-plane test
// (depth_plane.frag). The footprint's four comparisons, bilinearly weighted,
// decide where the nearest texel holds no silhouette or the receiver is not
// behind its edge (the paper's flags), where a texel of the footprint holds no
// silhouette, or where a texel's side of its edge disagrees with its own depth
// comparison (crossing shadows), as in lookup_edsm_soft.frag (which says why
// not one texel's comparison).
vec4 face_clip(vec3 world, out int layer);  // lookup_faces.frag: the face and its clip position
uniform mat4 u_face_matrix[6];              // lookup_faces.frag's
uniform sampler2DArray u_edge_map;          // r kOffset + signed distance (texels, lit side +), b edge depth, a mask

float penumbra_texels_at(mat4 m, vec3 world, float zo, vec2 n, vec2 size);
vec3 receiver_slope(mat4 m, vec3 world, vec3 normal, vec2 size, vec3 depth_gradient);  // depth_plane.frag
vec4 footprint_lit(int layer, vec3 p, vec3 g, out ivec2 base, out vec2 f);
float disc_fraction(float x);

const float kOffset = 1024.0;  // esm_soft_edges.frag

float shadow_visibility(vec3 world, vec3 normal) {
  int layer;
  vec4 c = face_clip(world, layer);
  if (c.w <= 0.0) return 1.0;
  vec3 p = c.xyz / c.w * 0.5 + 0.5;
  if (any(lessThan(p, vec3(0.0))) || any(greaterThan(p, vec3(1.0)))) return 1.0;
  ivec2 size = textureSize(u_edge_map, 0).xy;
  // The footprint's comparisons are ssm's receiver-plane test (depth_plane.frag).
  const vec3 slope = receiver_slope(u_face_matrix[layer], world, normal, vec2(size), vec3(0.0));
  ivec2 i;
  vec2 f;
  const vec4 lit = footprint_lit(layer, p, slope, i, f);  // (0,0) (1,0) (0,1) (1,1)
  float footprint = mix(mix(lit[0], lit[1], f.x), mix(lit[2], lit[3], f.x), f.y);
  ivec2 n = clamp(i + ivec2(f.x < 0.5 ? 0 : 1, f.y < 0.5 ? 0 : 1), ivec2(0), size - 1);
  vec4 tn = texelFetch(u_edge_map, ivec3(n, layer), 0);
  if (tn.a == 0.0 || p.z <= tn.b + 1e-4) return footprint;  // no silhouette here, or the receiver is in front of it
  float e[4];
  for (int k = 0; k < 4; ++k) {
    vec4 t = texelFetch(u_edge_map, ivec3(clamp(i + ivec2(k & 1, k >> 1), ivec2(0), size - 1), layer), 0);
    if (t.a == 0.0) return footprint;
    e[k] = t.r - kOffset;
    if ((e[k] > 0.0) != (lit[k] > 0.5)) return footprint;
  }
  float dist = mix(mix(e[0], e[1], f.x), mix(e[2], e[3], f.x), f.y);  // the one dot product
  vec2 grad = vec2(mix(e[1] - e[0], e[3] - e[2], f.y), mix(e[2] - e[0], e[3] - e[1], f.x));
  vec2 normal_t = dot(grad, grad) > 1e-12 ? normalize(grad) : vec2(1.0, 0.0);
  float h = penumbra_texels_at(u_face_matrix[layer], world, tn.b, normal_t, vec2(size));
  if (h < 0.5) return dist > 0.0 ? 1.0 : 0.0;  // narrower than the map resolves: the hard edge
  return disc_fraction(-dist / h);
}
