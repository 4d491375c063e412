#version 450 core
// Lookup of one 2D shadow map in hardware, the plainest an engine can adopt
// (examples/engine_sample.cpp, docs/library.md). The viewer's ssm and pcf use
// lookup_shadow_faces.frag instead: one or six faces, each texel compared with
// the receiver's plane at its centre (depth_plane.frag).
// The map holds light-space depth written with a slope-scaled depth bias
// (glPolygonOffset; Kenzel 2013, Sect. 1.2, Arneson, "Shadow mapping"), compared in hardware
// (sampler2DShadow, GL_LEQUAL). u_pcf = 0: one nearest-texel comparison (simple
// shadow map); 1: percentage-closer filtering, 3 x 3 bilinear comparison taps
// one texel apart (a 4 x 4 texel footprint), averaged after comparison.
// Outside the map (in front of the near plane, beyond the far plane or outside
// the frustum) nothing is known to occlude: lit.
uniform mat4 u_light_matrix;  // world -> light clip space
uniform sampler2DShadow u_shadow_map;
uniform int u_pcf;

float shadow_visibility(vec3 world, vec3 normal) {
  vec4 c = u_light_matrix * vec4(world, 1.0);
  if (c.w <= 0.0) return 1.0;
  vec3 p = c.xyz / c.w * 0.5 + 0.5;
  if (any(lessThan(p, vec3(0.0))) || any(greaterThan(p, vec3(1.0)))) return 1.0;
  if (u_pcf == 0) return textureLod(u_shadow_map, p, 0.0);
  vec2 texel = 1.0 / vec2(textureSize(u_shadow_map, 0));
  float sum = 0.0;
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) sum += textureLod(u_shadow_map, p + vec3(vec2(x, y) * texel, 0.0), 0.0);
  return sum / 9.0;
}
