#version 450 core
// Layered rendering of the six cube faces (+X -X +Y -Y +Z -Z) in one pass:
// each triangle is emitted once per face, gl_Layer selecting the face.
layout(triangles) in;
layout(triangle_strip, max_vertices = 18) out;
in vec3 g_world[];
out vec3 v_world;
uniform mat4 u_face[6];  // world -> clip of each face: 90 degree perspective * look-at
void main() {
  for (int f = 0; f < 6; ++f) {
    for (int k = 0; k < 3; ++k) {
      gl_Layer = f;
      v_world = g_world[k];
      gl_Position = u_face[f] * vec4(g_world[k], 1.0);
      EmitVertex();
    }
    EndPrimitive();
  }
}
