#version 450 core
// Writes the squared distance from the light (Gerasimov 2004, Sect. 12.3.3: a dot product, no
// square root), into an R32F cube face.
in vec3 v_world;
uniform vec3 u_light_position;
layout(location = 0) out float o_distance2;
void main() {
  vec3 d = v_world - u_light_position;
  o_distance2 = dot(d, d);
}
