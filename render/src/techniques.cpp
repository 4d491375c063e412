// techniques.cpp: the one table of techniques, generated from
// render/techniques.def (one row per technique: its --technique name, the
// caster buffers it draws, whether it has a shadow-map size, needs a point
// light or is soft, and its pass functions; one file per family: see
// render/render.h). A new technique is its file plus one row there.
#include <iterator>

#include "state.h"

namespace render {
namespace {

#define no_pass nullptr  // techniques.def's "no such function"
#define GEOM_TECHNIQUE(Id, name, esm, volume, adjacency, map, point, soft, passes, shade) \
  {Technique::Id, name, esm, volume, adjacency, map, point, soft, passes, shade},
constexpr TechniqueRow kTechniques[] = {
#include "render/techniques.def"
};
#undef GEOM_TECHNIQUE
#undef no_pass
constexpr int kCount = int(std::size(kTechniques));

}  // namespace

const TechniqueRow& technique_row(Technique t) { return kTechniques[int(t)]; }

std::vector<Technique> available_techniques() {
  std::vector<Technique> out;
  for (const TechniqueRow& row : kTechniques) out.push_back(row.id);
  return out;
}

const char* technique_name(Technique t) { return technique_row(t).name; }
bool technique_has_map(Technique t) { return technique_row(t).has_map; }
bool technique_needs_point_light(Technique t) { return technique_row(t).needs_point_light; }
bool technique_is_soft(Technique t) { return technique_row(t).soft; }

bool parse_technique(const std::string& name, Technique& out) {
  for (int i = 0; i < kCount; ++i)
    if (name == kTechniques[i].name) {
      out = kTechniques[i].id;
      return true;
    }
  return false;
}

}  // namespace render
