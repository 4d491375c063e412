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
