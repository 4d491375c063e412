#include "geombake/inputs.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "archive.h"

namespace geombake {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

bool is_mesh_file(const std::string& name) {
  const std::string n = lower(name);
  for (const char* ext : {".gltf", ".glb", ".obj", ".ply", ".off", ".stl", ".bsp", ".md3"}) {
    const std::string e = ext;
    if (n.size() >= e.size() && n.compare(n.size() - e.size(), e.size(), e) == 0) return true;
  }
  return false;
}

}  // namespace

bool expand_inputs(const std::vector<std::string>& args, std::vector<std::string>& inputs) {
  namespace fs = std::filesystem;
  for (const std::string& a : args) {
    const std::string l = lower(a);
    if ((l.size() > 4 && (l.compare(l.size() - 4, 4, ".pk3") == 0 || l.compare(l.size() - 4, 4, ".zip") == 0))) {
      std::vector<std::string> names;
      std::string error;
      // An archive that cannot be listed, or holds no map, stays one input: the
      // import says why (its `Error:`), and the other inputs go on.
      if (!geom::detail::list_archive_members(a, ".bsp", names, error) || names.empty()) {
        inputs.push_back(a);
        continue;
      }
      for (const std::string& n : names) inputs.push_back(a + ":" + n);
      continue;
    }
    std::error_code ec;
    if (fs::is_directory(a, ec)) {
      std::vector<std::string> files;
      for (const auto& entry : fs::directory_iterator(a, ec))
        if (!entry.is_directory(ec) && is_mesh_file(entry.path().filename().string()))  // FIFOs, broken links: errors
          files.push_back(entry.path().string());
      std::sort(files.begin(), files.end());
      inputs.insert(inputs.end(), files.begin(), files.end());
      continue;
    }
    inputs.push_back(a);
  }
  return true;
}

}  // namespace geombake
