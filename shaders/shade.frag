#version 450 core
// The shading pass shared by all techniques. The technique's lookup shader (a
// second fragment shader object linked beside this one, shaders/lookup_*.frag)
// defines shadow_visibility(): 1 lit, 0 in shadow, in between where filtered.
// Light: u_light is homogeneous (w = 1 point light at xyz, w = 0 a light at
// infinity in direction xyz). Surfaces are two-sided: the visible side is lit
// only when the light is on its side by more than the grazing epsilon
// (N.L >= 1e-4) and, for a spot, inside the cone.
// u_output 1 writes the mask (1 lit, 0 shadowed; the clear colour 0.5 marks no
// geometry), 0 writes a shaded colour, 2 the light fraction itself (the soft
// techniques' output, against geom/area_reference.h).
in vec3 v_world;
in vec3 v_normal;
in float v_view_depth;
uniform vec4 u_light;
uniform vec3 u_spot_direction;  // unit, where the spot shines
uniform float u_spot_cos;       // cos of the cone's half angle; < -1 for no cone
uniform float u_far;            // the camera's far plane (the projection itself has none)
uniform int u_output;
uniform int u_ambient_only;     // 1: everything shadowed (first pass of shadow volumes)
layout(location = 0) out vec4 o_color;

float shadow_visibility(vec3 world, vec3 normal);

void main() {
  if (v_view_depth > u_far) discard;
  vec3 n = normalize(v_normal);
  if (!gl_FrontFacing) n = -n;
  vec3 l = normalize(u_light.xyz - v_world * u_light.w);
  float ndl = dot(n, l);
  bool in_cone = u_light.w == 0.0 || u_spot_cos < -1.5 || dot(-l, u_spot_direction) >= u_spot_cos;
  // Facing away, parallel or grazing within kGrazing: no direct light,
  // whatever the map says (a map cannot resolve a face seen edge-on from the
  // light). geom/shadow_reference.h counts |N.L| < kGrazing as uncertain. The
  // lookup still runs in uniform control flow (some take derivatives).
  const float kGrazing = 1e-4;
  float visibility = shadow_visibility(v_world, n);
  if (u_ambient_only != 0 || !(ndl >= kGrazing) || !in_cone) visibility = 0.0;
  if (u_output == 2) {
    o_color = vec4(visibility, visibility, visibility, 1.0);
    return;
  }
  if (u_output == 1) {
    float m = visibility > 0.5 ? 1.0 : 0.0;
    o_color = vec4(m, m, m, 1.0);
    return;
  }
  vec3 albedo = vec3(0.8, 0.78, 0.74);
  vec3 c = albedo * (0.12 + 0.88 * max(ndl, 0.0) * visibility);
  o_color = vec4(pow(c, vec3(1.0 / 2.2)), 1.0);
}
