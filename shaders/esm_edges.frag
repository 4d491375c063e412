#version 450 core
// Extended shadow map (Bujnak 2004), silhouette quad pass: edge distance and
// edge depth are written beside the depth map into an RGBA32F map with MAX
// blending (Sect. 4.1; the map is cleared to 0, so MAX alone does what the
// paper's ONE / DESTALPHA factors do: the first quad's values pass, later ones
// keep the maximum).
//   r  encoded edge distance (Sect. 4.2): e = 0.33 + 0.17 * d / 0.707, d the
//      signed distance to the edge in texels, positive on the lit side (the
//      side the quad is extruded to along q, v_side > 0), clamped to [0, 1]:
//      the edge passes through 0.33, 0.5 lies 0.707 texels out, and the
//      occluder's side runs down into the guard zone under 0.25. Where quads
//      overlap MAX keeps the largest value, the edge the sample is least inside.
//   g  unused
//   b  edge depth (light window depth of the quad): MAX keeps the farthest edge
//   a  1: this texel holds silhouette information
// Edges hidden from the light are not written (Sect. 3.1): a quad sample behind
// the farthest depth of the 3 x 3 depth-map texels around it is discarded.
in float v_side;
flat in vec4 v_edge;  // edge end points in the light's NDC
uniform float u_map_size;
uniform sampler2D u_depth;  // the light's depth map, without comparison
layout(location = 0) out vec4 o_edge;

void main() {
  vec2 p = gl_FragCoord.xy / u_map_size * 2.0 - 1.0;
  vec2 a = v_edge.xy, ab = v_edge.zw - v_edge.xy;
  float len = length(ab);
  if (len <= 0.0) discard;
  float line = abs(ab.x * (p.y - a.y) - ab.y * (p.x - a.x)) / len;  // NDC distance to the edge's line
  float d = line * u_map_size * 0.5 * sign(v_side);
  float z_far = 0.0;
  ivec2 c = ivec2(gl_FragCoord.xy), top = ivec2(u_map_size) - 1;
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) z_far = max(z_far, texelFetch(u_depth, clamp(c + ivec2(x, y), ivec2(0), top), 0).r);
  if (gl_FragCoord.z > z_far + 1e-5) discard;
  o_edge = vec4(clamp(0.33 + 0.17 * d / 0.707, 0.0, 1.0), 0.0, gl_FragCoord.z, 1.0);
}
