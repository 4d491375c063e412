// tools/geombench/size_law.h: the law "error falls as the map grows", checked
// per scene and technique over the map sizes of a run: error_visible at the
// largest size at most half its error at 512 (where both were measured), or
// at most 0.01% (near zero, where halving is noise), and
// no size worse than the next smaller one by more than 0.02 percentage points
// (0.0002 of the visible pixels). A map that grows and gets worse has a
// numerical defect (bias, precision), not aliasing.
#pragma once
#include <string>
#include <vector>

namespace geombench {

struct SizePoint {
  std::string scene, technique;
  int size = 0;  // 0: no map (left out)
  double error_visible = 0;
};

// One verdict line per technique over all scenes ("holds: ..." / "fails: ..."),
// naming up to a few misses; nothing for techniques measured at one size only.
std::vector<std::string> size_law_lines(const std::vector<SizePoint>& points);

}  // namespace geombench
