// geom/area_reference.h (library geom::reference, reference/): the light
// fraction of each pixel under an area light, by ray casting (Embree): the
// reference of the soft techniques (edsm-soft, pcf-soft), as
// geom/shadow_reference.h is the hard techniques'.
//
// The camera, the visible point of each pixel and the two-sided facing rule are
// those of shadow_reference(). The light is a disc of radius `radius` centred on
// the light's position and facing the shaded point (a spherical light's
// outline); for a directional light `radius` is the disc's angular radius in
// radians (the sun is about 0.0047). `samples` points on the disc per pixel,
// stratified (a sqrt(samples)-square grid, jittered, mapped to the disc by
// Shirley and Chiu's concentric map); the pixel's fraction is the share of
// them whose segment to the shaded point is unblocked. A surface facing away
// from the light's centre, or outside a spot's cone, has fraction 0.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "geom/scene.h"
#include "geom/span.h"

namespace geom {

struct AreaReference {
  bool ok = false;
  std::string error;
  int width = 0, height = 0;
  std::vector<float> fraction;  // width * height, top row first: 0..1, -1 where no geometry
};

AreaReference area_light_reference(PositionSpan positions, const uint32_t* indices, size_t index_count,
                                   const Camera& camera, const Light& light, double radius, int samples,
                                   uint32_t seed = 1);

// The mean absolute difference between a rendered light fraction (8-bit, 1
// channel, 255 = 1) and the reference over the pixels where the reference sees
// geometry; `pixels` receives their count. -1 when the sizes differ.
double mean_fraction_error(const std::vector<uint8_t>& rendered, const AreaReference& ref, size_t* pixels = nullptr);

}  // namespace geom
