#version 450 core
// edsm-soft's distance-map pass (soft.cpp): edsm_edges.geom's silhouette
// detection and edge quads, each quad as wide as the widest penumbra its edge
// can cast (soft_light.frag's estimate for a receiver at the light frame's
// far side behind the edge's nearer end), at least u_half_width texels, at
// most u_max_half_width. The rest as in edsm_edges.geom:
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
uniform float u_half_width;      // texels: the narrowest quad
uniform float u_max_half_width;  // texels: the widest quad
uniform float u_light_radius;
// The widest penumbra an edge casts, for a receiver at the far side of the
// light's frame behind it (soft.cpp): the light (input coordinates,
// homogeneous; w 0 towards the sun), that far side's distance from a point
// light or depth along the sun's rays, and the map's texels per unit across
// the light at unit distance (a point light) or per unit (the sun). Any
// light clip matrix: the scene's frustum or a face of six.
uniform vec4 u_light;
uniform float u_far;
uniform float u_texel_scale;
in vec3 g_world[];
flat out float f_half_width;     // this edge's quad, texels
flat out vec3 f_line;        // NDC line, |(a, b)| = 1, positive inside the occluder
flat out vec4 f_segment;     // NDC end points a.xy, b.xy
flat out vec2 f_depth;       // NDC depth at a and b

float winding(vec4 a, vec4 b, vec4 c) { return determinant(mat3(a.xyw, b.xyw, c.xyw)); }

float reach(vec3 a, vec3 b) {
  float texels;
  if (u_light.w != 0.0) {
    vec3 L = u_light.xyz / u_light.w;
    float d_o = max(min(distance(a, L), distance(b, L)), 1e-6);
    texels = u_light_radius * max(u_far - d_o, 0.0) / (d_o * max(u_far, 1e-6)) * u_texel_scale;
  } else {
    vec3 ray = -normalize(u_light.xyz);
    texels = tan(u_light_radius) * max(u_far - min(dot(a, ray), dot(b, ray)), 0.0) * u_texel_scale;
  }
  return clamp(texels, u_half_width, u_max_half_width);
}

void emit_edge(vec4 a, vec4 b, vec3 wa, vec3 wb, float inside) {
  f_half_width = reach(wa, wb);
  vec2 A = a.xy / a.w, B = b.xy / b.w;
  vec2 ab = B - A;
  float len = length(ab);
  vec2 t = len > 0.0 ? ab / len : vec2(1.0, 0.0);
  vec2 n = vec2(-t.y, t.x) * inside;  // left of a -> b: inside a counter-clockwise triangle
  float h = f_half_width * 2.0 / u_map_size;
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
  for (int k = 0; k < 6; ++k)
    if (g_clip[k].w <= 0.0) return;  // behind a point light's plane: outside its map
  float own = winding(g_clip[0], g_clip[2], g_clip[4]);
  if (own == 0.0) return;
  for (int e = 0; e < 3; ++e) {
    vec4 a = g_clip[2 * e], x = g_clip[2 * e + 1], b = g_clip[(2 * e + 2) % 6];
    bool boundary = x == g_clip[(2 * e + 4) % 6];
    if (own > 0.0) {
      if (winding(a, x, b) <= 0.0) emit_edge(a, b, g_world[2 * e], g_world[(2 * e + 2) % 6], 1.0);
    } else if (boundary) {
      emit_edge(a, b, g_world[2 * e], g_world[(2 * e + 2) % 6], -1.0);
    }
  }
}
