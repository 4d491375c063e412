#version 450 core
// Lookup of the focused maps (psm, lispsm, uniform of geom/focus.h;
// render/src/focused.cpp): one warped map (u_faces 1) or six faces around a
// point light (u_faces 6, FocusFace::focused). The sample's face from
// lookup_faces.frag (the face of its direction's largest axis, as
// geom/focus.h assigns it), the texel from that face's matrix, the depth from
// light_depth.frag (linear along the light's rays, the same in every face),
// compared as depth_plane.frag does: the receiver's plane at each texel's
// centre, its slope taken through the warp; bilinear (the 2 x 2 footprint's
// comparisons blended).
// Outside the face's window (an empty face's zero matrix included): lit.
float light_depth(vec3 p);
vec3 light_depth_gradient(vec3 p);
vec4 face_clip(vec3 world, out int layer);
mat4 face_matrix(int layer);
vec3 receiver_slope(mat4 m, vec3 world, vec3 normal, vec2 size, vec3 depth_gradient);
vec4 footprint_lit(int layer, vec3 p, vec3 g, out ivec2 base, out vec2 f);
uniform sampler2DArray u_depth_raw;

float shadow_visibility(vec3 world, vec3 normal) {
  int layer;
  vec4 c = face_clip(world, layer);
  const vec2 size = vec2(textureSize(u_depth_raw, 0).xy);
  const vec3 g = receiver_slope(face_matrix(layer), world, normal, size, light_depth_gradient(world));
  if (c.w <= 0.0) return 1.0;
  vec3 p = vec3(c.xy / c.w * 0.5 + 0.5, light_depth(world));
  // Receivers on a fitted face's near or far plane, or on the window's edge,
  // land a hair outside through rounding: only a sample clearly outside is lit.
  if (any(lessThan(p.xy, vec2(-1e-3))) || any(greaterThan(p.xy, vec2(1.0 + 1e-3)))) return 1.0;
  ivec2 base;
  vec2 f;
  const vec4 lit = footprint_lit(layer, p, g, base, f);
  return mix(mix(lit[0], lit[1], f.x), mix(lit[2], lit[3], f.x), f.y);
}
