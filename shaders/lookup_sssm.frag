#version 450 core
// Shadow silhouette map lookup (Sen, Cammarano and Hanrahan 2003). The sample
// falls in one cell of the silhouette map, whose four corners are the depth
// samples of the bilinear footprint (the maps are offset by half a texel): the
// depth comparisons of the four corners (textureGather on the comparison
// sampler) agree: that answer stands. Otherwise the cell's silhouette point C
// and the points of its four neighbours (right, top, left, bottom; the 3 x 3
// neighbourhood) are read; the segments from C to them split the cell into four
// skewed quadrants, one per corner (the dual-contouring reconstruction of the
// paper), and the sample takes the comparison of the corner whose quadrant it
// lies in. A cell without a silhouette point holds its centre: its quadrants
// are the four quarters and the answer is the nearest depth sample's.
// One deviation, measured in docs/geombench.md (against the paper's lookup,
// this file without the test, at commit 6874cf6): where the receiver is not
// behind the silhouette edges stored around it (its own silhouette from the
// light, where the comparisons differ from the surface's slope alone), the
// nearest depth sample's comparison stands, as in lookup_edsm.frag.
// The light frame: the fitted frustum or six cube faces (lookup_faces.frag), as edsm's.
uniform sampler2DArrayShadow u_shadow_map;  // comparison sampler, gathered; a layer per face
uniform usampler2DArray u_edge_map;         // RG32UI: the silhouette point (offset from the cell's centre, 2 x snorm16), edge depth bits
vec4 face_clip(vec3 world, out int layer);
int g_layer = 0;

float edge_depth = 0.0;  // the farthest edge among the cells read

vec2 point_at(ivec2 cell, ivec2 size) {
  if (any(lessThan(cell, ivec2(0))) || any(greaterThanEqual(cell, size))) return vec2(0.0);
  uvec2 t = texelFetch(u_edge_map, ivec3(cell, g_layer), 0).rg;
  edge_depth = max(edge_depth, uintBitsToFloat(t.g));
  return 0.5 * unpackSnorm2x16(t.r);
}

// A pseudo-angle in [0, 4) increasing counter-clockwise (the "diamond angle").
float angle(vec2 v) {
  float s = abs(v.x) + abs(v.y);
  if (s == 0.0) return 0.0;
  float r = v.y / s;
  return v.x >= 0.0 ? (v.y >= 0.0 ? r : 4.0 + r) : 2.0 - r;
}

float ccw(float from, float to) { return mod(to - from, 4.0); }

float shadow_visibility(vec3 world, vec3 normal) {
  vec4 c = face_clip(world, g_layer);
  if (c.w <= 0.0) return 1.0;
  vec3 p = c.xyz / c.w * 0.5 + 0.5;
  if (any(lessThan(p, vec3(0.0))) || any(greaterThan(p, vec3(1.0)))) return 1.0;
  ivec2 size = textureSize(u_edge_map, 0).xy;
  vec2 tc = p.xy * vec2(size) - 0.5;
  ivec2 i = ivec2(floor(tc));          // the cell, and the footprint's lower corner
  vec2 q = tc - floor(tc) - 0.5;       // the sample, from the cell's centre
  // The comparisons of the corners (gather order: (0,1) (1,1) (1,0) (0,0)).
  vec4 g = textureGather(u_shadow_map, vec3(p.xy, float(g_layer)), p.z);
  if (all(equal(g, vec4(g.x)))) return g.x;
  vec2 C = point_at(i, size);
  vec2 P = q - C;
  float a = angle(P);
  float r = angle(point_at(i + ivec2(1, 0), size) + vec2(1.0, 0.0) - C);
  float t = angle(point_at(i + ivec2(0, 1), size) + vec2(0.0, 1.0) - C);
  float l = angle(point_at(i - ivec2(1, 0), size) - vec2(1.0, 0.0) - C);
  float b = angle(point_at(i - ivec2(0, 1), size) - vec2(0.0, 1.0) - C);
  if (p.z <= edge_depth + 1.0e-4) return q.y < 0.0 ? (q.x < 0.0 ? g.w : g.z) : (q.x < 0.0 ? g.x : g.y);
  if (ccw(r, a) < ccw(r, t)) return g.y;  // right .. top: corner (1, 1)
  if (ccw(t, a) < ccw(t, l)) return g.x;  // top .. left: corner (0, 1)
  if (ccw(l, a) < ccw(l, b)) return g.w;  // left .. bottom: corner (0, 0)
  return g.z;                             // bottom .. right: corner (1, 0)
}
