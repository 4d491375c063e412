// geom/shadow_reference.h (library geom::reference, reference/): the exact
// shadow mask of a scene, by ray casting. Links Embree; geom::geom does not.
//
// The reference every shadow technique is measured against (the viewer's GL
// tests, geombench): for each pixel a ray from the eye through the pixel centre
// finds the visible surface point P; a second ray from P to the light decides
// whether P is lit. Rays are cast with Embree (robust mode) in single precision.
//
// Conventions, the same as `geomview --output mask`:
//  - camera: geom/scene.h's Camera: right-handed look-at (eye, target, up),
//    perspective with vertical field of view `fovy_deg`, aspect width / height,
//    near and far planes as view-space depths; pixel (x, y), top row first, is
//    sampled at its centre.
//  - light: geom/scene.h's Light (glTF's convention: `direction` is where the
//    light travels). A spot light lights only the points within `outer_cone`
//    of its axis; its range and inner cone are ignored (a shadow test, not
//    shading).
//  - mask value per pixel: 255 lit, 0 in shadow, 128 where the ray meets no
//    geometry within [near, far]. Surfaces are two-sided: the side the camera
//    sees is lit only when the light is on that side of the triangle's plane
//    (a surface facing away from the light counts as shadowed).
//  - `uncertain`: 1 for pixels within one pixel (8-neighbourhood) of a pixel of
//    another mask value (shadow, silhouette and terminator boundaries), and for
//    pixels whose surface grazes the light (|cos| < 1e-4, cos the cosine between
//    the surface normal and the direction to the light: parallel and grazing
//    faces), where a one-pixel or rounding difference between a rasterizer and
//    the ray caster is legitimate. The shading (shaders/shade.frag) gives no
//    direct light below cos 1e-4, so such faces are shadowed there as a whole.
//  - the segment to a point light stops short of the light by 1e-4 of its
//    length: a light touching the geometry (at a vertex, on a face) is not
//    blocked by the surface it lies on.
//  - objects: each triangle belongs to an object (a caster). By default the
//    objects are the connected components of triangles sharing a vertex
//    position (exact float equality, so an unwelded box is still one object);
//    a caller may pass its own per-triangle ids instead. Per pixel the reference
//    says which object the visible surface lies on (`object`) and, where the
//    pixel is in shadow, which object blocks its ray to the light (`blocker`),
//    and so the pixel's class (`pixel_class`, ShadowClass): `Cast` (a receiver
//    shadowed by ANOTHER object: some other object blocks the segment, whatever
//    its own object does), `Self` (a caster in its own shadow: only its own
//    object blocks, or the surface faces away from the light: terminators),
//    `Unlit` (outside a spot light's cone), `Lit`, `None` (no geometry).
//    geom/shadow_error.h scores a technique's mask per class with it.
// Triangles are given as indices into a position span. Errors (an index out of
// range, a non-finite coordinate, an absurd image size, Embree failing) are
// returned in `error`, never thrown.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "geom/scene.h"
#include "geom/span.h"

namespace geom {

enum class ShadowClass : uint8_t { None = 0, Lit = 1, Cast = 2, Self = 3, Unlit = 4 };
constexpr uint32_t kNoObject = 0xffffffffu;

struct ShadowReference {
  bool ok = false;
  std::string error;
  int width = 0, height = 0;
  std::vector<uint8_t> mask;         // width * height, top row first: 255 / 0 / 128
  std::vector<uint8_t> uncertain;    // width * height: 1 near a true boundary, else 0
  std::vector<uint8_t> pixel_class;  // width * height: a ShadowClass per pixel
  std::vector<uint32_t> object;      // width * height: the visible surface's object, kNoObject where none
  std::vector<uint32_t> blocker;     // width * height: the object shadowing the pixel (its own one for a
                                     // surface facing away), kNoObject where lit, unlit or empty
  uint32_t object_count = 0;
};

ShadowReference shadow_reference(PositionSpan positions, const uint32_t* indices, size_t index_count,
                                 const Camera& camera, const Light& light);
// The same with the caller's object per triangle (index_count / 3 ids, any
// values; nullptr: the connected components above).
ShadowReference shadow_reference(PositionSpan positions, const uint32_t* indices, size_t index_count,
                                 const Camera& camera, const Light& light, const uint32_t* triangle_objects);

// The default objects: one id per triangle, 0..count-1, the connected components
// of triangles sharing a vertex position.
std::vector<uint32_t> triangle_components(PositionSpan positions, const uint32_t* indices, size_t index_count,
                                          uint32_t& count);

}  // namespace geom
