#version 450 core
// Lookup of the focused maps (psm, lispsm, uniform of geom/focus.h): the map's
// texel from the light matrix u_light_matrix (the warp), the depth compared
// from light_depth.frag (linear along the light's rays, as depth_linear.frag
// wrote it), in hardware (sampler2DShadow, GL_LEQUAL; bilinear: four texels
// compared and blended).
// Outside the map (in front of the near plane, beyond the far plane or outside
// the frustum of the warp, that is outside the focus body H) nothing is known
// to occlude: lit.
uniform mat4 u_light_matrix;  // world -> light clip space (geom/focus.h)
uniform sampler2DShadow u_shadow_map;

float light_depth(vec3 p);

float shadow_visibility(vec3 world, vec3 normal) {
  vec4 c = u_light_matrix * vec4(world, 1.0);
  if (c.w <= 0.0) return 1.0;
  vec3 p = c.xyz / c.w * 0.5 + 0.5;
  if (any(lessThan(p, vec3(0.0))) || any(greaterThan(p, vec3(1.0)))) return 1.0;
  return textureLod(u_shadow_map, vec3(p.xy, light_depth(world)), 0.0);
}
