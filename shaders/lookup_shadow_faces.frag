#version 450 core
// Lookup of ssm and pcf (render/src/shadow_map.cpp): one fitted frustum
// (u_faces 1) or six faces around a point light (u_faces 6; render/src/
// light_fit.cpp: 90-degree faces with near and far fitted to what each holds,
// widened by a guard band). The sample's face and clip position come from
// lookup_faces.frag, the test from depth_plane.frag: the receiver's plane
// against the depth map at each texel's centre. u_pcf = 0: the
// nearest texel (simple shadow map); 1: percentage-closer filtering, 3 x 3
// bilinear taps one texel apart (inside the guard band at a seam), averaged
// after comparison.
// Outside the face's window (an empty face's zero matrix included): lit.
uniform int u_pcf;

vec4 face_clip(vec3 world, out int layer);
mat4 face_matrix(int layer);
vec3 receiver_slope(mat4 m, vec3 world, vec3 normal, vec2 size, vec3 depth_gradient);
float nearest_lit(int layer, vec3 p, vec3 g);
float pcf_lit(int layer, vec3 p, vec3 g);
uniform sampler2DArray u_depth_raw;

float shadow_visibility(vec3 world, vec3 normal) {
  int layer;
  vec4 c = face_clip(world, layer);
  const vec3 g = receiver_slope(face_matrix(layer), world, normal, vec2(textureSize(u_depth_raw, 0).xy), vec3(0.0));
  if (c.w <= 0.0) return 1.0;
  vec3 p = c.xyz / c.w * 0.5 + 0.5;
  // The faces' near and far planes are fitted to what they hold: receivers lie
  // on them (a floor under a light looking down), where rounding puts z or the
  // window's edge a hair outside. Only a sample clearly outside the window is
  // lit; depth is compared clamped, as a comparison sampler clamps it.
  if (any(lessThan(p.xy, vec2(-1e-3))) || any(greaterThan(p.xy, vec2(1.0 + 1e-3)))) return 1.0;
  return u_pcf == 0 ? nearest_lit(layer, p, g) : pcf_lit(layer, p, g);
}
