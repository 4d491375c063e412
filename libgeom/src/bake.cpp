// The bake pipeline (geom/bake.h): Scene -> weld -> topology -> buffers -> sections.
#include "geom/bake.h"

#include <cmath>
#include <new>

#include "geom/weld.h"

namespace geom {
namespace {

using baked::Format;
using baked::SectionType;

// (nx, ny, nz, d) per triangle, in double so that coordinates far from the
// origin keep their planes; the offset is taken at the centroid.
std::vector<float> plane_equations(const std::vector<float>& p, const std::vector<uint32_t>& idx) {
  std::vector<float> planes(idx.size() / 3 * 4, 0.0f);
  for (size_t t = 0; t < idx.size() / 3; ++t) {
    const float* a = &p[3 * size_t(idx[3 * t])];
    const float* b = &p[3 * size_t(idx[3 * t + 1])];
    const float* c = &p[3 * size_t(idx[3 * t + 2])];
    double u[3], v[3];
    for (int k = 0; k < 3; ++k) u[k] = double(b[k]) - a[k], v[k] = double(c[k]) - a[k];
    double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(len > 0) || !std::isfinite(len)) continue;  // collapsed or collinear: (0, 0, 0, 0)
    double d = 0;
    for (int k = 0; k < 3; ++k) {
      n[k] /= len;
      d -= n[k] * ((double(a[k]) + b[k] + c[k]) / 3.0);
    }
    for (int k = 0; k < 3; ++k) planes[4 * t + k] = float(n[k]);
    planes[4 * t + 3] = float(d);
  }
  return planes;
}

}  // namespace

BakeResult bake_scene(const Scene& scene, const std::string& name, const BakeOptions& options) {
  BakeResult r;
  try {
    WeldResult w = weld(positions_of(scene.positions.data(), scene.vertex_count()), scene.indices.data(),
                        scene.indices.size(), options.weld_tolerance);
    Topology topo = build_topology(positions_of(w.positions.data(), w.vertex_count()), w.indices.data(),
                                   scene.triangle_count(), options.topology);
    r.report.file = name;
    r.report.stats = topo.stats;
    r.report.lights = scene.lights.size();
    r.report.source_counts = scene.source_counts;
    r.report.warnings = scene.warnings;

    auto& s = r.sections;
    if (options.positions)
      s.push_back(make_baked_section(SectionType::Positions, Format::F32x3, 12, "positions", w.positions));
    if (options.indices) s.push_back(make_baked_section(SectionType::Indices, Format::U32, 4, "indices", w.indices));
    if (options.weld_remap)
      s.push_back(make_baked_section(SectionType::WeldRemap, Format::U32, 4, "weld_remap", w.remap));
    if (options.face_planes)
      s.push_back(make_baked_section(SectionType::FacePlanes, Format::F32x4, 16, "face_planes",
                                     plane_equations(w.positions, w.indices)));
    if (options.topology_report) {
      std::string json = report_json(r.report);
      s.push_back(make_baked_section(SectionType::TopologyReport, Format::Utf8, 1, "topology",
                                     std::vector<char>(json.begin(), json.end())));
    }
  } catch (const std::bad_alloc&) {
    r = BakeResult();
    r.error = name + ": out of memory while baking";
    return r;
  } catch (const std::exception& e) {
    r = BakeResult();
    r.error = name + ": " + e.what();
    return r;
  }
  r.ok = true;
  return r;
}

BakeResult bake_file(const std::string& input, const std::string& output, const BakeOptions& options,
                     const ImportOptions& import_options) {
  ImportResult imported = import_file(input, import_options);
  if (!imported.ok) {
    BakeResult r;
    r.error = imported.error;
    return r;
  }
  BakeResult r = bake_scene(imported.scene, input, options);
  if (!r.ok) return r;
  std::string error;
  if (!write_baked(output, r.sections, error)) {
    r.ok = false;
    r.error = input + ": cannot write " + output + ": " + error;
  }
  return r;
}

}  // namespace geom
