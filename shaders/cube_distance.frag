#version 450 core
// Writes the squared distance from the light (Gerasimov 2004, Sect. 12.3.3)
// into an R32F cube face, pushed back by a slope-scaled bias measured in that
// distance: u_slope times the larger change of distance from one texel of the
// face to the next (dFdx / dFdy over the face's own pixels; Kenzel 2013, Sect.
// 1.2 and Arneson, "Shadow mapping": glPolygonOffset's bias, here in the
// light's own distance units). It shrinks as the map grows, where Gerasimov's
// multiplicative bias (Sect. 12.3.7) hides a fixed share of the distance at
// every size: thin gaps between a surface and what shadows it (a pipe's wall
// seen from inside through the camera's near plane) stay lit however fine the
// map is.
in vec3 v_world;
uniform vec3 u_light_position;
uniform float u_slope;  // texels of distance slope (lookup_cube.frag's taps reach about two)
layout(location = 0) out float o_distance2;
void main() {
  const float dist = length(v_world - u_light_position);
  const float pushed = dist + u_slope * max(abs(dFdx(dist)), abs(dFdy(dist)));
  o_distance2 = pushed * pushed;
}
