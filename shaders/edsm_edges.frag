#version 450 core
// Edge distance shadow map (Kenzel 2013), distance-map pass, per sample, with
// two edges per texel (the thesis's future work, Sect. 6.1: "more than one
// channel to store the distance to more than one edge"; Sect. 5.2's failure
// cases are where the nearest edge alone is not enough):
//  - each edge is stored as its line: the signed distance from the texel's
//    centre in texels and the line's normal angle (2 x unorm16), so the lookup
//    evaluates the line exactly at the sample instead of interpolating the
//    distance of whatever edges its four texels hold, and its light depth at
//    the sample (float bits): RGBA32UI = (line 1, depth 1, line 2, depth 2);
//  - corner priority (eq. 3.8, its spherical form near a corner vertex): the
//    distance to the edge within its span, the distance to the corner vertex
//    beyond it, combined with the edge's light depth (the edge nearer the
//    light wins: a caster's edge over a receiver's own outline) and written as
//    fragment depth; the depth test keeps the smallest where quads overlap
//    (Sect. 4.2.1);
//  - the second edge is peeled (render/src/edsm.cpp): a second pass over the
//    same quads reads the first pass's texel (u_first), drops the edge stored
//    there (and any edge on the same line at the same depth), and the depth
//    test keeps the smallest priority among the rest;
//  - occluded edges are killed against the light's depth map (Sect. 4.2.1):
//    the edge's own depth at the sample is compared with the farthest depth of
//    the 3 x 3 texels around it (a silhouette's own surface is steep there).
flat in vec3 f_line;
flat in vec4 f_segment;
flat in vec2 f_depth;
uniform float u_map_size;
uniform float u_half_width;
uniform sampler2D u_depth;            // the light's depth map, read without comparison
uniform int u_peel;                   // 0: the nearest edge; 1: the second
uniform usampler2DArray u_first;      // u_peel 1: the first pass's edges
uniform int u_layer;                  // its layer
layout(location = 0) out uvec4 o_edge;

const float kPi = 3.14159265358979;

void main() {
  vec2 p = gl_FragCoord.xy / u_map_size * 2.0 - 1.0;
  vec2 A = f_segment.xy, ab = f_segment.zw - f_segment.xy;
  float len2 = dot(ab, ab);
  float t = len2 > 0.0 ? clamp(dot(p - A, ab) / len2, 0.0, 1.0) : 0.0;
  float texels = u_map_size * 0.5;
  float priority = length(p - (A + t * ab)) * texels;
  if (priority > 2.0 * u_half_width) discard;
  float z_edge = mix(f_depth.x, f_depth.y, t) * 0.5 + 0.5;
  ivec2 c = ivec2(gl_FragCoord.xy), top = ivec2(u_map_size) - 1;
  float d = (dot(f_line.xy, p) + f_line.z) * texels;
  float angle = atan(f_line.y, f_line.x);
  uvec2 mine =
      uvec2(packUnorm2x16(vec2(clamp(d / 16.0 + 0.5, 0.0, 1.0), angle / (2.0 * kPi) + 0.5)), floatBitsToUint(z_edge));
  uvec4 first = uvec4(0u, 0xFFFFFFFFu, 0u, 0xFFFFFFFFu);
  if (u_peel == 1) {  // before the 3 x 3 reads: the first pass's own edge goes here
    first = texelFetch(u_first, ivec3(c, u_layer), 0);
    if (first.xy == mine) discard;
    vec2 l = unpackUnorm2x16(first.x);
    float d1 = (l.x - 0.5) * 16.0, a1 = (l.y - 0.5) * 2.0 * kPi;
    float da = abs(a1 - angle);
    da = min(da, 2.0 * kPi - da);
    if (abs(d1 - d) < 0.02 && da < 0.01 && abs(uintBitsToFloat(first.y) - z_edge) < 1e-4) discard;  // the same line
  }
  float z_far = 0.0;
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) z_far = max(z_far, texelFetch(u_depth, clamp(c + ivec2(x, y), ivec2(0), top), 0).r);
  if (z_edge > z_far + 1e-5) discard;
  o_edge = u_peel == 1 ? uvec4(first.xy, mine) : uvec4(mine, first.zw);
  // Priority resolved with depth: 0.85 of the edge's light depth, 0.15 of the
  // corner distance. With one edge per texel (measured on jenga at 512: distance
  // only 1.24% of visible pixels wrong, 0.5 / 0.9 / 0.95 / 0.99 of depth 1.22 /
  // 0.82 / 0.62 / 1.23%) 0.95 was best; with two (error_cast, jenga 512 / 2048,
  // wide-depth 512): 0.95 0.164 / 0.006 / 0.99%, 0.9 0.130 / 0.006 / 0.99%,
  // 0.85 0.120 / 0.006 / 0.99%, 0.8 0.119 / - / 0.99%, 0.7 0.118 / 0.006 /
  // 1.82%, 0 (the thesis's distance only) 0.117 / 0.006 / 1.82%: 0.85 keeps
  // clear of wide-depth's step between 0.7 and 0.8.
  gl_FragDepth = 0.85 * clamp(z_edge, 0.0, 1.0) + 0.15 * priority / (2.0 * u_half_width + 1.0);
}
