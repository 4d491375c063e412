#version 450 core
// Edge distance shadow map (Kenzel 2013, Sect. 3.2 and 4.2.1), distance-map
// pass without a geometry shader: the silhouette edges of the light, found
// by a compute pass over the baked candidate edges (geom/esm_quads.h records:
// both face planes of each edge, coplanar and concave edges already dropped;
// shaders/edsm_silhouettes.comp), each drawn as a quad. The thesis's
// geometry-shader path over every triangle with adjacency
// (shaders/edsm_edges.vert + .geom, technique edsm-gs) writes the same edges;
// the fragment shader, shaders/edsm_edges.frag, is the same for both.
//
// Draw: the silhouette edges found by shaders/edsm_silhouettes.comp,
// glDrawArraysIndirect with no instancing (a software rasterizer such as
// llvmpipe runs its vertex pipeline once per instance): vertex gl_VertexID / 6
// of its list (binding 2, from u_list_first) names a record of every caster's
// records gathered (binding 0, as they lie: geom/esm_quads.h: 9 uints, p0,
// p1, plane_a, plane_b, q as two snorm16), its caster (binding 4) the light
// matrix (binding 6: each caster's local frame, geom/face_planes.h, to the
// light's clip space); the two triangles (0 1 2) (2 1 3) of the strip of
// corners 0..3: the screen-aligned quad of edsm_edges.geom's emit_edge,
// u_half_width texels on each side of the segment and beyond each end.
//
// Silhouette (Bujnak 2004, Sect. 3.1): the light in front of one plane and
// behind the other, tested by the compute pass. The occluder's side: the
// quad's back side, along -q (the
// extrusion vector, normalize(nA + nB), points away from the faces): with the
// clipped end points a, b (clip x, y, w, w > 0) the NDC line through them is
// cross(a, b) / (a.w b.w), and a point moved from the edge along -q lands
// where cross(a, b) . (M q).xyw < 0 puts it on the left of a -> b.
// Edge line (eq. 3.7) and segment as the geometry shader writes them: the
// part on the light's side of the near plane (Sect. 3.2.2: clipped, not
// dropped), c . (x, y, 1) the signed NDC distance, positive on the occluder's side.
//
// Uniforms:
//   uint u_list_first               the list's first slot of this draw
//   float u_map_size, u_half_width   texels per side, quad half width in texels
layout(std430, binding = 0) readonly buffer Records { uint records[]; };
layout(std430, binding = 2) readonly buffer Silhouettes { uint silhouettes[]; };
layout(std430, binding = 4) readonly buffer RecordCasters { uint record_caster[]; };
layout(std430, binding = 6) readonly buffer CasterMatrices { mat4 caster_matrix[]; };
uniform uint u_list_first;
uniform float u_map_size;
uniform float u_half_width;
flat out vec3 f_line;
flat out vec4 f_segment;
flat out vec2 f_depth;

vec3 octahedral_decode(vec2 e) {
  e = max(e, vec2(-1.0));
  vec3 v = vec3(e.x, e.y, 1.0 - abs(e.x) - abs(e.y));
  if (v.z < 0.0) {
    vec2 o = v.xy;
    v.x = (1.0 - abs(o.y)) * (o.x >= 0.0 ? 1.0 : -1.0);
    v.y = (1.0 - abs(o.x)) * (o.y >= 0.0 ? 1.0 : -1.0);
  }
  return v / sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
}

// edsm_edges.geom's clip_near: the part of a-b with z >= -w.
bool clip_near(inout vec4 a, inout vec4 b) {
  float da = a.z + a.w, db = b.z + b.w;
  if (da < 0.0 && db < 0.0) return false;
  if (da < 0.0) a = mix(a, b, da / (da - db));
  else if (db < 0.0) b = mix(b, a, db / (db - da));
  return a.w > 0.0 && b.w > 0.0;
}

void main() {
  const vec4 nothing = vec4(2.0, 2.0, 0.0, 1.0);  // outside the clip volume: the quad draws nothing
  f_line = vec3(0.0), f_segment = vec4(0.0), f_depth = vec2(0.0);
  gl_Position = nothing;
  const int kCorner[6] = int[](0, 1, 2, 2, 1, 3);
  uint e = silhouettes[u_list_first + uint(gl_VertexID) / 6u], r = 9u * e;
  mat4 light_view_proj = caster_matrix[record_caster[e]];  // the caster's local frame -> light clip
  vec3 p0 = uintBitsToFloat(uvec3(records[r], records[r + 1u], records[r + 2u]));
  vec3 p1 = uintBitsToFloat(uvec3(records[r + 3u], records[r + 4u], records[r + 5u]));
  vec4 a = light_view_proj * vec4(p0, 1.0), b = light_view_proj * vec4(p1, 1.0);
  if (!clip_near(a, b)) return;
  vec4 mq = light_view_proj * vec4(octahedral_decode(unpackSnorm2x16(records[r + 8u])), 0.0);
  float inside = dot(cross(a.xyw, b.xyw), mq.xyw) < 0.0 ? 1.0 : -1.0;
  vec2 A = a.xy / a.w, B = b.xy / b.w;
  vec2 ab = B - A;
  float len = length(ab);
  vec2 t = len > 0.0 ? ab / len : vec2(1.0, 0.0);
  vec2 n = vec2(-t.y, t.x) * inside;  // towards the occluder
  float h = u_half_width * 2.0 / u_map_size;
  f_line = vec3(n, -dot(n, A));
  f_segment = vec4(A, B);
  f_depth = vec2(a.z / a.w, b.z / b.w);
  int k = kCorner[gl_VertexID % 6];
  vec2 along = (k < 2 ? A - t * h : B + t * h), across = (k & 1) == 0 ? -n * h : n * h;
  gl_Position = vec4(along + across, 0.0, 1.0);
}
