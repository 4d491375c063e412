// techniques.cpp: the one table of techniques. A row names the technique (its
// --technique name), the caster buffers it draws, whether it has a shadow-map
// size and needs a point light, and its pass functions (one file per family:
// see render/render.h). A new technique is its file plus one row here.
#include <iterator>

#include "state.h"

namespace render {
namespace {

// clang-format off
//  id                  name        esm    volume adjacency map    point  light passes        shade
constexpr TechniqueRow kTechniques[] = {
    {Technique::Ssm,     "ssm",      false, false, false, true,  false, shadow_map_passes, nullptr},
    {Technique::Pcf,     "pcf",      false, false, false, true,  false, shadow_map_passes, nullptr},
    {Technique::Esm,     "esm",      true,  false, false, true,  false, esm_passes,        nullptr},
    {Technique::Edsm,    "edsm",     false, false, true,  true,  false, edsm_passes,       nullptr},
    {Technique::Sv,      "sv",       false, true,  false, false, false, nullptr,           volume_shade},
    {Technique::SvZPass, "sv-zpass", false, true,  false, false, false, nullptr,           volume_shade},
    {Technique::SvZFail, "sv-zfail", false, true,  false, false, false, nullptr,           volume_shade},
    {Technique::Cube,    "cube",     false, false, false, true,  true,  cube_passes,       nullptr},
    {Technique::Psm,     "psm",      false, false, false, true,  false, focused_passes,    nullptr},
    {Technique::Lispsm,  "lispsm",   false, false, false, true,  false, focused_passes,    nullptr},
    {Technique::Uniform, "uniform",  false, false, false, true,  false, focused_passes,    nullptr},
    {Technique::EsmExact, "esm-exact", true, false, false, true,  false, esm_passes,        nullptr},
    {Technique::Sssm,    "sssm",     false, false, true,  true,  false, sssm_passes,       sssm_shade},
    {Technique::EdsmSoft,"edsm-soft",false, false, true,  true,  false, edsm_soft_passes,  edsm_soft_shade},
    {Technique::PcfSoft, "pcf-soft", false, false, false, true,  false, pcf_soft_passes,   pcf_soft_shade},
};
// clang-format on
constexpr int kCount = int(std::size(kTechniques));

constexpr bool rows_in_enum_order() {
  for (int i = 0; i < kCount; ++i)
    if (int(kTechniques[i].id) != i) return false;
  return int(Technique::PcfSoft) + 1 == kCount;
}
static_assert(rows_in_enum_order(), "kTechniques: one row per Technique, in enum order");

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
bool technique_is_soft(Technique t) { return t == Technique::EdsmSoft || t == Technique::PcfSoft; }

bool parse_technique(const std::string& name, Technique& out) {
  for (int i = 0; i < kCount; ++i)
    if (name == kTechniques[i].name) {
      out = kTechniques[i].id;
      return true;
    }
  return false;
}

}  // namespace render
