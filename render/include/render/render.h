// render/render.h: the GL layer the apps share (geomview, geombench, the GL
// tests): one state struct and the functions that drive it. Library
// geom::render (render/), above libgeom; OpenGL 4.5 core, shaders read at run
// time from shaders/.
//
// Layout of render/src (docs/architecture.md draws the layers):
//   gl.h, gl.cpp ........... RAII GL names, programs (cached by file list), render targets, uniforms, pass timer
//   state.h ................ the state struct, a caster's GL buffers, the per-frame context (Frame)
//   casters.cpp ............ BakedView (below) -> GL buffers; the in-process bake of a scene's casters
//   frame.cpp .............. draw_frame: state reset, casters, the technique's light passes, shading, inspection
//   techniques.cpp ......... THE table of techniques, from include/render/techniques.def (one row each)
//   shadow_map.cpp ......... ssm, pcf: the depth map with slope-scaled bias, shared by every map technique
//   focused.cpp ............ psm, lispsm, uniform: the light matrix of geom/focus.h per frame (or six faces)
//   light_fit.cpp .......... the single-map techniques' frustum fitted to the view, or six fitted faces
//   silhouette_faces.cpp ... the faces' 2D-array textures, and each face's passes
//   cube.cpp ............... cube: omnidirectional map of squared distances (Gerasimov 2004)
//   esm.cpp, edsm.cpp ...... extended shadow map (Bujnak 2004), edge distance shadow map (Kenzel 2013)
//   edge_pass.h, .cpp ...... the edge pass the silhouette maps share (esm, edsm, sssm, the edge-distance soft ones)
//   silhouette_edges.cpp ... edsm's and sssm's silhouette edges of the frame's light: a compute pass, an indirect draw
//   pass_counters.h, .cpp .. pipeline statistics per pass (PassCounters below)
//   shadow_volume.cpp ...... sv, sv-zpass, sv-zfail: stencil shadow volumes per caster (Arneson)
//   sssm.cpp ............... sssm: shadow silhouette maps (Sen et al. 2003, Kenzel 2013's baseline)
//   soft.cpp ............... edsm-soft, pcf-soft: soft shadows of a disc light (light radius; Kenzel 2013, Sect. 6)
//   esm_soft.cpp ........... esm-soft: the extended shadow map's distance under the disc (own extension of 000)
//   inspection.cpp ......... the overlay: topology problems, silhouette quads, the focus body
//   platform.cpp ........... EGL (headless) and GLFW (window) glue, render/platform.h
//
// Adding a technique is one file plus one row: write render/src/<name>.cpp
// with its light passes (`bool <name>_passes(Frame&)`: render what it needs, then
// set Frame::lookup to its shaders/lookup_<name>.frag and Frame::shadow_texture)
// and add its row to render/techniques.def, which the Technique enum below, the
// table of techniques.cpp and the declarations in state.h are generated from.
//
// A frame = the technique's light passes (shadow map, cube map, extended map,
// stencil volumes...) then one shared shading pass: the technique decides lit
// or shadowed per fragment (shaders/lookup_*.frag), shaders/shade.frag shades.
// Conventions are those of geom/scene.h (Light, Camera) and
// geom/shadow_reference.h (the mask).
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "geom/baked_reader.h"
#include "geom/esm_quads.h"
#include "geom/pipeline.h"
#include "geom/png.h"
#include "geom/scene.h"
#include "geom/shadow_volume.h"

namespace render {

// One value per row of render/techniques.def, in its order.
enum class Technique {
#define GEOM_TECHNIQUE(Id, name, esm, volume, adjacency, map, point, soft, passes, shade) Id,
#include "render/techniques.def"
#undef GEOM_TECHNIQUE
};

// The names of --technique, in order; only techniques this build renders.
std::vector<Technique> available_techniques();
const char* technique_name(Technique t);
bool parse_technique(const std::string& name, Technique& out);  // false: unknown or unavailable
bool technique_has_map(Technique t);                            // false for the shadow volumes (no shadow-map size)
bool technique_needs_point_light(Technique t);                  // cube: no directional light
bool technique_is_soft(Technique t);                            // the *-soft ones: a light fraction (light_radius)

// The silhouette buffers of one caster as the renderer takes them: borrowed
// arrays, from an in-process bake (geom/pipeline.h) or a baked container
// (geom/baked_reader.h) alike. Null arrays with `has_*` false: not baked.
struct BakedView {
  double origin[3] = {0, 0, 0};   // the caster's local frame (geom/face_planes.h)
  const float* welded = nullptr;  // xyz per welded vertex (input coordinates)
  size_t welded_count = 0;
  const uint32_t* indices = nullptr;  // 3 per triangle, into welded
  size_t triangle_count = 0;
  bool has_adjacency = true, has_esm = true, has_volume = true;
  const uint32_t* adjacency = nullptr;  // 6 per triangle, into welded
  size_t adjacency_count = 0;
  const geom::EsmQuad* esm = nullptr;
  size_t esm_count = 0;
  const float* esm_planes = nullptr;  // 4 per plane
  size_t esm_plane_count = 0;
  const geom::SvSide* sides = nullptr;
  size_t side_count = 0;
  const geom::SvCap* caps = nullptr;
  size_t cap_count = 0;
  const float* volume_planes = nullptr;
  size_t volume_plane_count = 0;
  struct LightVolume {               // the exact volume of one static light
    double light[4] = {0, 0, 0, 0};  // homogeneous, input coordinates
    const geom::SvSide* sides = nullptr;
    size_t side_count = 0;
    const geom::SvCap* caps = nullptr;
    size_t cap_count = 0;
    const float* planes = nullptr;
    size_t plane_count = 0;
  };
  std::vector<LightVolume> light_volumes;
};

// The view of an in-process bake (borrows `buffers`).
BakedView baked_view(const geom::Pipeline& buffers);
// The view of a baked container's one caster (borrows the reader's bytes);
// false with `error` when it has no usable positions and indices.
bool baked_view(const geom::baked::Reader& reader, BakedView& out, std::string& error);

// Mask: 255 lit, 0 shadow, 128 no geometry; Fraction (the soft techniques): the
// light fraction of each visible pixel, 0..255 (128 also where no geometry is).
enum class Output { Color, Mask, Fraction };

// The pipeline statistics of one pass (ARB_pipeline_statistics_query), the
// hardware-independent figures Kenzel 2013, Sect. 5.1 (figs. 5.3, 5.4) sets
// beside each algorithm's time: primitives submitted, vertex, geometry and
// fragment shader invocations, primitives out of clipping. `valid` false: the
// context has no such queries (every count 0).
struct PassCounters {
  bool valid = false;
  uint64_t primitives = 0, vs_invocations = 0, gs_invocations = 0, fs_invocations = 0, clipping_primitives = 0;
  PassCounters& operator+=(const PassCounters& o);
};

struct PassTime {
  std::string pass;
  double ms = 0;
  PassCounters counters;  // the pass's own draws
};

// A technique's shadow passes: every pass but the camera's ("depth + ambient",
// "lit shading", "shading"), the inspection overlay and the once-only bake.
bool is_shadow_pass(const std::string& pass);
// The counters of a frame's shadow passes, summed.
PassCounters shadow_counters(const std::vector<PassTime>& times);

struct FrameSettings {
  Technique technique = Technique::Ssm;
  Output output = Output::Color;
  int shadow_map_size = 1024;
  bool inspect = false;  // overlay: silhouette quads, topology problems, focus body (colour output only)
  // The light's radius for the soft techniques (edsm-soft, esm-soft, pcf-soft): a disc facing
  // the receiver, world units for a point or spot light, radians (its angular
  // radius) for a directional light. 0: a point light (their hard answer).
  float light_radius = 0;
};

struct State;  // the one state struct (GL objects, buffers, cached programs)

struct StateDeleter {
  void operator()(State* s) const;
};
using StatePtr = std::unique_ptr<State, StateDeleter>;

// Uploads the scene's triangles (the current GL context must stay current for
// the life of the state). `shader_dir` holds the shaders/ files. The casters'
// silhouette buffers (one per glTF mesh instance, or the whole scene) are baked
// in process on first use and uploaded from their BakedView.
StatePtr create_state(const geom::Scene& scene, const std::string& shader_dir, std::string& error);

// Reads a baked container (geom/baked_reader.h, written by `geombake bake`) and
// draws its buffers: the welded triangles (`positions`, `indices`) as the scene,
// its ESM quads, shadow volume and adjacency buffer as one caster, as they lie
// (its BakedView). `scene` receives the triangles and the baked static lights
// (for a default light and the reference). Every index in the file is checked
// before upload.
StatePtr create_state_baked(const void* bytes, size_t size, const std::string& shader_dir, geom::Scene& scene,
                            std::string& error);

// Renders one frame into an offscreen framebuffer of camera.width x
// camera.height and reads it back into `image` (Output::Mask: 1 channel, 255
// lit / 0 shadow / 128 background; Output::Color: 3 channels), top row first.
// `times` receives the time of each pass (GPU timer queries, or CPU wall time
// around glFinish on a software rasterizer: see timing_kind()).
bool render(State& state, const geom::Camera& camera, const geom::Light& light, const FrameSettings& settings,
            geom::PngImage& image, std::vector<PassTime>& times, std::string& error);

// Draws the frame into the default framebuffer (window mode), no read back.
bool render_to_window(State& state, const geom::Camera& camera, const geom::Light& light, const FrameSettings& settings,
                      int width, int height, std::vector<PassTime>& times, std::string& error);

// The light projection the last frame (render, render_to_window) drew, so
// that figures never carry a name that is not what was drawn: "fitted
// frustum" (ssm, pcf, esm, edsm: one map fitted to what the camera sees),
// "6 faces" (a point light among the receivers or needing a cone over 120
// degrees: six fitted 90-degree faces, "(k empty)" when some hold nothing),
// "psm near=..", "lispsm n=..", "uniform", "uniform (fallback: <why>)" (the
// focused maps: geom/focus.h's method, its warp parameter and fallback),
// "6 faces: lispsm x4 + uniform x2" (a focused map's faces and the method each
// used), "cube map", "scene frustum" (pcf-soft, edsm-soft), "shadow volumes".
// Never a comma (geombench's CSV takes it as it is).
std::string drawn_projection(const State& state);

std::string renderer_name(State& state);  // GL_RENDERER
std::string timing_kind(State& state);    // "GPU timer queries" or "wall time around glFinish (software)"

// Bounding sphere of the scene (centre xyz, radius), for default cameras and light frusta.
void scene_bounds(const State& state, float out[4]);

// The default camera: the whole bounding sphere of the scene in view (both
// fields of view), seen from the front, right and above, where "above" is
// along `up_axis` (0 x, 1 y, 2 z: Quake 3's maps and models are Z-up).
// geomview's default camera and its reset key.
geom::Camera default_view(const State& state, int width, int height, int up_axis);
// The earlier fixed view (centre lowered by a fifth of the radius, at 0.9
// radius: close, may crop): the golden images and geombench's scenes use it.
geom::Camera default_view(const State& state, int width, int height);

// What the inspection overlay draws, counted as the topology report counts it
// (geom/topology.h, per caster, summed): its legend. Bakes the casters first.
// `report`: the topology report of the whole scene after an exact weld (what
// `geombake info` prints); `drawn`: what the overlay draws, per caster (an
// edge that two casters share counts in each, never as non-manifold).
struct InspectionCounts {
  struct Kinds {
    uint64_t boundary_edges = 0, non_manifold_edges = 0, inconsistent_edges = 0, degenerate_faces = 0;
  };
  Kinds report, drawn;
  size_t casters = 0;
};
bool inspection_counts(State& state, InspectionCounts& out, std::string& error);
// The overlay's colours (RGB 0..1), for legends and the tests that count its pixels.
enum class InspectKind { Boundary, NonManifold, Inconsistent, Degenerate, Silhouette, FocusBody };
void inspection_colour(InspectKind kind, float rgb[3]);

}  // namespace render
