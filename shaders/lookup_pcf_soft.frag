#version 450 core
// The soft baseline: percentage-closer filtering with a kernel as wide as the
// penumbra (the PCSS recipe, Fernando 2005): a blocker search over the widest
// penumbra of the frame (4 x 4 depth taps, u_reach texels each side) gives
// the mean blocker depth; the penumbra's half width of soft_light.frag for it
// sets the kernel, 6 x 6 bilinear comparison taps spanning it, averaged. The
// depth of each tap is moved along the receiver's plane (receiver-plane depth
// bias from the screen-space derivatives), so that wide kernels do not shadow
// the receiver itself.
uniform mat4 u_light_matrix;
uniform sampler2DShadow u_shadow_map;
uniform sampler2D u_depth_map;  // the same depth map, read without comparison
uniform float u_reach;          // texels: the widest penumbra of the frame

float penumbra_texels(float zo, float zr);

float shadow_visibility(vec3 world, vec3 normal) {
  vec4 c = u_light_matrix * vec4(world, 1.0);
  vec3 p = c.xyz / c.w * 0.5 + 0.5;
  // The receiver plane: depth change per texel in the map (d z / d uv).
  vec2 size = vec2(textureSize(u_shadow_map, 0));
  vec3 px = dFdx(p), py = dFdy(p);
  mat2 uv = mat2(px.xy * size, py.xy * size);
  float det = determinant(uv);
  vec2 dz = abs(det) > 1e-12 ? inverse(transpose(uv)) * vec2(px.z, py.z) : vec2(0.0);
  dz = clamp(dz, vec2(-0.01), vec2(0.01));
  if (c.w <= 0.0) return 1.0;
  if (any(lessThan(p, vec3(0.0))) || any(greaterThan(p, vec3(1.0)))) return 1.0;
  float sum = 0.0, n = 0.0;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      vec2 o = (vec2(x, y) / 3.0 * 2.0 - 1.0) * u_reach;
      float z = textureLod(u_depth_map, p.xy + o / size, 0.0).r;
      if (z < p.z + dot(dz, o) - 2e-4) sum += z, n += 1.0;
    }
  if (n == 0.0) return 1.0;
  float h = clamp(penumbra_texels(sum / n, p.z), 0.5, u_reach);
  float lit = 0.0;
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 6; ++x) {
      vec2 o = ((vec2(x, y) + 0.5) / 6.0 * 2.0 - 1.0) * h;
      lit += textureLod(u_shadow_map, vec3(p.xy + o / size, p.z + dot(dz, o)), 0.0);
    }
  return lit / 36.0;
}
