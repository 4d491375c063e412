#version 450 core
// Shadow silhouette map (Sen et al. 2003), silhouette-map pass. Silhouette
// edges from the light are found as in the edge distance map (Kenzel 2013, Sect.
// 3.2.1: a triangle facing the light whose neighbour across the edge does not;
// boundary edges from both sides) and drawn as thin quads covering every
// silhouette-map cell the segment touches (conservative: 0.75 texel around the
// segment and beyond its ends, more than half a cell's diagonal).
// The silhouette map is the depth map's dual grid, offset by half a texel: the
// corners of cell (i, j) are the depth samples (i, j) ... (i + 1, j + 1), so a
// cell's centre lies at depth-map texel coordinate (i + 1, j + 1), and the
// framebuffer coordinate of a depth-map texel coordinate t is t - 0.5.
layout(triangles_adjacency) in;
layout(triangle_strip, max_vertices = 12) out;
in vec4 g_clip[];
uniform float u_map_size;  // texels per side (both maps)
flat out vec4 f_segment;   // end points in silhouette-map framebuffer coordinates
flat out vec2 f_depth;     // window depth at the two ends

float winding(vec4 a, vec4 b, vec4 c) { return determinant(mat3(a.xyw, b.xyw, c.xyw)); }

void emit_edge(vec4 a, vec4 b) {
  // NDC -> depth-map texel coordinates -> silhouette-map framebuffer coordinates.
  vec2 A = (a.xy / a.w * 0.5 + 0.5) * u_map_size - 0.5, B = (b.xy / b.w * 0.5 + 0.5) * u_map_size - 0.5;
  vec2 ab = B - A;
  float len = length(ab);
  vec2 t = len > 0.0 ? ab / len : vec2(1.0, 0.0);
  vec2 n = vec2(-t.y, t.x);
  const float h = 0.75;
  f_segment = vec4(A, B);
  f_depth = vec2(a.z / a.w, b.z / b.w) * 0.5 + 0.5;
  vec2 corners[4] = vec2[](A - t * h - n * h, A - t * h + n * h, B + t * h - n * h, B + t * h + n * h);
  for (int k = 0; k < 4; ++k) {
    gl_Position = vec4(corners[k] / u_map_size * 2.0 - 1.0, 0.0, 1.0);
    EmitVertex();
  }
  EndPrimitive();
}

void main() {
  for (int k = 0; k < 6; ++k)
    if (g_clip[k].w <= 0.0) return;  // behind a point light's plane: outside its map
  float own = winding(g_clip[0], g_clip[2], g_clip[4]);
  if (own == 0.0) return;
  for (int e = 0; e < 3; ++e) {
    vec4 a = g_clip[2 * e], x = g_clip[2 * e + 1], b = g_clip[(2 * e + 2) % 6];
    bool boundary = x == g_clip[(2 * e + 4) % 6];
    if (own > 0.0 ? winding(a, x, b) <= 0.0 : boundary) emit_edge(a, b);
  }
}
