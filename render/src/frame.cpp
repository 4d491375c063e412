// frame.cpp: one frame. The state is reset, the casters the technique draws
// are baked once, the technique's light passes run (its row in
// techniques.cpp), then the shared shading pass (scene.vert + shade.frag +
// the technique's lookup shader), then the inspection overlay.
#include <algorithm>
#include <glm/gtc/matrix_transform.hpp>

#include "state.h"

namespace render {
namespace {

void reset_state() {
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glDisable(GL_STENCIL_TEST);
  glDisable(GL_POLYGON_OFFSET_FILL);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

// The buffers a baked file lacks for this frame, as an error; "" when none.
std::string missing_buffers(const State& s, const TechniqueRow& row, const FrameSettings& fs) {
  if (!s.baked) return "";
  const bool missing = ((row.needs_esm || fs.inspect) && !s.baked_esm) || (row.needs_adjacency && !s.baked_adjacency) ||
                       (row.needs_volume && !s.baked_volume);
  if (!missing) return "";
  return std::string("the baked file has no buffers for ") + (fs.inspect ? "inspection" : row.name) +
         " (bake it with ESM quads, the shadow volume and adjacency)";
}

// The shared shading program: scene.vert + shade.frag + the technique's lookup shader.
GLuint shading_program(Frame& f) {
  State& s = f.s;
  // depth_plane.frag: the receiver-plane test (unused by some lookups; linked with every one).
  std::vector<std::string> files = {"scene.vert", "shade.frag", f.lookup, "depth_plane.frag"};
  const bool linear_depth = f.lookup.rfind("lookup_focused", 0) == 0;  // the focused maps' lookups
  if (linear_depth) files.push_back("light_depth.frag");               // their light_depth()
  if (f.faces) files.push_back("lookup_faces.frag");                   // 1 or 6 faces: face_clip()
  if (!f.lookup_extra.empty()) files.push_back(f.lookup_extra);
  GLuint p = program(s.programs, files, f.error);
  if (!p) return 0;
  const View& view = f.view;
  const FrameLight& light = f.light;
  set(p, "u_view_proj", at(f.view_proj, s.origin));
  set(p, "u_view", at(glm::lookAt(glm::dvec3(view.eye), glm::dvec3(view.target), glm::dvec3(view.up)), s.origin));
  set(p, "u_far", view.far_plane);
  set(p, "u_light", local_light(s, light));
  set(p, "u_spot_direction", glm::normalize(light.spot_direction));
  set(p, "u_spot_cos", light.spot && light.position.w != 0 ? std::cos(light.spot_angle) : -2.0f);
  set(p, "u_output", f.fs.output == Output::Mask ? 1 : f.fs.output == Output::Fraction ? 2 : 0);
  set(p, "u_ambient_only", 0);
  set(p, "u_light_matrix", at(glm::dmat4(f.light_frame.clip()), s.origin));
  if (linear_depth) set(p, "u_depth_range", light_depth_range(s, light));
  set(p, "u_shadow_map", 0);
  set(p, "u_distance_map", 1);
  set(p, "u_edge_map", 1);
  set(p, "u_depth_raw", 3);
  set(p, "u_pcf", f.t == Technique::Pcf ? 1 : 0);
  set(p, "u_esm_exact", f.t == Technique::EsmExact ? 1 : 0);
  if (f.faces) {
    set(p, "u_faces", f.faces);
    for (int i = 0; i < f.faces; ++i)
      set(p, ("u_face_matrix[" + std::to_string(i) + "]").c_str(), at(glm::dmat4(f.face_clip[i]), s.origin));
    set(p, "u_face_light", glm::vec3(glm::dvec3(glm::vec3(light.position)) - s.origin));
  }
  set(p, "u_cube_bias", 0.999f);               // rounding; the slope-scaled bias is in the map (cube.cpp)
  set(p, "u_cube_filter", 1.0f / float(f.n));  // Gerasimov 2004, Sect. 12.4: tap offsets of about one texel
  return p;
}

}  // namespace

// Draws one frame into the framebuffer `fbo` of w x h.
bool draw_frame(State& s, const View& view, const FrameLight& light, const FrameSettings& fs, GLuint fbo, int w, int h,
                PassTimer& timer, std::string& error) {
  Frame f(s, view, light, fs, timer, error);
  f.n = std::clamp(fs.shadow_map_size, 16, 16384);
  f.w = w, f.h = h, f.aspect = float(w) / float(h);
  const glm::mat4 camera_proj = glm::infinitePerspective(glm::radians(view.fovy_deg), f.aspect, view.near_plane);
  f.view_proj =
      glm::dmat4(camera_proj) * glm::lookAt(glm::dvec3(view.eye), glm::dvec3(view.target), glm::dvec3(view.up));
  reset_state();
  s.projection.clear();
  const TechniqueRow& row = technique_row(fs.technique);
  if (std::string missing = missing_buffers(s, row, fs); !missing.empty()) return error = missing, false;
  if ((row.needs_esm || row.needs_volume || row.needs_adjacency || fs.inspect) && !s.casters_built) {
    timer.begin("silhouette buffers (bake, once)");
    const bool ok = build_casters(s, error);
    timer.end();
    if (!ok) return false;
  }
  if (row.light_passes && !row.light_passes(f)) return false;
  // What was drawn: the passes name their projection; the other map techniques draw the scene-wide frustum.
  s.projection = !f.projection.empty() ? f.projection : row.has_map ? "scene frustum" : "shadow volumes";

  const GLuint p = shading_program(f);
  if (!p) return false;
  glBindTextureUnit(0, f.shadow_texture);
  glBindTextureUnit(1, f.second_texture);
  glBindTextureUnit(3, f.faces ? f.shadow_texture : 0);  // the depth maps without comparison (depth_plane.frag)
  glBindSampler(3, depth_sampler(s));
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glViewport(0, 0, w, h);
  const float grey = 0.5f;  // mask: 128 where no geometry is
  if (fs.output != Output::Color)
    glClearColor(grey, grey, grey, 1.0f);
  else
    glClearColor(0.18f, 0.2f, 0.24f, 1.0f);
  glClearDepth(1.0);
  glClearStencil(0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
  glUseProgram(p);
  const TechniqueRow& drawn = technique_row(f.t);
  if (drawn.shade) {
    if (!drawn.shade(f, p)) return false;
  } else {
    timer.begin("shading");
    draw_scene(s);
    timer.end();
  }
  glBindTextureUnit(0, 0);
  glBindTextureUnit(1, 0);
  glBindTextureUnit(3, 0);
  glBindSampler(3, 0);
  const geom::FocusMethod method = f.t == Technique::Lispsm    ? geom::FocusMethod::Lispsm
                                   : f.t == Technique::Uniform ? geom::FocusMethod::Uniform
                                                               : geom::FocusMethod::Psm;
  if (fs.inspect && fs.output == Output::Color && !inspection_pass(f, method)) return false;
  return true;
}

}  // namespace render
