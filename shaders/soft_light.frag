#version 450 core
// The penumbra of a disc light, shared by the soft lookups (lookup_edsm_soft.frag,
// lookup_pcf_soft.frag). The light is a disc of radius u_light_radius facing the
// receiver (a point or spot light: world units; a directional light: its
// angular radius, radians). A straight occluder edge at light depth d_o seen
// from a receiver at d_r covers a share of the disc given by the receiver's
// signed distance to the hard shadow's edge (the centre's shadow); by similar
// triangles the penumbra's half width, in shadow-map texels, is
//   point:       R (d_r - d_o) / (d_o d_r) * P[0][0] * N / 2   (the map's angle per texel)
//   directional: tan(R) (d_r - d_o) * P[0][0] * N / 2           (orthographic)
// and the light fraction at signed distance x (in half widths, positive on the
// occluder's side) is the disc's share on the far side of a chord at x:
//   (acos(x) - x sqrt(1 - x^2)) / pi, 1 at x <= -1, 0 at x >= 1.
uniform mat4 u_light_proj;     // the light's projection (its near / far give depths)
uniform float u_light_radius;  // R
uniform float u_map_size;      // N

// Light-space depth (along the light's axis) of a window depth in [0, 1].
float light_distance(float window_z) {
  float z = window_z * 2.0 - 1.0;
  if (u_light_proj[3][3] == 1.0) return (u_light_proj[3][2] - z) / u_light_proj[2][2];  // orthographic
  return u_light_proj[3][2] / (z + u_light_proj[2][2]);
}

// The penumbra's half width in texels for an occluder at window depth zo and a receiver at zr.
float penumbra_texels(float zo, float zr) {
  float d_o = light_distance(zo), d_r = light_distance(zr);
  float behind = max(d_r - d_o, 0.0);
  float ndc = u_light_proj[3][3] == 1.0 ? tan(u_light_radius) * behind * u_light_proj[0][0]
                                        : u_light_radius * behind / max(d_o * d_r, 1e-30) * u_light_proj[0][0];
  return ndc * u_map_size * 0.5;
}

float disc_fraction(float x) {
  x = clamp(x, -1.0, 1.0);
  return (acos(x) - x * sqrt(1.0 - x * x)) / 3.14159265;
}

// The same half width for any light clip matrix m (a fitted frustum, a cube
// face: lookup_esm_soft.frag), from the geometry instead of a projection's
// parameters: the occluder is the point of the receiver's ray to the light
// (u_light, homogeneous, in m's frame) at window depth zo (m is projective, so
// its depth along the ray solves linearly); the penumbra's half width there is
// W = R (d_r - d_o) / d_o (point) or tan(R) (d_r - d_o) (directional), across
// the ray; in texels across the edge, whose texel-space normal is n, it is
// W |J^T n| with J the exact derivative of the texel position across the ray.
uniform vec4 u_light;  // shade.frag's: the light, homogeneous, local frame

float penumbra_texels_at(mat4 m, vec3 world, float zo, vec2 n, vec2 size) {
  bool point = u_light.w != 0.0;
  vec3 ray = point ? world - u_light.xyz / u_light.w : -normalize(u_light.xyz);  // light -> receiver
  vec4 c = m * vec4(world, 1.0), dc = m * vec4(-ray, 0.0);  // along the ray towards the light
  float zn = zo * 2.0 - 1.0;
  // (c + s dc).z / (c + s dc).w = zn: s, the share of `ray` back to the occluder.
  float den = dc.z - zn * dc.w;
  if (abs(den) < 1e-30) return 0.0;
  float s = (zn * c.w - c.z) / den;
  float W = point ? u_light_radius * s / max(1.0 - s, 1e-6)          // d_r s / (d_r (1 - s)) = (d_r - d_o) / d_o
                  : tan(u_light_radius) * s;                          // |ray| = 1 for the sun
  if (!(W > 0.0)) return 0.0;
  vec3 r = normalize(ray);
  vec3 u1 = normalize(cross(r, abs(r.x) < 0.9 ? vec3(1, 0, 0) : vec3(0, 1, 0))), u2 = cross(r, u1);
  vec4 a = m * vec4(u1, 0.0), b = m * vec4(u2, 0.0);
  vec2 ja = (a.xy * c.w - c.xy * a.w) / (c.w * c.w) * 0.5 * size;  // texels per unit along u1
  vec2 jb = (b.xy * c.w - c.xy * b.w) / (c.w * c.w) * 0.5 * size;
  return W * length(vec2(dot(ja, n), dot(jb, n)));
}
