// tools/geombench/size_law.cpp: the law of size_law.h.
#include "size_law.h"

#include <algorithm>
#include <cstdio>
#include <map>

namespace geombench {

// An error this small (0.01% of the visible pixels) counts as reached zero: halving it is noise.
constexpr double kNearZero = 1e-4;

std::vector<std::string> size_law_lines(const std::vector<SizePoint>& points) {
  // technique -> scene -> size -> error
  std::map<std::string, std::map<std::string, std::map<int, double>>> by;
  std::map<std::string, bool> soft;
  for (const SizePoint& p : points)
    if (p.size > 0 && p.error >= 0) by[p.technique][p.scene][p.size] = p.error, soft[p.technique] = p.soft;
  std::vector<std::string> out;
  for (const auto& [technique, scenes] : by) {
    const bool fraction = soft[technique];
    const double step = fraction ? 0.001 : 0.0002;
    int checked = 0, held = 0;
    std::string misses;
    for (const auto& [scene, sizes] : scenes) {
      if (sizes.size() < 2) continue;
      ++checked;
      bool ok = true;
      char buf[160];
      double previous = -1;
      int previous_size = 0;
      for (const auto& [size, error] : sizes) {
        if (previous >= 0 && error > previous + step + (fraction ? 0.05 * previous : 0.0)) {
          ok = false;
          std::snprintf(buf, sizeof buf, " %s %d->%d (%.5f->%.5f)", scene.c_str(), previous_size, size, previous,
                        error);
          if (misses.size() < 300) misses += buf;
        }
        previous = error, previous_size = size;
      }
      const auto at512 = sizes.find(512);
      const int largest = sizes.rbegin()->first;
      if (!fraction && at512 != sizes.end() && largest > 512 &&
          sizes.rbegin()->second > std::max(0.5 * at512->second, kNearZero)) {
        ok = false;
        std::snprintf(buf, sizeof buf, " %s %d not half of 512 (%.5f vs %.5f)", scene.c_str(), largest,
                      sizes.rbegin()->second, at512->second);
        if (misses.size() < 300) misses += buf;
      }
      held += ok;
    }
    if (!checked) continue;
    out.push_back(std::string(held == checked ? "holds" : "fails") + ": " + technique +
                  (fraction ? " light-fraction error does not grow with the map (no step up by > 0.1 points + 5%): "
                            : " error falls as the map grows (sampling: a finer map is no worse; largest <= 512's / 2, "
                              "no step up by > 0.02 points): ") +
                  std::to_string(held) + " of " + std::to_string(checked) + " scenes" +
                  (misses.empty() ? "" : "; missed:" + misses));
  }
  return out;
}

}  // namespace geombench
