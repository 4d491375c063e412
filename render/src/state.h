// state.h (private to render/): the one state struct, a caster's GL buffers,
// the per-frame context every technique's passes take, and the functions the
// technique files share. See render/render.h for the file map.
#pragma once
#include <string>
#include <vector>

#include "geom/focus.h"
#include "gl.h"

namespace render {

// The static buffers of one caster (geom/pipeline.h), in its local frame,
// uploaded from a BakedView (casters.cpp).
struct Caster {
  glm::vec3 lo{0}, hi{0};  // world bounding box
  glm::dvec3 origin{0};    // local frame origin (geom/face_planes.h)
  // Edge distance shadow map: welded positions (world) + GL_TRIANGLES_ADJACENCY indices.
  Buffer welded, adjacency;
  VertexArray adjacency_vao;
  GLsizei adjacency_count = 0;
  // Extended shadow map quads and their planes (texture buffer).
  Buffer esm_records, esm_plane_buffer;
  Texture esm_planes;
  VertexArray esm_vao;
  GLsizei esm_count = 0;
  // Shadow volume sides, caps and planes.
  Buffer sv_sides, sv_caps, sv_plane_buffer;
  Texture sv_planes;
  VertexArray sides_vao, caps_vao;
  GLsizei side_count = 0, cap_count = 0;
  // Exact volumes of the static lights (geom/shadow_volume.h build_light_volume):
  // used instead of the generic one when the frame's light is one of them.
  struct LightVolume {
    glm::dvec4 light{0};  // input coordinates
    Buffer sides, caps, plane_buffer;
    Texture planes;
    VertexArray sides_vao, caps_vao;
    GLsizei side_count = 0, cap_count = 0;
  };
  std::vector<LightVolume> light_volumes;
  // Inspection lines (world): boundary, non-manifold, inconsistent edges, then degenerate faces' edges.
  Buffer lines;
  VertexArray lines_vao;
  GLsizei line_first[4] = {0, 0, 0, 0}, line_count[4] = {0, 0, 0, 0};
};

struct State {
  Programs programs;
  bool gpu_timers = false;
  std::string renderer;
  // Scene: non-indexed triangles, position + face normal per vertex (world space).
  Buffer scene_vbo;
  VertexArray scene_vao;
  GLsizei scene_vertices = 0;
  glm::vec4 bounds{0, 0, 0, 1};
  glm::vec3 scene_lo{-1}, scene_hi{1};  // bounding box
  glm::dvec3 origin{0};  // the scene buffer's local frame (its box centre): far coordinates keep float precision
  // Render targets, re-created when their size changes.
  Target camera, shadow_map, cube, edge_map;
  // The edge map's clear value as a texture of the same size and format
  // (edge_pass.cpp copies it over the edge map), re-made when either changes.
  Texture edge_blank;
  int edge_blank_n = 0;
  GLenum edge_blank_format = 0;
  Sampler depth_sampler;  // reads a depth texture without comparison
  // esm / edsm: the depth and edge maps of their faces (1 fitted frustum or 6
  // cube faces) as 2D arrays (silhouette_faces.cpp).
  Texture face_depth, face_edges;
  // edsm, sssm: the frame's silhouette edges (silhouette_edges.cpp): the list
  // of record indices, the silhouette counts per run, an indirect draw per chunk.
  Buffer silhouette_lists, silhouette_groups, silhouette_commands;
  size_t silhouette_list_size = 0, silhouette_group_size = 0, silhouette_command_size = 0;
  // Every caster's ESM records and planes gathered into one buffer each, so
  // that one dispatch finds and one draw per pass draws every caster's edges:
  // the caster of each record, each caster's first plane, its light (per
  // frame) and matrix (per face), and the key of the casters gathered.
  Buffer merged_records, merged_plane_buffer, record_casters, caster_lights, caster_matrices;
  Texture merged_planes;
  VertexArray no_attributes;  // the edge quads read no vertex attribute
  std::vector<GLuint> caster_plane_first;
  size_t merged_count = 0, merged_key[3] = {0, 0, 0};
  int face_n = 0, face_layers = 0;
  GLenum face_format = 0;
  // Silhouette buffers per caster, baked on first use.
  geom::Scene scene;  // positions, indices, sources: the casters are baked from it
  bool casters_built = false;
  std::vector<Caster> casters;
  // A baked file's casters come with it; the buffers it lacks are named here.
  bool baked = false, baked_esm = true, baked_volume = true, baked_adjacency = true;
  std::string projection;  // what the last frame's light passes drew (drawn_projection)
};

// The frame's light in the form the passes use (floats, as the shaders take them).
struct FrameLight {
  glm::vec4 position{0, 10, 0, 1};  // homogeneous (geom::light_homogeneous)
  bool spot = false;
  glm::vec3 spot_direction{0, -1, 0};  // where the spot shines
  float spot_angle = 0;                // radians, axis to cone edge
};
FrameLight frame_light(const geom::Light& light);

// The frame's camera with glm vectors.
struct View {
  glm::vec3 eye, target, up;
  float fovy_deg, near_plane, far_plane;
};

// A light's view and projection (the single shadow map's, or a focused matrix).
struct LightFrame {
  glm::mat4 proj{1}, view{1};
  glm::mat4 clip() const { return proj * view; }
};

// Everything one frame's passes read, and what the light passes leave for the
// shading pass.
struct Frame {
  Frame(State& state, const View& v, const FrameLight& l, const FrameSettings& settings, PassTimer& pass_timer,
        std::string& error_out)
      : s(state), view(v), light(l), fs(settings), t(settings.technique), timer(pass_timer), error(error_out) {}
  State& s;
  const View& view;
  const FrameLight& light;
  const FrameSettings& fs;
  Technique t;  // the technique drawn
  int n = 0;    // shadow-map size
  int w = 0, h = 0;
  float aspect = 1;
  glm::dmat4 view_proj{1};
  PassTimer& timer;
  std::string& error;
  // Set by the technique's light passes:
  std::string lookup = "lookup_none.frag";  // its shaders/lookup_*.frag
  std::string lookup_extra;                 // a shader file the lookup links with ("": none)
  GLuint shadow_texture = 0, second_texture = 0;
  LightFrame light_frame;  // u_light_matrix
  bool focused = false;    // psm, lispsm, uniform (even when drawn as cube)
  int faces = 0;           // 1 fitted frustum or 6 faces (shaders/lookup_faces.frag); 0: u_light_matrix alone
  glm::mat4 face_clip[6];  // their light clip matrices (world); an empty face's is zero
  // The projection drawn, as render/render.h's drawn_projection reports it
  // ("fitted frustum", "6 faces", "lispsm n=2.1", "uniform (fallback: ...)").
  std::string projection;
};

// The technique table (techniques.cpp, from render/techniques.def): one row per Technique, in enum order.
struct TechniqueRow {
  Technique id;
  const char* name;
  bool needs_esm, needs_volume, needs_adjacency;  // the caster buffers it draws
  bool has_map;
  bool needs_point_light;
  bool soft;                       // a light fraction under a disc light
  bool (*light_passes)(Frame& f);  // the passes before shading; sets lookup and textures
  // The shading (null: one pass of the shading program); `p` is the program.
  bool (*shade)(Frame& f, GLuint p);
};
const TechniqueRow& technique_row(Technique t);

// The light passes and shading functions the rows of render/techniques.def
// name, one family per file (see its rows); `no_pass` (never defined) stands for
// "none" and is the null pointer in the table.
#define GEOM_TECHNIQUE(Id, name, esm, volume, adjacency, map, point, soft, passes, shade) \
  bool passes(Frame& f);                                                                  \
  bool shade(Frame& f, GLuint p);
#include "render/techniques.def"
#undef GEOM_TECHNIQUE
bool inspection_pass(Frame& f, geom::FocusMethod method);  // inspection.cpp

// soft.cpp, shared by the soft techniques (FrameSettings::light_radius): the
// widest penumbra's half width in texels over the scene's bounding sphere (the
// edge quads' reach), on the scene-wide light frame or on a light clip matrix
// of projection scale `projection` (projection_scale), at most `cap` texels
// (the edge quads' 32 unless given); soft_shade (one pass with
// soft_light.frag's uniforms) is named in techniques.def.
float soft_reach(const Frame& f);
float soft_reach(const Frame& f, float projection);
float soft_reach(const Frame& f, float projection, float cap);

// Shared by the map techniques (shadow_map.cpp).
LightFrame light_frame(const State& s, const FrameLight& light);
// The depth map from the light into s.shadow_map, with a slope-scaled bias of
// factor `slope` (0: none); `linear_light`: the linear light depth of the
// focused maps, its bias computed in it.
bool depth_map_pass(Frame& f, const glm::mat4& light_clip, float slope, bool linear_light,
                    const char* pass = "depth map");  // the timer's name of the pass
// Sets the depth map's filter for the technique and makes it the shadow texture.
void finish_map(Frame& f);
void ensure_edge_map(State& s, int n, GLenum format);
GLuint depth_sampler(State& s);
// The light as shade.frag's u_light: homogeneous, in the scene buffer's local frame.
glm::vec4 local_light(const State& s, const FrameLight& light);
// u_depth_range of shaders/light_depth.frag.
glm::vec2 light_depth_range(const State& s, const FrameLight& light);

// light_fit.cpp: the single-map techniques' light frames fitted to what the
// camera sees: 1 (f.light_frame: the uniform focused matrix of H) or 6 (a
// point light among the receivers or needing a cone over kMaxConeDeg:
// f.face_clip, the 90-degree faces with their fitted near and far, widened
// by `guard` texels; an empty face's matrix is zero). Sets f.projection.
// glPolygonOffset's factor of the depth maps that ssm, pcf, edsm and esm-exact
// share: the edge passes need the offset to tell a silhouette from the surface
// behind it, and with one map edsm's and esm-exact's fallback is exactly ssm's
// test (edsm.cpp passes the same 2; with six faces they draw ssm's fitted
// faces, silhouette_faces.cpp). The lookups add the receiver-plane test.
constexpr float kMapSlope = 2.0f;
constexpr double kMaxConeDeg = 120;  // full angle of the widest single frustum worth drawing
int fit_light_frames(Frame& f, float guard);
glm::mat4 to_mat4(const double m[16]);  // geom/focus.h's column-major doubles
// silhouette_faces.cpp: esm and edsm drawn with the fitted frustum or as six
// faces: `draw_face` draws the depth map and the edge map of one light
// clip matrix into s.shadow_map / s.edge_map; the faces are gathered into
// s.face_depth / s.face_edges (2D arrays), which become the frame's textures.
bool silhouette_faces(Frame& f, bool (*draw_face)(Frame& f, const glm::mat4& light_clip), GLenum edge_format);
// The depth maps of the first `faces` (1 or 6) of f.face_clip (zero: skipped;
// `slope` and `linear_light` as depth_map_pass) into the layers of
// s.face_depth, which becomes the shadow texture; their lookups test the
// receiver's plane (shaders/depth_plane.frag).
bool depth_faces(Frame& f, int faces, float slope, bool linear_light);
float face_guard();  // the guard band of the 90-degree faces, in texels
// Clip x (or y, the smaller) per unit of length at w = 1 of a light's clip matrix.
float projection_scale(const glm::mat4& clip);

// focused.cpp: the focused light matrix of psm / lispsm / uniform, and H
// (`faces`: H's polygons; `cube_cone`: geom/focus.h FocusOptions::cube_cone_degrees).
geom::FocusResult focus(const State& s, const View& view, float aspect, const FrameLight& light,
                        geom::FocusMethod method, bool faces = false, double cube_cone = 0);
// The projection a focused matrix drew, for drawn_projection: "lispsm n=3.2",
// "psm near=0.8", "uniform (fallback: warp_no_gain)".
std::string describe_focus(geom::FocusMethod requested, const geom::FocusResult& r);

// casters.cpp
bool build_casters(State& s, std::string& error);  // bakes and uploads every caster, once
bool upload_caster(State& s, const BakedView& src, std::string& error);
glm::vec4 local_light(const Caster& c, const glm::dvec4& light);                   // in a caster's local frame
const Caster::LightVolume* light_volume(const Caster& c, const glm::vec4& light);  // exact volume, if any

void draw_scene(const State& s);

// frame.cpp: one frame into the framebuffer `fbo` of w x h.
bool draw_frame(State& s, const View& view, const FrameLight& light, const FrameSettings& fs, GLuint fbo, int w, int h,
                PassTimer& timer, std::string& error);

}  // namespace render
