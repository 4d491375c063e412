// tools/geombench/size_law.h: the law "error falls as the map grows", checked
// per scene and technique over the map sizes of a run: error_visible at the
// largest size at most half its error at 512 (where both were measured), or
// at most 0.01% (near zero, where halving is noise), and
// no size worse than the next smaller one by more than 0.02 percentage points
// (0.0002 of the visible pixels). A map that grows and gets worse has a
// numerical defect (bias, precision), not aliasing.
// A soft technique is judged on its own output, the light fraction against
// the area-light reference (error_fraction): its floor is the penumbra
// estimate's, not the map's, so only the second part applies, with 0.1
// points (0.001 of the mean fraction) and 5% of the smaller map's error of
// slack for the sampling of kernels of a fixed number of taps.
#pragma once
#include <string>
#include <vector>

namespace geombench {

struct SizePoint {
  std::string scene, technique;
  int size = 0;       // 0: no map (left out)
  double error = 0;   // error_visible, or error_fraction for a soft technique
  bool soft = false;  // a soft technique (see above)
};

// One verdict line per technique over all scenes ("holds: ..." / "fails: ..."),
// naming up to a few misses; nothing for techniques measured at one size only.
std::vector<std::string> size_law_lines(const std::vector<SizePoint>& points);

}  // namespace geombench
