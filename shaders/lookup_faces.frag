#version 450 core
// The light frame of the silhouette maps (esm, edsm): one frustum fitted to what
// the camera sees (u_faces 1), or six cube faces around a point light (u_faces
// 6; render/src/silhouette_faces.cpp). A sample takes the face of its
// direction's largest axis (+X -X +Y -Y +Z -Z, ties towards x then y); each
// face's frustum is wider than 90 degrees by a guard band of a few texels, so a
// sample's 2 x 2 footprint and the edge quads around it lie inside the face it
// takes, and no lookup reads across a seam.
uniform int u_faces;
uniform mat4 u_face_matrix[6];  // local frame -> the face's clip space
uniform vec3 u_face_light;      // the point light in the local frame

vec4 face_clip(vec3 world, out int layer) {
  layer = 0;
  if (u_faces == 6) {
    vec3 d = world - u_face_light, a = abs(d);
    if (a.x >= a.y && a.x >= a.z)
      layer = d.x >= 0.0 ? 0 : 1;
    else if (a.y >= a.z)
      layer = d.y >= 0.0 ? 2 : 3;
    else
      layer = d.z >= 0.0 ? 4 : 5;
  }
  return u_face_matrix[layer] * vec4(world, 1.0);
}

mat4 face_matrix(int layer) { return u_face_matrix[layer]; }
