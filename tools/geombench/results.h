// tools/geombench/results.h: geombench's rows and the files made of them
// (results.csv, bake.csv, plot.svg); main.cpp writes them all or none
// (cli/output.h).
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "bake_throughput.h"

namespace geombench {

// One technique at one map size on one scene (main.cpp's header says what each figure is).
struct Row {
  std::string scene, technique, time_kind;
  std::string projection;  // what was drawn (render::drawn_projection)
  int size = 0;
  double time_ms = 0, error_visible = 0, error_boundary = 0, error_cast = 0, error_self = 0, error_fraction = -1;
  size_t visible = 0, boundary = 0, cast = 0, self = 0, triangles = 0;
  int frames = 0;
  // The shadow passes' pipeline statistics of one frame (render::shadow_counters),
  // -1 where the context has none: primitives submitted, vertex, geometry and
  // fragment shader invocations.
  long long primitives = -1, vs_invocations = -1, gs_invocations = -1, fs_invocations = -1;
};

std::string fmt(const char* format, double v);  // printf of one number

// results.csv: a header line, then a line per row.
std::string results_csv(const std::vector<Row>& rows);

// Row i's speed and peak memory against meshoptimizer's row of the same mesh.
void bake_ratios(const std::vector<BakeRow>& bake, size_t i, double& speed, double& memory);

// bake.csv: a header line, then a line per bake row with its ratios.
std::string bake_csv(const std::vector<BakeRow>& bake);

// plot.svg: error against time, a panel per scene, a line per technique, a point per map size.
std::string plot_svg(const std::vector<Row>& rows, const std::vector<std::string>& scenes,
                     const std::vector<std::string>& techniques, const std::string& kind);

}  // namespace geombench
