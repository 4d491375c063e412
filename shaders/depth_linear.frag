#version 450 core
// Depth pass of the focused maps (psm, lispsm, uniform): writes the linear light
// depth of light_depth.frag with a slope-scaled bias measured in that depth, per
// texel of the warped map: u_bias_slope times the larger change of depth from
// one texel to the next (dFdx / dFdy over the map's own pixels: where the warp
// magnifies, texels are small and so is the bias; where it compresses, both
// grow), plus u_bias_constant (depth units) for rounding.
// (Kenzel 2013, Sect. 1.2 and Arneson, "Shadow mapping": the bias of glPolygonOffset, computed
// here in a depth that the warp does not distort.)
in vec3 v_position;
uniform float u_bias_slope;
uniform float u_bias_constant;

float light_depth(vec3 p);

void main() {
  const float d = light_depth(v_position);
  gl_FragDepth = d + u_bias_slope * max(abs(dFdx(d)), abs(dFdy(d))) + u_bias_constant;
}
