#version 450 core
// edsm-soft on the six faces of a point light among its receivers
// (render/src/soft.cpp; lookup_faces.frag picks the face): as
// lookup_edsm_soft.frag, the bilinear signed edge distance turned into a light
// fraction by the disc's kernel, with the face's own frame. Each texel's
// comparison is ssm's receiver-plane test (depth_plane.frag), and the
// penumbra's half width is measured across the edge in the face's texels
// (soft_light.frag's penumbra_texels_at, the edge's normal from the
// distances' gradient). The footprint's four comparisons, bilinearly weighted
// (lookup_edsm_soft.frag says why), decide where a texel of the footprint
// holds no edge, where the receiver is not behind the edges, or where a
// texel's side of its edge disagrees with its comparison (crossing shadows).
vec4 face_clip(vec3 world, out int layer);  // lookup_faces.frag: the face and its clip position
uniform mat4 u_face_matrix[6];              // lookup_faces.frag's
uniform sampler2DArray u_distance_map;      // RG32F per face: signed distance in texels, edge depth

float penumbra_texels_at(mat4 m, vec3 world, float zo, vec2 n, vec2 size);
float disc_fraction(float x);
vec3 receiver_slope(mat4 m, vec3 world, vec3 normal, vec2 size, vec3 depth_gradient);  // depth_plane.frag
vec4 footprint_lit(int layer, vec3 p, vec3 g, out ivec2 base, out vec2 f);

float shadow_visibility(vec3 world, vec3 normal) {
  int layer;
  vec4 c = face_clip(world, layer);
  if (c.w <= 0.0) return 1.0;
  vec3 p = c.xyz / c.w * 0.5 + 0.5;
  if (any(lessThan(p.xy, vec2(-1e-3))) || any(greaterThan(p.xy, vec2(1.0 + 1e-3)))) return 1.0;
  ivec2 size = textureSize(u_distance_map, 0).xy;
  const vec3 slope = receiver_slope(u_face_matrix[layer], world, normal, vec2(size), vec3(0.0));
  ivec2 i;
  vec2 f;
  const vec4 lit = footprint_lit(layer, p, slope, i, f);  // (0,0) (1,0) (0,1) (1,1)
  float footprint = mix(mix(lit[0], lit[1], f.x), mix(lit[2], lit[3], f.x), f.y);
  float d[4];
  float edge_depth = 0.0;
  for (int k = 0; k < 4; ++k) {
    vec2 t = texelFetch(u_distance_map, ivec3(clamp(i + ivec2(k & 1, k >> 1), ivec2(0), size - 1), layer), 0).rg;
    if (abs(t.r) > 1.0e6) return footprint;
    d[k] = t.r;
    edge_depth = max(edge_depth, t.g);
  }
  if (p.z <= edge_depth + 1.0e-4) return footprint;
  for (int k = 0; k < 4; ++k)
    if ((d[k] <= 0.0) != (lit[k] > 0.5)) return footprint;
  float dist = mix(mix(d[0], d[1], f.x), mix(d[2], d[3], f.x), f.y);
  vec2 grad = vec2(mix(d[1] - d[0], d[3] - d[2], f.y), mix(d[2] - d[0], d[3] - d[1], f.x));
  vec2 across = dot(grad, grad) > 1e-12 ? normalize(grad) : vec2(1.0, 0.0);
  float h = penumbra_texels_at(u_face_matrix[layer], world, edge_depth, across, vec2(size));
  if (h < 0.5) return dist > 0.0 ? 0.0 : 1.0;  // narrower than the map resolves: the hard edge
  return disc_fraction(dist / h);
}
