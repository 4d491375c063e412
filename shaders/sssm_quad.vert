#version 450 core
// Shadow silhouette map (Sen et al. 2003), silhouette-map pass without a
// geometry shader: the silhouette edges of the frame's light found once by
// shaders/edsm_silhouettes.comp (the baked candidate edges' two planes,
// Bujnak 2004, Sect. 3.1), or tested here (u_compact 0), each drawn as the
// thin quad of shaders/sssm_edges.geom (0.75 texel around the segment and
// beyond its ends, in the silhouette map's framebuffer coordinates, the
// depth map's dual grid); the fragment shader is sssm_edges.frag. An edge with
// an end behind a point light's plane (w <= 0) is outside the map, as there.
// Draw and buffers: those of shaders/edsm_quad.vert (6 vertices per edge, the
// records at binding 0, the list at binding 2 from u_list_first).
layout(std430, binding = 0) readonly buffer Records { uint records[]; };
layout(std430, binding = 2) readonly buffer Silhouettes { uint silhouettes[]; };
uniform int u_compact;
uniform uint u_list_first;
uniform mat4 u_light_view_proj;  // local frame (geom/face_planes.h) -> light clip
uniform vec4 u_light;            // the light in the local frame, homogeneous
uniform samplerBuffer u_planes;  // the records' planes
uniform float u_map_size;        // texels per side (both maps)
flat out vec4 f_segment;         // end points in silhouette-map framebuffer coordinates
flat out vec2 f_depth;           // window depth at the two ends

const uint kFlip = 0x80000000u;

bool in_front(uint index) {  // as shaders/esm_quad.vert
  vec4 p = texelFetch(u_planes, int(index & 0x7fffffffu));
  precise float s = p.x * u_light.x;
  s = s + p.y * u_light.y;
  s = s + p.z * u_light.z;
  s = s + p.w * u_light.w;
  return (s > 0.0) != ((index & kFlip) != 0u);
}

void main() {
  const int kCorner[6] = int[](0, 1, 2, 2, 1, 3);
  f_segment = vec4(0.0), f_depth = vec2(0.0);
  gl_Position = vec4(2.0, 2.0, 0.0, 1.0);  // outside the clip volume: nothing drawn
  uint r = 9u * (u_compact == 1 ? silhouettes[u_list_first + uint(gl_VertexID) / 6u] : uint(gl_VertexID) / 6u);
  if (u_compact == 0 && in_front(records[r + 6u]) == in_front(records[r + 7u])) return;
  vec3 p0 = uintBitsToFloat(uvec3(records[r], records[r + 1u], records[r + 2u]));
  vec3 p1 = uintBitsToFloat(uvec3(records[r + 3u], records[r + 4u], records[r + 5u]));
  vec4 a = u_light_view_proj * vec4(p0, 1.0), b = u_light_view_proj * vec4(p1, 1.0);
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
