#version 450 core
// Lookup of the focused maps (psm, lispsm, uniform) drawn as six faces around
// a point light (geom/focus.h FocusFace::focused, render/src/focused.cpp):
// the sample's face from lookup_faces.frag (the face of its direction's
// largest axis, as geom/focus.h assigns it), the texel from that face's
// matrix, the depth compared from light_depth.frag (the distance to the
// light, the same in every face), bilinear, as lookup_focused.frag does.
// Outside the face's window (an empty face's zero matrix included): lit.
uniform sampler2DArrayShadow u_shadow_map;

float light_depth(vec3 p);
vec4 face_clip(vec3 world, out int layer);

float shadow_visibility(vec3 world, vec3 normal) {
  int layer;
  vec4 c = face_clip(world, layer);
  if (c.w <= 0.0) return 1.0;
  vec3 p = c.xyz / c.w * 0.5 + 0.5;
  // The faces' near and far planes are fitted to what they hold: receivers lie
  // on them (a floor under a light looking down), where rounding puts z or the
  // window's edge a hair outside. Only a sample clearly outside the window is
  // lit; depth is compared as it is (clamped by the comparison).
  if (any(lessThan(p.xy, vec2(-1e-3))) || any(greaterThan(p.xy, vec2(1.0 + 1e-3)))) return 1.0;
  const vec2 zero = vec2(0.0);
  return textureGrad(u_shadow_map, vec4(p.xy, float(layer), light_depth(world)), zero, zero);
}
