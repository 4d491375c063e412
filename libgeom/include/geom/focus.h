// geom/focus.h: focus regions and light matrices for shadow maps, per frame.
//
// What it computes (Stamminger and Drettakis 2002,
// "Perspective Shadow Maps"):
//   - the focus body H = conv(R u {l}) n S n L (Sect. 4.1), where R = V n S n L
//     is the receiver region: the part of the view frustum V that lies in the
//     scene bounds S and in the light frustum L (and in the optional receiver
//     bounds). l is the light position; a directional light is a point at
//     infinity, so conv(R u {l}) is R extruded towards the light. H holds every
//     point that can cast a shadow onto a visible point of the scene: the
//     paper's conv(V u {l}) n S n L contains it, and the two agree on what
//     matters (a point of V outside S n L has no receiver on which a shadow
//     could fall). Using R instead of V is what lets an infinite far plane work.
//   - the light's kind in the camera's post-perspective space (Sect. 3): point,
//     inverted point (rays converge; the depth order along a ray is reversed)
//     or directional (a point light on the camera plane, a directional light
//     parallel to the image plane);
//   - the virtual camera shift (Sect. 4.2) that moves the camera back until H
//     lies in front of it, with the near plane pushed as far as the scene allows;
//   - the 4x4 world-to-shadow-clip matrix that maps H into the unit cube, by one
//     of three methods: PSM (the paper), LiSPSM (Wimmer et al. 2004, "Light
//     Space Perspective Shadow Maps", whose warp fades smoothly to none as the
//     light direction approaches the view direction), and uniform (the same H,
//     no warp: the ordinary focused shadow map);
//   - the six 90-degree cube-face matrices of a point light (Gerasimov
//     2004, "Omnidirectional Shadow Mapping").
//
// Conventions (all of them, for an engine):
//   - World space is right-handed; units are the caller's.
//   - Matrices are 4x4 doubles, column-major (m[col*4 + row]) like OpenGL and
//     glTF: clip = M * (x, y, z, 1).
//   - Clip space is OpenGL's: x, y, z in [-1, 1] after the divide by w ("the
//     unit cube"). The camera's projection must be an OpenGL-style perspective
//     (gluPerspective / glFrustum, off-centre allowed, infinite far allowed:
//     m[10] == -1) or orthographic projection; the view matrix maps world to an
//     eye space that looks down -z.
//   - Shadow depth: the result's matrix always gives a smaller z/w to the point
//     nearer the light along a light ray, for every light kind, inverted point
//     lights included (their depth row is already flipped). Render the shadow
//     map and compare with the ordinary depth test (GL_LESS, compare <=); an
//     engine needs no special case for LightKind::InvertedPoint.
//   - The matrix's handedness is not promised (an inverted point light flips
//     depth, LiSPSM's warp swaps axes): render shadow passes without face
//     culling, or cull by the sign the matrix gives.
//   - A point light's frustum L is the half-space beyond `light_near` along
//     `light_axis` (from the light towards the receivers' centre), cut by its
//     range; a spot light's is the square pyramid around its cone (half-angle
//     clamped to 89.9 degrees) from `light_near` to its range.
//   - The near plane of a point or spot light's map is at the nearest point
//     that must be covered (H's nearest point along the axis: a receiver, or a
//     caster between one and the light), with a floor for depth precision:
//     FocusOptions::light_near, by default 1e-3 of the farthest receiver's
//     distance along the axis. When the floor cuts something that must be
//     covered (a light inside the scene: the casters next to it; receivers
//     beside or behind it) the result says so (near_floor_cut); what lies
//     beyond the floor is in the map, whatever the light's place.
//   - Every vertex of H is mapped to w > 0 and into the unit cube; the matrix
//     is always finite, whatever the input (non-finite or absurd input gives
//     the identity and FocusFallback::InvalidInput).
//
// How H is computed (libgeom/src/focus_body.cpp): R by plane clips of V;
// conv(R u {l}) as half-spaces (R's planes that keep the light inside, and
// the planes through the light and R's silhouette, which CGAL's 2D convex
// hull of R seen from the light gives); H by clipping S with those and L's.
// H's faces are the clipped polygons when they form a clean closed surface,
// else those of a CGAL 3D convex hull of H's vertices (exact predicates);
// either way they close (V - E + F = 2).
//
// Cost (bench/bench_focus.cpp, median per light per frame on one core of the
// shared 2-core build machine): 20-41 microseconds for the matrix alone
// (FocusOptions::faces off), 27-51 with H's faces; of a PSM frame about 8
// go to R's clips, 1.5 to CGAL's silhouette hull, 8 to H's clips, 10 to the
// faces and 1.5 to the matrix. A frame whose faces need the 3D hull costs
// 60-200 more.
// Reusing the same FocusResult frame after frame keeps its vectors' capacity.
//
// No exception escapes these functions. They may run on several threads at
// once (working memory is per thread).
#pragma once
#include <cstdint>
#include <vector>

#include "geom/scene.h"
#include "geom/span.h"

namespace geom {

// The camera of a frame is geom/scene.h's CameraMatrices (camera_look_at,
// camera_from_matrices); the light is geom/scene.h's Light (glTF's
// convention: `direction` is where the light travels; `outer_cone` is a
// spot's half-angle; `range` cuts point and spot frusta).

struct FocusBox {
  double min[3];
  double max[3];
};

// A half-space: a point p is inside where n.p + d >= 0 (n unit, pointing inside).
// The element of a baked file's caster_hull section (F64x4: nx, ny, nz, d).
struct FocusPlane {
  double n[3];
  double d;
};

enum class FocusMethod : uint8_t { Psm, Lispsm, Uniform };
enum class LightKind : uint8_t { Point, InvertedPoint, Directional };

// Why the result is not the plain requested method. Ordered by severity; when
// several apply, the most severe is reported.
enum class FocusFallback : uint8_t {
  None,
  NearLimited,         // psm: the near plane could not be pushed (camera inside the scene): the warp is limited
  WarpNoGain,          // psm / lispsm: the warp (lispsm's eased too) would resolve some visible receiver more coarsely
                       // than the unwarped map (texel steps per screen step at R's samples): uniform used
  ParallelLight,       // the light is (nearly) parallel to the view direction: no warp is possible, uniform used
  LightTooClose,       // psm: the post-perspective light is too close to H for one frustum: uniform used
  OrthographicCamera,  // the camera has no perspective: psm / lispsm equal uniform, uniform used
  LightInsideView,     // a point light lies among the receivers: one map covers only the half-space facing
                       // them; render the six fitted faces (FocusResult::cube_faces; needs_cube_map is set)
  DegenerateScene,     // scene bounds of zero size on some axis: that axis is inflated to 1e-6 of the largest
                       // extent or 1e-9 of the largest coordinate, whichever is more (min > max: swapped)
  EmptyFocus,          // H is empty (nothing visible is in the scene and the light): matrix covers S n L instead
  InvalidInput,        // non-finite or absurd input: identity matrix
};

// Seconds spent in each stage of compute_focus, added up over the calls that
// are given it (FocusOptions::stage_times): for a profiler, or to see where a
// frame's microseconds go (bench/bench_focus.cpp).
struct FocusStageTimes {
  double setup = 0;      // inputs checked, S and L as half-spaces
  double receivers = 0;  // R = V n S n L: plane clips of the view frustum
  double hull = 0;       // the silhouette of R from the light (CGAL's 2D hull), or the 3D hull of R and the light
  double clip = 0;       // S cut by the half-spaces of conv(R u {l}) and L
  double faces = 0;      // H's faces for the output: the indexed polygons (a CGAL 3D hull when they do not close)
  double matrix = 0;     // the light's kind, the shift, the matrix of the method
  double cube = 0;       // point light: the six faces fitted (FocusResult::cube_faces)
};

struct FocusOptions {
  FocusMethod method = FocusMethod::Psm;
  // PSM: the virtual camera's near plane is at least this fraction of the
  // receivers' far depth (bounds the warp to far/near <= 1/ratio; 0 = none).
  double psm_min_near_ratio = 0.05;
  // LiSPSM: multiplies Wimmer's optimal warp distance n_opt (1 = optimal,
  // larger = weaker warp, towards uniform).
  double lispsm_n_scale = 1.0;
  // PSM, LiSPSM: the warp's gain over the unwarped (uniform) matrix is the
  // least, over samples of the receiver region R (its vertices, its centre,
  // the points halfway), of the ratio of their resolutions (the length in the
  // map of a step along the camera's right, up and view directions). When the
  // paper's warp has a gain under this fraction, LiSPSM's warp eases (its n
  // doubles, up to 256 times, towards uniform: Wimmer et al. 2004, Sect. 4.3)
  // until the gain is reached; when none reaches it, and for PSM (whose eased
  // warps do not tend to the unwarped map), the unwarped matrix is used
  // (FocusFallback::WarpNoGain). 0: always the paper's warp.
  // At 0.75 psm was at most uniform's error x1.1 + 2 pixels on 199 to 200 of
  // 200 random frames of the bundled scene per light type, lispsm on 197 to
  // 199, and lispsm on 188 of 200 down geombench's wide-depth alley at half
  // uniform's mean error (tests/test_gl_warp_law).
  double min_warp_gain = 0.75;
  // Optional receiver bounds: only points inside receive shadows. Tightens R and H.
  const FocusBox* receivers = nullptr;
  // H's faces (FocusResult::face_sizes / face_indices) for a wireframe. An
  // engine that needs only the matrix turns it off (a few microseconds, and
  // no 3D hull on the frames whose clipped polygons do not close cleanly).
  // Vertices are H's corners plus, at times, points in the middle of edges.
  bool faces = true;
  // Optional shadow casters: S becomes the convex hull of these points
  // intersected with the scene box (the box alone when empty); a hull of
  // more than 16 faces is bounded by the supporting planes of its 16
  // largest (of distinct directions), so that the frame's clips stay few.
  // The hull is computed every call (CGAL); static casters pass caster_hull.
  PositionSpan casters;
  // Optional, in place of `casters` (which it overrides): their convex hull
  // computed once, by focus_caster_hull or read from a baked file's
  // caster_hull section (4 doubles per plane, stride 32). S becomes the box
  // cut by these planes: the same S, the same result, without a hull per call.
  StridedSpan<FocusPlane> caster_hull;
  // Optional: each stage's time is added here (a clock read per stage).
  FocusStageTimes* stage_times = nullptr;
  // Point, spot: the floor of the light's near plane; 0 = automatic (1e-3 of
  // the farthest receiver's distance along the light's axis).
  double light_near = 0;
  // Point light: the six cube faces (FocusResult::cube_faces) are fitted when
  // the light is among the receivers (needs_cube_map), and also when H needs a
  // cone wider than this full angle (degrees) from the light, where one
  // frustum would spread its texels thin at the sides. 0: only the first case.
  double cube_cone_degrees = 0;
};

// One 90-degree face of a point light's cube (FocusResult::cube_faces), fitted
// to the part of H the face looks at: H_i = conv(R_i u {l}) n S n L_i, where
// R_i is the receiver region in the face's direction (the closed square
// pyramid from the light around the face's axis, as focus_cube_face_of
// assigns directions) and L_i that pyramid beyond the near floor. A caster
// that shadows a receiver lies on the segment from it to the light, in the
// same direction, so face i's map holds every occluder of its receivers
// (Stamminger and Drettakis 2002, Sect. 1: an omnidirectional light as
// several maps, each focused as a spot light's).
struct FocusFace {
  bool empty = true;  // no receiver is seen in this direction: nothing to render (matrices: identity)
  double near = 0;    // distances along the face's axis: H_i's nearest point (at least the floor) ...
  double far = 0;     // ... and farthest point; 0 < near < far when not empty
  // The 90-degree face of focus_cube_faces (OpenGL's cube-map orientation)
  // with this near and far: H_i maps into the unit cube.
  double matrix[16];
  // The requested method's matrix for this face (geom/focus.h's psm, lispsm or
  // uniform of H_i, the face's pyramid as the light frustum): H_i maps into the
  // unit cube, tighter than `matrix`. Depth as FocusResult::matrix.
  double focused[16];
  FocusMethod method = FocusMethod::Uniform;  // the method `focused` used (uniform where warping cannot help)
  FocusFallback fallback = FocusFallback::None;
  const char* reason = "";  // static text: why this face fell back ("" when none)
  double lispsm_n = 0;      // lispsm: the face's warp distance (0 = no warp)
  double psm_near = 0;      // psm: the face's virtual near distance
};

struct FocusResult {
  double matrix[16];                          // world -> shadow clip, column-major; maps H into the unit cube
  FocusMethod method = FocusMethod::Uniform;  // the method actually used
  FocusFallback fallback = FocusFallback::None;
  const char* reason = "";                            // static text: why the fallback was taken ("" when none)
  LightKind light_kind = LightKind::Directional;      // the light in the camera's post-perspective space
  LightKind psm_light_kind = LightKind::Directional;  // psm: the same for the shifted virtual camera
  bool needs_cube_map = false;                        // point light among the receivers (see LightInsideView)
  double camera_shift = 0;                            // psm: how far the virtual camera moved back (world units)
  double psm_near = 0;                                // psm: the virtual camera's near distance (from the shifted eye)
  double psm_far = 0;                                 // psm: its far distance
  double lispsm_n = 0;                                // lispsm: the warp frustum's near distance (0 = no warp)
  double light_axis[3] = {0, 0, 0};                   // point, spot: the axis of the light frustum L (unit)
  double light_near = 0;                              // point, spot: the map's near plane (distance along light_axis)
  // Point, spot: the near plane is at its floor and cut something that must be
  // covered (casters next to a light inside the scene, or receivers beside or
  // behind it): points nearer than light_near along light_axis are not in the map.
  bool near_floor_cut = false;
  // H, for a wireframe: xyz per vertex (world space), and convex polygons as
  // counts + indices (counter-clockwise seen from outside).
  std::vector<double> vertices;
  std::vector<uint32_t> face_sizes;
  std::vector<uint32_t> face_indices;
  size_t vertex_count() const { return vertices.size() / 3; }
  // Point light: true when the six faces below are fitted (needs_cube_map, or
  // H wider than FocusOptions::cube_cone_degrees). Order: +X, -X, +Y, -Y, +Z, -Z.
  // A point of H at least a face's near from the light along the face's axis
  // lies, in the face focus_cube_face_of gives its direction, inside both of
  // that face's matrices' unit cube; points nearer the light than the floor
  // are not in any map (near_floor_cut says so when they exist).
  bool cube = false;
  FocusFace cube_faces[6];
};

// The whole per-frame computation: H, the light's kind, the shift and the
// matrix of options.method. Always fills `out` with a finite matrix. Returns
// false only for FocusFallback::InvalidInput.
bool compute_focus(const CameraMatrices& camera, const Light& light, const FocusBox& scene, const FocusOptions& options,
                   FocusResult& out);

// The convex hull of static casters as the planes FocusOptions::caster_hull
// takes (CGAL's 3D hull, once: at load or bake time; at most 16 planes, each
// supporting the hull, see FocusOptions::casters), 4 doubles per plane
// (nx, ny, nz, d), appended to `planes` after clearing it. The same planes
// compute_focus makes from FocusOptions::casters. False (planes empty) when
// the points span no volume or one is not finite. Matches geom/bake.h's
// CasterHullFunction: `geombake bake` stores its result as caster_hull.
bool focus_caster_hull(PositionSpan casters, std::vector<double>& planes);

const char* focus_method_name(FocusMethod method);        // "psm", "lispsm", "uniform"
const char* light_kind_name(LightKind kind);              // "point", "inverted_point", "directional"
const char* focus_fallback_name(FocusFallback fallback);  // "none", "near_limited", ...

// Omnidirectional shadows (Gerasimov 2004): the six view-projection matrices of a
// cube map around `position`, 90-degree field of view, aspect 1, depth range
// [near_dist, far_dist] (0 < near < far). Face order and orientation are
// OpenGL's cube-map faces: +X, -X, +Y, -Y, +Z, -Z (GL_TEXTURE_CUBE_MAP_POSITIVE_X
// + i), so that rendering face i with matrices[i] into layer i makes
// texture(samplerCube, p - position) fetch the right texel. Column-major.
void focus_cube_faces(const double position[3], double near_dist, double far_dist, double matrices[6][16]);
// The face a direction falls on: the axis of largest magnitude, ties broken
// towards x, then y (so every direction, seams and corners included, has
// exactly one face); +0 counts as positive. -1 for the zero or a non-finite vector.
int focus_cube_face_of(const double direction[3]);

}  // namespace geom
