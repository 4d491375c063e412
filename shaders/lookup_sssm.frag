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
// Deviation (Sen et al. have no depth per point): where the cell's comparisons
// differ, only silhouette points in front of the receiver take part, as
// lookup_edsm.frag's step 1: an edge counts if its stored depth lies kInFront
// nearer the light than the receiver's plane at the point (the receiver's
// window depth carried along its screen-derivative slope to the point). A
// point that does not (the receiver's own outline, e.g. an upper block's
// silhouette on the lower block's face at the default scene's tower seams) is
// read as the cell's centre; no point in front in the five cells: lit. This
// replaces the nearest depth sample's comparison for a receiver not behind the
// farthest edge around it (1e-4 window depth; docs/geombench.md: 2-8x better
// than the paper's lookup at 1024-2048 in its run), which made the default
// scene's 5-71 wrong cast pixels. Measured (geombench, 640x480, 1 frame,
// wrong cast-class pixels at 256 / 512 / 1024 / 2048 / 4096; edsm 2/0/0/0/0 on
// default, 0 on pipes): the nearest fallback default 71/37/19/12/5, pipes
// 10/0/0/0/1; the rule with the receiver's own depth (no plane), kInFront 2e-6
// default 23/8/2/0/0, 1e-5 10/4/4, 1e-4 1/0/0/0/0 but scan's error_visible
// 0.31/0.16/0.066% at 256/512/1024 against 0.15/0.060/0.024% before; with the
// plane, kInFront 2e-6 2/3/1/1/0, 1e-5 1/1/0/0/0 (kept), 2e-5 2/1/0/0/0, 3e-5
// 3/0/0/0/0 with scan@2048 error_visible 0.012% against 0.0046% at 1e-5;
// pipes 0 from 256 up for all of them. Keeping the points of edges not in
// front (the lit rule alone) gave default 65/34/10 at 256/512/1024.
// A cell that holds no silhouette point at all (no edge crosses it, by the
// edge pass's conservative cover) yet whose corners' comparisons differ: the
// difference is not a silhouette's but the comparison's own (the gathered
// comparison at the sample's depth, no receiver plane: corners along a steep
// receiver's diagonal gradient read its own face as in front, since the map's
// slope-scaled offset covers one axis's slope, not the sum of both), or detail
// thinner than a texel. There the corners are compared as ssm compares them,
// with the receiver's plane at each corner's centre (depth_plane.frag), and
// the reconstruction below picks among those. Measured (geombench, 640x480,
// jenga, wrong pixels at 256 / 512 / 1024 / 2048 / 4096): 929 / 1030 / 249 /
// 9 / 9 with the gathered corners (lit faces shadowed in patches along
// each block), 879 / 513 / 115 / 8 / 8 with this; heavy 767 / 107 / 45 / 20 /
// 14 against 769 / 114 / 47 / 20 / 14. The plane's corners in every cell, or
// ssm's own answer wherever its four agree (as lookup_edsm.frag), took jenga
// to 230 / 163 at 256 / 512 but heavy to 1439 / 332 (near occluders on the
// rippled sphere inside the map's offset, which the gathered corners catch).
// The light frame: the fitted frustum or six cube faces (lookup_faces.frag), as edsm's.
uniform sampler2DArrayShadow u_shadow_map;  // comparison sampler, gathered; a layer per face
uniform usampler2DArray u_edge_map;         // RG32UI: the silhouette point (offset from the cell's centre, 2 x snorm16), edge depth bits
vec4 face_clip(vec3 world, out int layer);
mat4 face_matrix(int layer);
vec3 receiver_slope(mat4 m, vec3 world, vec3 normal, vec2 size, vec3 depth_gradient);  // depth_plane.frag
vec4 footprint_lit(int layer, vec3 p, vec3 g, out ivec2 base, out vec2 f);
int g_layer = 0;

const float kInFront = 1.0e-5;  // window depth: an edge this far in front of the receiver (its plane) can shadow it
const float kPlaneMax = 1.0e-3;  // the receiver plane's reach in window depth (grazing receivers)
float g_z = 0.0;                // the receiver's window depth
bool g_in_front = false;        // some cell read holds an edge in front of the receiver

vec2 g_grad = vec2(0.0);        // the receiver's window depth per texel (its plane)
vec2 g_q = vec2(0.0);           // the sample, from its cell's centre

vec2 point_at(ivec2 cell, ivec2 size, ivec2 o) {
  if (any(lessThan(cell, ivec2(0))) || any(greaterThanEqual(cell, size))) return vec2(0.0);
  uvec2 t = texelFetch(u_edge_map, ivec3(cell, g_layer), 0).rg;
  vec2 pt = 0.5 * unpackSnorm2x16(t.r);
  // The receiver's depth at the point, on its plane: its own outline lies in it.
  float z_at = g_z + clamp(dot(g_grad, vec2(o) + pt - g_q), -kPlaneMax, kPlaneMax);
  bool front = t.g != 0u && uintBitsToFloat(t.g) + kInFront <= z_at;
  g_in_front = g_in_front || front;
  if (!front) return vec2(0.0);  // no edge in front: the cell's centre, as an empty cell
  return pt;
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
  vec3 p = c.xyz / c.w * 0.5 + 0.5;
  ivec2 size = textureSize(u_edge_map, 0).xy;
  vec2 tc = p.xy * vec2(size) - 0.5;
  // The receiver's plane in the map: window depth per texel, from the screen derivatives.
  mat2 J = mat2(dFdx(tc), dFdy(tc));
  vec2 dz = vec2(dFdx(p.z), dFdy(p.z));
  float det = determinant(J);
  g_grad = abs(det) > 1.0e-12 ? dz * inverse(J) : vec2(0.0);
  if (c.w <= 0.0) return 1.0;
  if (any(lessThan(p, vec3(0.0))) || any(greaterThan(p, vec3(1.0)))) return 1.0;
  g_z = p.z;
  ivec2 i = ivec2(floor(tc));          // the cell, and the footprint's lower corner
  vec2 q = tc - floor(tc) - 0.5;       // the sample, from the cell's centre
  g_q = q;
  // The comparisons of the corners (gather order: (0,1) (1,1) (1,0) (0,0)).
  vec4 g = textureGather(u_shadow_map, vec3(p.xy, float(g_layer)), p.z);
  if (all(equal(g, vec4(g.x)))) return g.x;
  if (texelFetch(u_edge_map, ivec3(i, g_layer), 0).g == 0u) {  // no edge crosses the cell: ssm's comparisons
    ivec2 base;
    vec2 f;
    const vec3 slope = receiver_slope(face_matrix(g_layer), world, normal, vec2(size), vec3(0.0));
    const vec4 lit = footprint_lit(g_layer, p, slope, base, f);  // (0,0) (1,0) (0,1) (1,1)
    g = vec4(lit.z, lit.w, lit.y, lit.x);                         // gather order
  }
  vec2 C = point_at(i, size, ivec2(0));
  vec2 P = q - C;
  float a = angle(P);
  float r = angle(point_at(i + ivec2(1, 0), size, ivec2(1, 0)) + vec2(1.0, 0.0) - C);
  float t = angle(point_at(i + ivec2(0, 1), size, ivec2(0, 1)) + vec2(0.0, 1.0) - C);
  float l = angle(point_at(i - ivec2(1, 0), size, ivec2(-1, 0)) - vec2(1.0, 0.0) - C);
  float b = angle(point_at(i - ivec2(0, 1), size, ivec2(0, -1)) - vec2(0.0, 1.0) - C);
  if (!g_in_front) return 1.0;  // no edge in front of the receiver in the five cells: lit
  if (ccw(r, a) < ccw(r, t)) return g.y;  // right .. top: corner (1, 1)
  if (ccw(t, a) < ccw(t, l)) return g.x;  // top .. left: corner (0, 1)
  if (ccw(l, a) < ccw(l, b)) return g.w;  // left .. bottom: corner (0, 0)
  return g.z;                             // bottom .. right: corner (1, 0)
}
