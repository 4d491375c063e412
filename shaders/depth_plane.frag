#version 450 core
// The receiver-plane depth test every depth-map lookup makes (ssm, pcf, the
// focused maps, the faces of a point light, and the silhouette maps where
// their reconstruction cannot decide): a map texel is compared with the depth
// of the receiver's own plane at that texel's centre, not at the sample.
//
// A depth map stores, at each texel's centre, the depth of the nearest surface
// there (the rasterizer samples at texel centres). A receiver lit at its
// sample is lit at the texel centre exactly when its plane, carried to that
// centre, is not behind the stored depth: the comparison needs no slope
// factor, at any angle and any map size. A projective map takes planes to
// planes, so the plane's window depth is linear in the map's texel
// coordinates, and its gradient comes exactly from the receiver's normal (Dou
// et al. 2014, adaptive depth bias: the depth of the receiver's
// tangent plane at the texel's centre; Isidoro 2006, receiver plane depth
// bias, with the plane taken from the normal instead of screen derivatives,
// which break at triangle edges). A convex caster's lit faces are never behind
// its front at any texel centre, so they get no acne (a slope-scaled offset
// uses the stored face's slope, not the receiver's: a round pillar's
// neighbouring facets fall inside its texels and shadow it).
// At a concave crease (a wall on a floor, a pillar's foot) the texel's centre
// may fall on the other face, and where the receiver's plane runs away from
// the light towards that centre the other face stands in front of it there:
// acne in a band along every crease, however the map is sized. So the
// receiver is compared at the nearer of its plane at the texel's centre and
// its own depth at the sample: min(z, plane(centre)). Where the plane runs
// towards the light that is the plane, as above; where it runs away, the
// sample's own depth, and the face at the centre beyond the crease line lies
// between the two and is pushed back by the depth pass's slope-scaled offset
// (shadow_map.cpp, factor 2: at least the stored face's own depth change over
// the 0.71 texel from the sample to the centre), so it is never in front of
// the sample. A convex caster's neighbouring facets are behind both.
// (tests/test_gl_bias_crease.cpp: an open corner lit from inside, no shadowed
// pixel at maps of 64 to 1024 texels; the plane alone shadowed it in 39 of
// 504 cases.)
// What remains is rounding, the allowance `depth_allowance`: a few units in
// the last place of the depth; the rasterizer's snapping of the depth pass's
// vertices, 1/16 texel times the plane's slope (GL's minimum of 4 sub-pixel
// bits); and the float rounding of world positions, a fixed world error whose
// depth error does not shrink as the map grows. A larger slope allowance hides
// real occluders close to a steep receiver: a quarter texel hid the 1 cm step
// between a jenga tower's levels at every map size up to 4096 (its error
// stayed flat), and lit the rippled sphere's self-shadows near the terminator.
// Measured (geombench, 640x480, 1 frame, error_visible at 512 / 1024 / 2048 /
// 4096 in %; in brackets the plane alone with a quarter texel): ssm on
// wide-depth 1.27 / 0.22 / 0.072 / 0.073 (1.29 / 0.83 / 0.31 / 0.14), heavy
// 0.30 / 0.12 / 0.055 / 0.028 (0.36 / 0.16 / 0.073 / 0.037), quake3 at 256
// 0.014 (0.052), jenga 0.079 / 0.163 / 0.095 / 0.029 (0.082 / 0.076 / 0.089
// / 0.042: the step's shadow, a few texels tall on the nearest tower's faces,
// aliases once the map resolves it); a quarter texel with this rule left
// heavy at 0.18 at 1024, 1/256 at 0.095.
// Linked with the lookups that call it; the caller passes the light matrix it
// used (the face's, for six faces) and the map's size in texels.

// The receiver plane's depth gradient per texel of the map (xy), from its
// world position and normal under the light matrix `m` (local frame -> clip),
// and the rounding allowance of its depth (z). `depth_gradient`: the world
// gradient of the stored depth for a linear light depth (light_depth.frag),
// or vec3(0) for the matrix's own window depth.
vec3 receiver_slope(mat4 m, vec3 world, vec3 normal, vec2 size, vec3 depth_gradient) {
  const vec3 n = normalize(normal);
  const vec3 t1 = normalize(cross(n, abs(n.x) < 0.9 ? vec3(1, 0, 0) : vec3(0, 1, 0)));
  const vec3 t2 = cross(n, t1);
  const vec4 c = m * vec4(world, 1.0);
  const vec3 q = c.xyz / c.w;
  // The derivative of the projection along each tangent: exact, the plane's
  // image being a plane.
  const vec4 d1 = m * vec4(t1, 0.0), d2 = m * vec4(t2, 0.0);
  const vec3 e1 = (d1.xyz - q * d1.w) / c.w, e2 = (d2.xyz - q * d2.w) / c.w;
  const mat2 J = mat2(e1.xy * 0.5 * size, e2.xy * 0.5 * size);  // texels per unit along t1, t2
  const bool linear = depth_gradient != vec3(0.0);
  // The depth's world gradient: the stored depth's, or the window depth's (0.5 d(z/w)).
  const vec3 row_z = vec3(m[0][2], m[1][2], m[2][2]), row_w = vec3(m[0][3], m[1][3], m[2][3]);
  const vec3 grad_world = linear ? depth_gradient : 0.5 * (row_z - q.z * row_w) / c.w;
  const vec2 dz = vec2(dot(grad_world, t1), dot(grad_world, t2));
  // World positions carry float rounding (a few units in the last place of
  // their largest coordinate), in the camera pass and in the depth pass alike:
  // a fixed world error whose depth error does not shrink as the map grows.
  const float position_error = 16.0 * max(max(abs(world.x), abs(world.y)), max(abs(world.z), 1.0)) / 8388608.0;
  const float allowance = position_error * length(grad_world);
  const float det = determinant(J);
  // Edge-on to the light (the shading gives it no direct light): no slope.
  if (!(abs(det) > 1.0e-20 * max(dot(J[0], J[0]), dot(J[1], J[1])))) return vec3(0.0, 0.0, allowance);
  return vec3(dz * inverse(J), allowance);
}

// The rounding allowance of a comparison at depth z with plane slope s.xy and
// world allowance s.z.
float depth_allowance(float z, vec3 s) {
  const float ulps = 8.0 * max(abs(z), 1.0 / 1024.0) * (1.0 / 8388608.0);
  return ulps + (abs(s.x) + abs(s.y)) * (1.0 / 16.0) + s.z;
}

// The receiver's depth at the centre of the texel `texel` (integer coords),
// from the sample's texel coordinates `tc` (texel units, centres at +0.5),
// depth z and plane slope s (receiver_slope), less the allowance: what the
// stored depth is compared with (lit where stored >= this).
float plane_depth(ivec2 texel, vec2 tc, float z, vec3 s) {
  return min(z, z + dot(s.xy, vec2(texel) + 0.5 - tc)) - depth_allowance(z, s);
}

// The depth maps without comparison (texture unit 3, a sampler without
// compare mode), a layer per face; a single frustum is layer 0.
uniform sampler2DArray u_depth_raw;

// Window depth clamped as a comparison sampler clamps its reference.
float compared(float z) { return clamp(z, 0.0, 1.0); }

// 1 where texel t (clamped to the map, as GL_CLAMP_TO_EDGE) of `layer` holds
// nothing in front of the receiver's plane (depth z at texel coordinates tc,
// slope g) at its centre, else 0.
float texel_lit(int layer, ivec2 t, vec2 tc, float z, vec3 g) {
  const ivec2 top = textureSize(u_depth_raw, 0).xy - 1;
  const ivec2 c = clamp(t, ivec2(0), top);
  const float stored = texelFetch(u_depth_raw, ivec3(c, layer), 0).r;
  return stored >= compared(plane_depth(c, tc, z, g)) ? 1.0 : 0.0;
}

// ssm's test: the nearest texel of window position p (x, y, depth in [0, 1]).
float nearest_lit(int layer, vec3 p, vec3 g) {
  const vec2 tc = p.xy * vec2(textureSize(u_depth_raw, 0).xy);
  return texel_lit(layer, ivec2(floor(tc)), tc, p.z, g);
}

// The 2 x 2 footprint around p (texels (0,0) (1,0) (0,1) (1,1) from the one
// below and left of the sample), each compared at its own centre; `base` and
// `f` receive the footprint's first texel and the sample's bilinear weights.
vec4 footprint_lit(int layer, vec3 p, vec3 g, out ivec2 base, out vec2 f) {
  const vec2 tc = p.xy * vec2(textureSize(u_depth_raw, 0).xy);
  const vec2 b = tc - 0.5;
  base = ivec2(floor(b));
  f = b - floor(b);
  vec4 lit;
  for (int k = 0; k < 4; ++k) lit[k] = texel_lit(layer, base + ivec2(k & 1, k >> 1), tc, p.z, g);
  return lit;
}

// pcf's test: 3 x 3 bilinear taps one texel apart around p, averaged (a 4 x 4
// texel footprint: per axis the weights (1 - f, 1, 1, f) / 3).
float pcf_lit(int layer, vec3 p, vec3 g) {
  const vec2 tc = p.xy * vec2(textureSize(u_depth_raw, 0).xy);
  const vec2 b = tc - 0.5;
  const ivec2 base = ivec2(floor(b)) - 1;
  const vec2 f = b - floor(b);
  const vec4 wx = vec4(1.0 - f.x, 1.0, 1.0, f.x), wy = vec4(1.0 - f.y, 1.0, 1.0, f.y);
  float sum = 0.0;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) sum += wx[x] * wy[y] * texel_lit(layer, base + ivec2(x, y), tc, p.z, g);
  return sum / 9.0;
}
