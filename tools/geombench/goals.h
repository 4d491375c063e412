// tools/geombench/goals.h: the checks of a full geombench run, one line each,
// "MET: ..." or "MISSED: ..." (the shadow volumes near zero error, the
// silhouette maps' error against ssm's (Kenzel 2013, Sect. 5.2) and their
// cost, the warped maps on wide-depth, the bake against meshoptimizer, the soft
// techniques, the error falling as the map grows: size_law.h).
#pragma once
#include <set>
#include <string>
#include <vector>

#include "bake_throughput.h"
#include "results.h"

namespace geombench {

std::vector<std::string> goals(const std::vector<Row>& rows, const std::set<std::string>& hard,
                               const std::vector<BakeRow>& bake);

}  // namespace geombench
