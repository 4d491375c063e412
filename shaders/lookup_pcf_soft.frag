#version 450 core
// The soft baseline: percentage-closer filtering with a kernel as wide as the
// penumbra (the PCSS recipe, Fernando 2005), on pcf's light frames (one
// fitted frustum or six faces: lookup_faces.frag). A blocker search over the
// widest penumbra of the frame (u_reach texels around the sample, 25 texels
// on a golden-angle spiral whose radius grows with the square of the tap's
// index: dense near the sample, so a thin blocker above it is not stepped
// over as a coarse grid over a wide reach would) gives the mean blocker depth; the penumbra's half width for it (soft_light.frag,
// the larger across either axis of the map) sets the kernel, 6 x 6 bilinear
// taps spanning it, averaged. Every texel is tested as ssm's are
// (depth_plane.frag): the receiver's own plane carried to the texel's centre
// against the stored depth, so a kernel wider than the receiver's texel does
// not shadow the receiver itself at any angle or map size. Outside the face's
// window: lit. At a seam of six faces the kernel's taps beyond the guard band
// read the face's clamped border.
uniform vec2 u_reach;  // texels along the map's x and y: the widest penumbra of the frame
const int kSearch = 24;  // blocker taps beyond the sample's own texel
const float kGoldenAngle = 2.39996323;

vec4 face_clip(vec3 world, out int layer);
mat4 face_matrix(int layer);
vec3 receiver_slope(mat4 m, vec3 world, vec3 normal, vec2 size, vec3 depth_gradient);
float plane_depth(ivec2 texel, vec2 tc, float z, vec3 s);
float compared(float z);
float texel_lit(int layer, ivec2 t, vec2 tc, float z, vec3 g);
float penumbra_texels_at(mat4 m, vec3 world, float zo, vec2 n, vec2 size);
uniform sampler2DArray u_depth_raw;

float shadow_visibility(vec3 world, vec3 normal) {
  int layer;
  vec4 c = face_clip(world, layer);
  if (c.w <= 0.0) return 1.0;
  vec3 p = c.xyz / c.w * 0.5 + 0.5;
  if (any(lessThan(p.xy, vec2(-1e-3))) || any(greaterThan(p.xy, vec2(1.0 + 1e-3)))) return 1.0;
  const ivec2 size = textureSize(u_depth_raw, 0).xy;
  const mat4 m = face_matrix(layer);
  const vec3 g = receiver_slope(m, world, normal, vec2(size), vec3(0.0));
  const vec2 tc = p.xy * vec2(size);
  float sum = 0.0, n = 0.0;
  for (int k = 0; k <= kSearch; ++k) {  // a spiral from the sample's texel out to u_reach
    const float r = float(k * k) / float(kSearch * kSearch), a = float(k) * kGoldenAngle;
    const ivec2 t = clamp(ivec2(floor(tc + r * u_reach * vec2(cos(a), sin(a)))), ivec2(0), size - 1);
    const float z = texelFetch(u_depth_raw, ivec3(t, layer), 0).r;
    if (z < compared(plane_depth(t, tc, p.z, g))) sum += z, n += 1.0;
  }
  if (n == 0.0) return 1.0;
  const float zo = sum / n;
  // The penumbra's half width along each axis of the map: a fitted frustum's
  // texels need not be square in the world.
  const vec2 h = clamp(vec2(penumbra_texels_at(m, world, zo, vec2(1.0, 0.0), vec2(size)),
                            penumbra_texels_at(m, world, zo, vec2(0.0, 1.0), vec2(size))),
                       vec2(0.5), u_reach);
  float lit = 0.0;
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 6; ++x) {
      const vec2 q = tc + ((vec2(x, y) + 0.5) / 6.0 * 2.0 - 1.0) * h - 0.5;
      const ivec2 b = ivec2(floor(q));
      const vec2 f = q - floor(q);
      const float l00 = texel_lit(layer, b, tc, p.z, g), l10 = texel_lit(layer, b + ivec2(1, 0), tc, p.z, g);
      const float l01 = texel_lit(layer, b + ivec2(0, 1), tc, p.z, g), l11 = texel_lit(layer, b + ivec2(1, 1), tc, p.z, g);
      lit += mix(mix(l00, l10, f.x), mix(l01, l11, f.x), f.y);
    }
  return lit / 36.0;
}
