// geombake volume INPUT --light X,Y,Z,W [--extrude-distance D] -o volume.obj:
// the shadow volume of one light as a triangle mesh, for debugging assets
// (geom/extrude.h finite_volume: the CPU reference of shaders/shadow_volume.vert
// with the points at infinity brought to a finite distance past the bounds).
#include <cmath>
#include <cstdio>
#include <string>

#include "cli/args.h"
#include "geom/atomic_file.h"
#include "geom/extrude.h"
#include "geom/import.h"
#include "geom/pipeline.h"
#include "geombake/command.h"
#include "geombake/flags.h"
#include "geombake/inputs.h"

namespace geombake {
namespace {

const char* kVolumeHelp =
    "usage: geombake volume INPUT --light X,Y,Z,W -o volume.obj [options]\n"
    "  Writes the exact shadow volume of one light as an OBJ triangle mesh: faces\n"
    "  oriented outward, a face repeated where its multiplicity is 2 or more (open\n"
    "  and non-manifold surfaces count both sides), extruded to a finite distance\n"
    "  past the scene's bounds instead of infinity.\n"
    "  W = 1: a point light at (X,Y,Z); W = 0: a directional light lying at infinity\n"
    "  in direction (X,Y,Z) (its rays travel along -(X,Y,Z)).\n"
    "options:\n"
    "  --light X,Y,Z,W       the light (required)\n"
    "  -o FILE               the OBJ to write (required; written atomically)\n"
    "  --extrude-distance D  how far past the bounds (default: the bounds' diagonal)\n"
    "  --no-caps             sides only (what depth-pass draws; not a closed mesh)\n"
    "  --weld-tolerance T    merge vertices closer than T (default 0: exact positions)\n"
    "  -v                    what each rule saved, on stderr\n"
    "  --coplanar-degrees D, --patch-level N, --md3-frame N, --max-triangles N,\n"
    "  --allow-outside-uris  as for `geombake info`\n";

// Wavefront OBJ text of a VolumeMesh (17 significant digits), each line of
// `comment` a "# " line first.
std::string volume_obj(const geom::VolumeMesh& mesh, const std::string& comment) {
  std::string s;
  char line[160];
  size_t start = 0;
  while (start <= comment.size()) {
    size_t end = comment.find('\n', start);
    if (end == std::string::npos) end = comment.size();
    s += "# " + comment.substr(start, end - start) + "\n";
    start = end + 1;
  }
  for (size_t i = 0; i + 2 < mesh.positions.size(); i += 3) {
    std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", mesh.positions[i], mesh.positions[i + 1],
                  mesh.positions[i + 2]);
    s += line;
  }
  for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
    std::snprintf(line, sizeof line, "f %u %u %u\n", mesh.indices[i] + 1, mesh.indices[i + 1] + 1,
                  mesh.indices[i + 2] + 1);
    s += line;
  }
  return s;
}

// --light and the numeric flags; false (after the message) when one is bad.
bool parse_volume_flags(const cli::Args& args, unsigned shared_flags, float light[4], SharedFlags& shared,
                        double& distance) {
  if (!cli::parse_floats(args.get("--light"), 4, light) || !std::isfinite(light[0]) || !std::isfinite(light[1]) ||
      !std::isfinite(light[2]) || (light[3] != 0.0f && light[3] != 1.0f) ||
      (light[3] == 0.0f && light[0] == 0.0f && light[1] == 0.0f && light[2] == 0.0f)) {
    std::fprintf(stderr,
                 "Error: --light '%s': expected X,Y,Z,W with finite numbers, W = 1 (point) or W = 0 (a non-zero "
                 "direction)\n",
                 args.get("--light").c_str());
    return false;
  }
  if (!parse_shared_flags(args, shared_flags, shared) || !parse_number(args, "--extrude-distance", distance))
    return false;
  if (args.has("--extrude-distance") && !std::isfinite(distance)) {
    std::fprintf(stderr, "Error: option --extrude-distance: not a finite number\n");
    return false;
  }
  return true;
}

// The bounds of the vertices the triangles use ({0,0,0} twice for none).
void used_bounds(const geom::Scene& scene, double lo[3], double hi[3]) {
  for (int k = 0; k < 3; ++k) lo[k] = hi[k] = 0;
  for (size_t i = 0; i < scene.indices.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const double c = scene.positions[3 * size_t(scene.indices[i]) + k];
      lo[k] = i == 0 ? c : std::min(lo[k], c);
      hi[k] = i == 0 ? c : std::max(hi[k], c);
    }
}

// The buffers of the run, the volume's OBJ text and its triangle count.
struct VolumeOut {
  geom::Pipeline pipeline;
  std::string obj;
  size_t triangles = 0;
};

// The exact volume of this light (geom/shadow_volume.h build_light_volume):
// closed components one-sided on the light's side, open ones double-sided,
// extruded `distance` past the bounds (distance < 0: the bounds' diagonal).
VolumeOut volume_of(const std::string& input, const geom::Scene& scene, const SharedFlags& shared, const float lf[4],
                    double distance, bool caps) {
  geom::PipelineOptions po = shared.pipeline;
  po.esm = false;
  po.adjacency = false;
  po.release_early = true;
  const double h[4] = {lf[0], lf[1], lf[2], lf[3]};
  geom::Light light = geom::light_from_homogeneous(h);
  light.name = "--light";
  VolumeOut out;
  geom::Pipeline& b = out.pipeline;
  b = geom::run_pipeline(geom::positions_of(scene.positions.data(), scene.vertex_count()), scene.indices.data(),
                         scene.triangle_count(), {light}, po);
  double lo[3], hi[3];
  used_bounds(scene, lo, hi);
  if (distance < 0) {
    distance = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                         (hi[2] - lo[2]) * (hi[2] - lo[2]));
    if (!(distance > 0)) distance = 1;
  }
  double homogeneous[4];
  float local[4];
  geom::light_homogeneous(light, homogeneous);
  geom::to_local_light(b.planes.origin, homogeneous, local);
  geom::ShadowVolume volume = b.lights[0].volume;
  if (!caps) volume.caps.clear();
  const geom::VolumeMesh mesh = geom::finite_volume(volume, local, lo, hi, distance);
  char comment[512];
  std::snprintf(comment, sizeof comment,
                "shadow volume of %s\nlight %.9g,%.9g,%.9g,%g (%s), extruded %.9g past the bounds\n"
                "%zu triangles, %zu vertices; faces oriented outward, repeated by multiplicity",
                input.c_str(), double(lf[0]), double(lf[1]), double(lf[2]), double(lf[3]),
                lf[3] != 0 ? "point" : "directional", distance, mesh.indices.size() / 3, mesh.positions.size() / 3);
  out.triangles = mesh.indices.size() / 3;
  out.obj = volume_obj(mesh, comment);
  return out;
}

int run_volume(const std::vector<std::string>& argv) {
  constexpr unsigned kShared = kImportFlags | kPipelineFlags;
  cli::Args args(argv, with_shared_flags({"-v", "--help", "-h", "--no-caps"}, kShared, false),
                 with_shared_flags({"-o", "--light", "--extrude-distance"}, kShared, true));
  if (args.has("--help") || args.has("-h")) {
    std::fputs(kVolumeHelp, stdout);
    return 0;
  }
  if (!args.error().empty()) {
    std::fprintf(stderr, "Error: %s\n%s", args.error().c_str(), kVolumeHelp);
    return 2;
  }
  if (args.positional().size() != 1) {
    std::fprintf(stderr, "Error: give exactly one input file\n%s", kVolumeHelp);
    return 2;
  }
  if (!args.has("--light") || !args.has("-o")) {
    std::fprintf(stderr, "Error: --light and -o are required\n%s", kVolumeHelp);
    return 2;
  }
  float lf[4];
  SharedFlags shared;
  double distance = -1;
  if (!parse_volume_flags(args, kShared, lf, shared, distance)) return 2;

  const std::string& input = args.positional()[0];
  geom::ImportResult imported = geom::import_file(input, shared.import);
  if (!imported.ok) {
    std::fprintf(stderr, "Error: %s\n", imported.error.c_str());
    return 1;
  }
  const geom::Scene& scene = imported.scene;
  for (const std::string& w : scene.warnings) std::fprintf(stderr, "Warning: %s\n", w.c_str());
  if (scene.triangle_count() == 0)
    std::fprintf(stderr, "Warning: %s: no triangles, the volume is empty\n", input.c_str());
  const VolumeOut out = volume_of(input, scene, shared, lf, distance, !args.has("--no-caps"));
  std::string error;
  if (!geom::write_file_atomically(args.get("-o"), out.obj, error)) {
    std::fprintf(stderr, "Error: %s\n", error.c_str());
    return 1;
  }
  if (args.has("-v")) {
    std::fputs(geom::silhouette_report(out.pipeline).c_str(), stderr);
    std::fprintf(stderr, "volume: %zu triangles written to %s\n", out.triangles, args.get("-o").c_str());
  }
  return 0;
}

}  // namespace

GEOMBAKE_COMMAND("volume", "write the shadow volume of one light as an OBJ mesh", run_volume);

}  // namespace geombake
