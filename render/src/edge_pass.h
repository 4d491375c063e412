// edge_pass.h (private to render/): the edge pass the silhouette-map
// techniques share (esm, edsm, edsm-gs, sssm, edsm-soft): after the face's depth map, a
// second map of the same size (s.edge_map) drawn from the casters' edges with
// the depth map on texture unit 1 (read without comparison).
#pragma once
#include <string>
#include <vector>

#include "state.h"

namespace render {

// How the edge map starts and blends.
enum class EdgeTarget {
  Distance,     // edsm-soft, esm-exact: RG32F cleared to 3e38 ("no edge yet") and depth-tested
  EdgePair,     // edsm, first edge: RGBA32UI cleared to "no edge" (depth bits all ones) and depth-tested
  EdgeSecond,   // edsm, second edge (peeled): the first pass's colours kept, depth cleared and tested
  Silhouette,   // sssm: RG32UI cleared to 0 (the cell's centre) and depth-tested from 1
  ExtendedMax,  // esm: cleared to 0, no depth test, MAX blending (Bujnak 2004, Sect. 4.1)
};

// The face's depth map (slope-scaled bias `slope`, shadow_map.cpp), the edge
// map sized n x n in `format`, and the program of `files` with u_map_size and
// u_depth (unit 1) set: 0 with f.error when a pass or a shader fails.
GLuint edge_program(Frame& f, const glm::mat4& light_clip, float slope, GLenum format,
                    const std::vector<std::string>& files);

// Starts the timer `label`, makes s.edge_map the n x n target, clears it for
// `target`, binds the depth map to unit 1 and uses `p`.
void begin_edge_pass(Frame& f, GLuint p, const char* label, EdgeTarget target);
// Restores what begin_edge_pass changed and stops the timer.
void end_edge_pass(Frame& f, EdgeTarget target);
// Every caster's triangles with adjacency (geom/adjacency.h), between the two.
void draw_adjacency(const State& s);
// begin_edge_pass, draw_adjacency, end_edge_pass.
void adjacency_edge_pass(Frame& f, GLuint p, const char* label, EdgeTarget target);

// Every caster's ESM silhouette quads (esm_quad.vert with program `p`, its
// u_light_view_proj / u_light set per caster, the planes on texture unit
// `planes_unit`), between the two.
void draw_esm_quads(Frame& f, GLuint p, const glm::mat4& light_clip, int planes_unit = 2);

// silhouette_edges.cpp: edsm's and sssm's silhouette edges of the frame's
// light, once per frame before its faces (shaders/edsm_silhouettes.comp over
// every caster's records gathered into one buffer: one list of the silhouette
// records and an indirect draw; timed as "silhouette edges"); false with
// f.error when the shader fails.
bool find_silhouettes(Frame& f);
// Every caster's silhouette edges as edge quads (program `p`: edsm_quad.vert
// or sssm_quad.vert, 6 vertices per silhouette edge, each caster's light
// matrix `light_clip` in its local frame; u_list_first set), one indirect
// draw, between begin_edge_pass and end_edge_pass.
void draw_silhouette_quads(Frame& f, GLuint p, const glm::mat4& light_clip);

// esm's and esm-soft's edge pass: ESM's silhouette quads (esm_quad.vert, each
// `texels` wide beyond its edge) with the fragment shader `frag`, MAX blended
// into the edge map after the face's depth map (bias factor `slope`).
bool esm_quad_pass(Frame& f, const glm::mat4& light_clip, float slope, float texels, const std::string& frag);

}  // namespace render
