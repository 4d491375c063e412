#version 450 core
// Shadow silhouette map (Sen et al. 2003), silhouette-map pass without a
// geometry shader: the silhouette edges of the frame's light found once by
// shaders/edsm_silhouettes.comp (the baked candidate edges' two planes,
// Bujnak 2004, Sect. 3.1), each drawn as the
// thin quad of shaders/sssm_edges.geom (0.75 texel around the segment and
// beyond its ends, in the silhouette map's framebuffer coordinates, the
// depth map's dual grid); the fragment shader is sssm_edges.frag. An edge with
// an end behind a point light's plane (w <= 0) is outside the map, as there.
// Draw and buffers: those of shaders/edsm_quad.vert (6 vertices per edge, the
// gathered records at binding 0, the list at binding 2 from u_list_first, the
// caster of each record at binding 4, each caster's light matrix at binding 6).
layout(std430, binding = 0) readonly buffer Records { uint records[]; };
layout(std430, binding = 2) readonly buffer Silhouettes { uint silhouettes[]; };
layout(std430, binding = 4) readonly buffer RecordCasters { uint record_caster[]; };
layout(std430, binding = 6) readonly buffer CasterMatrices { mat4 caster_matrix[]; };
uniform uint u_list_first;
uniform float u_map_size;        // texels per side (both maps)
flat out vec4 f_segment;         // end points in silhouette-map framebuffer coordinates
flat out vec2 f_depth;           // window depth at the two ends

void main() {
  const int kCorner[6] = int[](0, 1, 2, 2, 1, 3);
  f_segment = vec4(0.0), f_depth = vec2(0.0);
  gl_Position = vec4(2.0, 2.0, 0.0, 1.0);  // outside the clip volume: nothing drawn
  uint e = silhouettes[u_list_first + uint(gl_VertexID) / 6u], r = 9u * e;
  mat4 light_view_proj = caster_matrix[record_caster[e]];  // the caster's local frame -> light clip
  vec3 p0 = uintBitsToFloat(uvec3(records[r], records[r + 1u], records[r + 2u]));
  vec3 p1 = uintBitsToFloat(uvec3(records[r + 3u], records[r + 4u], records[r + 5u]));
  vec4 a = light_view_proj * vec4(p0, 1.0), b = light_view_proj * vec4(p1, 1.0);
  if (a.w <= 0.0 || b.w <= 0.0) return;
  vec2 A = (a.xy / a.w * 0.5 + 0.5) * u_map_size - 0.5, B = (b.xy / b.w * 0.5 + 0.5) * u_map_size - 0.5;
  vec2 ab = B - A;
  float len = length(ab);
  vec2 t = len > 0.0 ? ab / len : vec2(1.0, 0.0);
  vec2 n = vec2(-t.y, t.x);
  const float h = 0.75;
  f_segment = vec4(A, B);
  f_depth = vec2(a.z / a.w, b.z / b.w) * 0.5 + 0.5;
  int k = kCorner[gl_VertexID % 6];
  vec2 corner = (k < 2 ? A - t * h : B + t * h) + ((k & 1) == 0 ? -n * h : n * h);
  gl_Position = vec4(corner / u_map_size * 2.0 - 1.0, 0.0, 1.0);
}
