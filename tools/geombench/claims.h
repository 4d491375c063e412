// tools/geombench/claims.h: the published claims a full geombench run checks,
// one line each, "holds: ..." or "fails: ...", each naming the paper and
// section it comes from (the shadow volumes near zero error, the
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

std::vector<std::string> claims(const std::vector<Row>& rows, const std::set<std::string>& hard,
                                const std::vector<BakeRow>& bake);

}  // namespace geombench
