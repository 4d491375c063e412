#version 450 core
// Lookup of the omnidirectional cube shadow map (Gerasimov 2004, Sect. 12.3-12.4):
// the map stores the squared distance to the light, pushed back by a
// slope-scaled bias (shaders/cube_distance.frag); the fragment's squared
// distance times a multiplicative factor (Gerasimov's form, 12.3.7:
// "fDistSquared * DepthBias", here only 1/1000 for rounding: his 3% hid a
// fixed share of the distance, whatever the map's size) is compared with 4
// taps around the light-to-fragment direction, and the comparisons are
// averaged (percentage-closer filtering, 12.4).
uniform vec4 u_light;
uniform samplerCube u_shadow_map;  // R32F squared distances
uniform float u_cube_bias;         // < 1: 0.999
uniform float u_cube_filter;       // tap offset relative to the direction's length (about a texel)

float shadow_visibility(vec3 world, vec3 normal) {
  vec3 d = world - u_light.xyz;
  float depth = dot(d, d) * u_cube_bias;
  const vec3 taps[4] = vec3[](vec3(1, 1, 1), vec3(-1, -1, 1), vec3(-1, 1, -1), vec3(1, -1, -1));
  float lit = 0.0;
  for (int i = 0; i < 4; ++i) {
    float stored = textureLod(u_shadow_map, d + taps[i] * (u_cube_filter * length(d)), 0.0).r;
    lit += depth - stored < 0.0 ? 0.25 : 0.0;
  }
  return lit;
}
