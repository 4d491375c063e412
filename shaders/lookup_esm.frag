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
// Where the 2 x 2 footprint is not wholly shadowed, the nearest texel's depth
// flag compares 3e-5 * cos(incidence) of window depth nearer the light (as
// esm-exact's fallbacks, lookup_esm_exact.frag): the default scene's block
// faces are lit up to the joint under the block above, whose depth their
// texels hold within a few 1e-5. error_cast pixels at 512 / 2048 (1 frame):
// default 33 / 12 -> 3 / 0 (ssm 1 / 0), quake3 46 / 15 -> 3 / 0 (ssm 16 / 0),
// scan 1 / 0 unchanged; the same bias on every footprint leaked light at the
// bunny's contact with the ground (scan@512 36 pixels). esm-exact, the boundary on
// the true edge, has its own pass and lookup (lookup_esm_exact.frag).
vec4 face_clip(vec3 world, out int layer);  // lookup_faces.frag: the face and its clip position
uniform sampler2DArrayShadow u_shadow_map;  // comparison sampler, gathered; a layer per face
uniform sampler2DArray u_edge_map;          // r encoded distance, b edge depth, a mask
uniform vec4 u_light;                       // shade.frag's light: for the receiver's facing

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
  // The comparisons of the 2 x 2 footprint (gather order: (0,1) (1,1) (1,0) (0,0)).
  vec4 g = textureGather(u_shadow_map, vec3(p.xy, float(layer)), p.z);
  float nearest = f.y < 0.5 ? (f.x < 0.5 ? g.w : g.z) : (f.x < 0.5 ? g.x : g.y);
  // 000 Sect. 3.2: point-filtered depth and edge depth as flags, the bilinear
  // edge distance through the transfer function. ESM only adds shadow: the
  // depth test's shadow stands; a lit receiver behind the nearest texel's edge
  // depth is shadowed within 0.707 texel outside the edge.
  if (all(equal(g, vec4(0.0)))) return 0.0;
  float facing = max(dot(normalize(normal), normalize(u_light.xyz - world * u_light.w)), 0.0);
  vec4 gb = textureGather(u_shadow_map, vec3(p.xy, float(layer)), p.z - 3e-5 * facing);
  nearest = f.y < 0.5 ? (f.x < 0.5 ? gb.w : gb.z) : (f.x < 0.5 ? gb.x : gb.y);
  if (nearest < 0.5) return 0.0;
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
