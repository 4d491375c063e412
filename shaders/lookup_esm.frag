#version 450 core
// Extended shadow map lookup (Bujnak 2004, Sect. 3.2 and 4.2), the paper's:
// the depth map and the edge depth are point filtered (the nearest texel) and
// used as flags, the encoded edge distance is interpolated bilinearly (0.75,
// the depth pass's value, where no quad wrote) and sent through the transfer
// function. ESM only adds shadow: the depth test's shadow stands; a lit
// receiver behind the nearest texel's edge depth by more than the paper's
// z-bias (2e-2 of window depth) is shadowed where the distance is under 0.5, 0.707 texel
// outside the edge, with a short ramp for shading; under 0.25 (the guard zone,
// deep inside an occluder) the depth test decides. The z-bias decides where the
// dilation applies: a receiver just behind the edge (a jenga block under the
// one above, 0.1-0.3 texel apart) is left to the depth test. geombench
// (640x480, 1 frame) error_cast at 512 / 2048 for a z-bias of 2e-3 / 5e-3 /
// 2e-2 / 5e-2: jenga 2.19 / 1.31 / 1.30 / 1.30% and 0.356 / - / 0.152 / 0.152%
// (ssm 1.68 / 0.203%), duelling@512 error_visible 1.26 / - / 0.122 / 0.122%
// (ssm 0.113%); pipes, scan and default unchanged; 1e-1 as 5e-2.
// The depth test is ssm's (depth_plane.frag: the receiver's plane against the
// nearest texel at its centre), where the paper biases the depth ("depth
// biasing and read values one shadow map unit above rendered surface",
// Sect. 6.1): a fixed bias shadowed faces steep to the light whose texels hold
// their lit neighbour (the pillars' faces of wide-depth and colonnade, wholly
// dark), and the paper leaves the bias to the implementation. geombench
// (640x480, 1 frame) error_self at 512 / 1024 / 2048 / 4096 in %, a comparison
// at the sample's depth 3e-5 * cos(incidence) nearer the light against this
// test: wide-depth 1.93 / 6.62 / 1.41 / 0.86 -> 0.15 / 0.10 / 0.024 / 0;
// colonnade 7.41 / 5.56 / 2.86 / 1.08 -> 0.090 / 0.047 / 0.016 / 0.003;
// jenga error_cast 1.30 / 0.50 / 0.15 / 0.061 -> ssm's 0.079 / 0.16 / 0.095 /
// 0.029 (its blocks lie within the z-bias of the edge above: no dilation).
// esm-exact, the boundary on the true edge, has its own pass and lookup (lookup_esm_exact.frag).
vec4 face_clip(vec3 world, out int layer);  // lookup_faces.frag: the face and its clip position
mat4 face_matrix(int layer);
vec3 receiver_slope(mat4 m, vec3 world, vec3 normal, vec2 size, vec3 depth_gradient);  // depth_plane.frag
float nearest_lit(int layer, vec3 p, vec3 g);
uniform sampler2DArray u_edge_map;          // r encoded distance, b edge depth, a mask

float shadow_visibility(vec3 world, vec3 normal) {
  int layer;
  vec4 c = face_clip(world, layer);
  if (c.w <= 0.0) return 1.0;
  vec3 p = c.xyz / c.w * 0.5 + 0.5;
  if (any(lessThan(p, vec3(0.0))) || any(greaterThan(p, vec3(1.0)))) return 1.0;
  ivec2 size = textureSize(u_edge_map, 0).xy;
  vec2 tc = p.xy * vec2(size) - 0.5;
  ivec2 i = ivec2(floor(tc));
  vec2 f = tc - floor(tc);
  // Bujnak 2004, Sect. 3.2: point-filtered depth and edge depth as flags, the
  // bilinear edge distance through the transfer function. ESM only adds
  // shadow: the depth test's shadow stands; a lit receiver behind the nearest
  // texel's edge depth is shadowed within 0.707 texel outside the edge.
  const vec3 slope = receiver_slope(face_matrix(layer), world, normal, vec2(size), vec3(0.0));
  if (nearest_lit(layer, p, slope) < 0.5) return 0.0;
  ivec2 n = clamp(i + ivec2(f.x < 0.5 ? 0 : 1, f.y < 0.5 ? 0 : 1), ivec2(0), size - 1);
  vec4 tn = texelFetch(u_edge_map, ivec3(n, layer), 0);
  if (tn.a == 0.0 || p.z <= tn.b + 2e-2) return 1.0;  // no silhouette here, or the receiver is in front of it
  float e[4];
  for (int k = 0; k < 4; ++k) {
    vec4 t = texelFetch(u_edge_map, ivec3(clamp(i + ivec2(k & 1, k >> 1), ivec2(0), size - 1), layer), 0);
    e[k] = t.a == 0.0 ? 0.75 : t.r;  // the depth pass's 0.75 where no quad wrote
  }
  float v = mix(mix(e[0], e[1], f.x), mix(e[2], e[3], f.x), f.y);
  if (v < 0.25) return 1.0;  // guard zone: deep inside an occluder the depth test decides
  return clamp((v - 0.5) / 0.08 + 0.5, 0.0, 1.0);
}
