#version 450 core
// Lookup of ssm and pcf drawn as six faces around a point light (render/src/
// light_fit.cpp: 90-degree faces with near and far fitted to what each holds,
// widened by a guard band): the sample's face from lookup_faces.frag, then the
// same comparison as lookup_shadow_map.frag in that face's layer of a 2D-array
// depth texture. u_pcf = 0: one nearest-texel comparison; 1: 3 x 3 bilinear
// comparison taps one texel apart (inside the guard band at a seam).
// Outside the face's window (an empty face's zero matrix included): lit.
uniform sampler2DArrayShadow u_shadow_map;
uniform int u_pcf;

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
  if (u_pcf == 0) return textureGrad(u_shadow_map, vec4(p.xy, float(layer), p.z), zero, zero);
  vec2 texel = 1.0 / vec2(textureSize(u_shadow_map, 0).xy);
  float sum = 0.0;
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x)
      sum += textureGrad(u_shadow_map, vec4(p.xy + vec2(x, y) * texel, float(layer), p.z), zero, zero);
  return sum / 9.0;
}
