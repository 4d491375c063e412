// esm.cpp: the extended shadow map (Bujnak 2004, Sect. 4.1-4.2): the depth map,
// then the caster's silhouette quads (geom/esm_quads.h, extruded in
// shaders/esm_quad.vert) write edge distance and edge depth beside it.
//  - esm, the paper's: MAX blending of the encoded distance
//    (shaders/esm_edges.frag), the lookup shaders/lookup_esm.frag (point-sampled
//    flags, 0.707-texel outward shift, guard zone);
//  - esm-exact: the same quads drawn with a depth test that resolves overlaps
//    by the edge's light depth (shaders/esm_exact_edges.frag), the boundary on
//    the true edge (shaders/lookup_esm_exact.frag).
#include <cmath>

#include "edge_pass.h"

namespace render {
namespace {
// Depth bias factor: the lookup compares a 2 x 2 footprint, taps up to one
// texel from the sample (shadow_map.cpp: k + 1 texel slopes for k texels).
constexpr float kBias = 2.0f;

// One face: the depth map, then the silhouette quads beside it.
bool esm_face(Frame& f, const glm::mat4& light_clip) {
  return esm_quad_pass(f, light_clip, kBias, 2.5f, "esm_edges.frag");  // quad reach beyond the edge: 2.5 texels
}

// esm-exact's quads: 4 texels out along q, so the occluder's side (half as far,
// at worst 70.7% of it across the map: 000 Fig. 5) reaches 1.41 texels, the
// farthest a 2 x 2 footprint's texel lies from an edge crossing it; written
// within kReach texels of the edge segment. Measured (geombench jenga,
// error_cast at 512 / 1024 / 2048, 1 frame): reach 2: 0.302 / 0.118 / 0.028%,
// reach 3: 0.230 / 0.111 / 0.028%, reach 1.6: 0.334% at 512; the occluder's
// side lengthened to 2 texels (reach 2; a uniform of esm_quad.vert, not kept): 0.765% at 512, 3 texels out and 1.5
// in: 0.765%, 6 out and 1.5 in (reach 3): 0.711%, 4 out and 1.5 in (reach 3):
// 0.169 / 0.085 / 0.034%. Reach 3 was better on geombench's jenga but worse on
// the GL tests' jenga tower (test_gl_edge_shadow_maps.cpp; 30 / 10 pixels wrong at 128 / 256 against
// 23 / 6 with reach 2): 2 kept.
constexpr float kExactTexels = 4.0f, kReach = 2.0f;

bool esm_exact_face(Frame& f, const glm::mat4& light_clip) {
  GLuint p = edge_program(f, light_clip, kMapSlope, GL_RG32F, {"esm_quad.vert", "esm_exact_edges.frag"});
  if (!p) return false;
  set(p, "u_extrude_scale", 2.0f * kExactTexels / (float(f.n) * projection_scale(light_clip)));
  set(p, "u_planes", 2);
  set(p, "u_reach", kReach);
  begin_edge_pass(f, p, "extended map quads", EdgeTarget::Distance);
  draw_esm_quads(f, p, light_clip);
  end_edge_pass(f, EdgeTarget::Distance);
  return true;
}

}  // namespace

bool esm_passes(Frame& f) {
  if (f.t == Technique::EsmExact) {
    if (!silhouette_faces(f, esm_exact_face, GL_RG32F)) return false;
    f.lookup = "lookup_esm_exact.frag";
    return true;
  }
  if (!silhouette_faces(f, esm_face, GL_RGBA32F)) return false;
  f.lookup = "lookup_esm.frag";
  return true;
}

}  // namespace render
