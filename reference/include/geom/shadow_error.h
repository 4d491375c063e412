// geom/shadow_error.h (library geom::reference, reference/): a technique's
// shadow mask scored against the ray-cast reference (geom/shadow_reference.h),
// in total and per class. geombench, the viewer's HUD and the GL tests all
// report these same figures.
//
// The mask: one byte per pixel in the reference's layout (width * height, top
// row first), 0 in shadow, anything else lit (geomview --output mask: 255 lit,
// 0 shadow, 128 no geometry). Only the reference's visible pixels (it sees
// geometry) outside its one-pixel `uncertain` band are scored ("scored pixels").
//  - error_visible: the share of scored pixels whose state differs;
//  - error_boundary: the same among the scored pixels within `band_radius`
//    pixels (Chebyshev) of a true shadow boundary (a lit pixel next to a
//    shadowed one in the reference); 0 with boundary_pixels 0 where there is none;
//  - error_cast: the same among the pixels of the cast class: pixels the
//    reference shadows by ANOTHER object (ShadowClass::Cast), and lit pixels
//    whose nearest shadowed pixel in the image (8-connected distance, over
//    every pixel) is of that class: a lit receiver next to a cast shadow, where
//    an aliased or dilated shadow lands. This is the aliasing silhouette shadow
//    maps exist for;
//  - error_self: the same for the self class: pixels shadowed only by their own
//    object or facing away from the light (terminators, a caster's concavities),
//    and the lit pixels nearest to such a shadow.
// Lit pixels of an image with no shadow at all, and pixels outside a spot
// light's cone, are in neither class; they count in error_visible only. The
// two classes partition the other scored pixels: cast_pixels + self_pixels +
// (unclassed) = scored pixels.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "geom/shadow_reference.h"

namespace geom {

// Values of ShadowError::wrong, one per pixel.
enum class WrongPixel : uint8_t {
  Right = 0,      // agrees with the reference, or no geometry
  Cast = 1,       // wrong, cast class
  Self = 2,       // wrong, self class
  Other = 3,      // wrong, in neither class
  Uncertain = 4,  // differs inside the uncertain band: not scored
};

struct ShadowError {
  size_t visible_pixels = 0, wrong_visible = 0;    // scored pixels
  size_t boundary_pixels = 0, wrong_boundary = 0;  // scored pixels near a true boundary
  size_t cast_pixels = 0, wrong_cast = 0;
  size_t self_pixels = 0, wrong_self = 0;
  double error_visible = 0, error_boundary = 0, error_cast = 0, error_self = 0;  // wrong / pixels, 0 where none
  std::vector<uint8_t> wrong;        // width * height WrongPixel values, when asked for
  std::vector<uint8_t> pixel_class;  // width * height: ShadowClass of the class each pixel is scored in
};

struct ShadowErrorOptions {
  int band_radius = 3;      // error_boundary's band, pixels
  bool wrong_mask = false;  // fill ShadowError::wrong
  bool class_mask = false;  // fill ShadowError::pixel_class
};

// `mask` must hold ref.width * ref.height bytes; a shorter one is scored over
// the pixels it has (the rest count as wrong). An invalid reference (ok false)
// scores nothing (all counts 0).
ShadowError shadow_error(const std::vector<uint8_t>& mask, const ShadowReference& ref,
                         const ShadowErrorOptions& options = {});

// 1 for the pixels within `radius` (Chebyshev) of a lit reference pixel touching
// a shadowed one (error_boundary's band).
std::vector<uint8_t> shadow_boundary_band(const ShadowReference& ref, int radius);

}  // namespace geom
