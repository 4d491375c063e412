#version 450 core
// Edge distance shadow map (Kenzel 2013), distance-map pass.
// Silhouette detection (Sect. 3.2.1): the winding of a projected triangle is the
// sign of det[p1 p2 p3] of its clip-space (x, y, w) columns; an edge is a
// silhouette when the triangle faces the light (det > 0) and its neighbour
// across the edge (geom/adjacency.h: the neighbour of edge (0,2) is (0,1,2))
// does not. Boundary edges (the neighbour is the triangle itself reversed) are
// silhouettes from both sides: a back-facing triangle emits them too, inside
// flipped. Edge line (Sect. 3.2.2, eq. 3.7): c = p1 x p2 in homogeneous (x, y, w);
// here normalised in the light's NDC so that c . (x, y, 1) is the signed
// distance, positive on the occluder's side (inside the projected triangle).
// Edge quad: screen aligned around the segment, u_half_width texels on each
// side and beyond each end, so quads of joined edges overlap at corners
// (Sect. 3.2.3, Fig. 3.5); the fragment shader sorts samples there.
layout(triangles_adjacency) in;
layout(triangle_strip, max_vertices = 12) out;
in vec4 g_clip[];
uniform float u_map_size;    // texels per side
uniform float u_half_width;  // texels
flat out vec3 f_line;        // NDC line, |(a, b)| = 1, positive inside the occluder
flat out vec4 f_segment;     // NDC end points a.xy, b.xy
flat out vec2 f_depth;       // NDC depth at a and b

float winding(vec4 a, vec4 b, vec4 c) { return determinant(mat3(a.xyw, b.xyw, c.xyw)); }

// The part of segment a-b on the visible side of the light's near plane
// (z >= -w in clip space), in homogeneous space (Sect. 3.2.2: primitives are
// clipped, not dropped). False when none is.
bool clip_near(inout vec4 a, inout vec4 b) {
  float da = a.z + a.w, db = b.z + b.w;
  if (da < 0.0 && db < 0.0) return false;
  if (da < 0.0) a = mix(a, b, da / (da - db));
  else if (db < 0.0) b = mix(b, a, db / (db - da));
  return a.w > 0.0 && b.w > 0.0;
}

void emit_edge(vec4 a, vec4 b, float inside) {
  if (!clip_near(a, b)) return;
  vec2 A = a.xy / a.w, B = b.xy / b.w;
  vec2 ab = B - A;
  float len = length(ab);
  vec2 t = len > 0.0 ? ab / len : vec2(1.0, 0.0);
  vec2 n = vec2(-t.y, t.x) * inside;  // left of a -> b: inside a counter-clockwise triangle
  float h = u_half_width * 2.0 / u_map_size;
  f_line = vec3(n, -dot(n, A));
  f_segment = vec4(A, B);
  f_depth = vec2(a.z / a.w, b.z / b.w);
  vec2 corners[4] = vec2[](A - t * h - n * h, A - t * h + n * h, B + t * h - n * h, B + t * h + n * h);
  for (int k = 0; k < 4; ++k) {
    gl_Position = vec4(corners[k], 0.0, 1.0);
    EmitVertex();
  }
  EndPrimitive();
}

void main() {
  // det[p1 p2 p3] of the homogeneous (x, y, w) columns is the triangle's
  // orientation seen from the light whatever the signs of w: no triangle is
  // dropped; each silhouette edge is clipped to the near plane.
  float own = winding(g_clip[0], g_clip[2], g_clip[4]);
  if (own == 0.0) return;
  for (int e = 0; e < 3; ++e) {
    vec4 a = g_clip[2 * e], x = g_clip[2 * e + 1], b = g_clip[(2 * e + 2) % 6];
    bool boundary = x == g_clip[(2 * e + 4) % 6];
    if (own > 0.0) {
      if (winding(a, x, b) <= 0.0) emit_edge(a, b, 1.0);
    } else if (boundary) {
      emit_edge(a, b, -1.0);
    }
  }
}
