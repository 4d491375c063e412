#version 450 core
// Linear light depth of the focused maps (psm, lispsm, uniform), linked into
// both their depth pass (depth_linear.frag) and their lookup (lookup_focused_faces.frag).
// The warped map of a perspective shadow map (Stamminger and Drettakis 2002) keeps its light matrix for
// x, y only: the post-perspective z/w of the warp crowds the far receivers'
// depths into a sliver of [0, 1] (and a slope-scaled glPolygonOffset measured
// there over- or under-biases by the warp's local scale: acne on some faces,
// shadows lost on others). Depth is instead the distance from the light along
// its ray, measured in the local frame, mapped linearly to [0, 1]:
//   directional light (u_light.w == 0): -dot(p, normalize(u_light.xyz)), the
//     position along the light's travel direction;
//   point and spot light: |p - u_light.xyz|.
// u_depth_range = (value at depth 0, 1 / span): the scene's bounding sphere.
uniform vec4 u_light;        // homogeneous, local frame (as in shade.frag)
uniform vec2 u_depth_range;

float light_depth(vec3 p) {
  const float s = u_light.w == 0.0 ? -dot(p, u_light.xyz) / max(length(u_light.xyz), 1e-30) : distance(p, u_light.xyz);
  return (s - u_depth_range.x) * u_depth_range.y;
}

// The world gradient of light_depth at p (the receiver-plane test's slope, depth_plane.frag).
vec3 light_depth_gradient(vec3 p) {
  const vec3 d = u_light.w == 0.0 ? -u_light.xyz : p - u_light.xyz;
  return d / max(length(d), 1e-30) * u_depth_range.y;
}
