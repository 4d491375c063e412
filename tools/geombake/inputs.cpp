#include "geombake/inputs.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "geom/import.h"
#include "geombake/tree.h"

namespace geombake {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
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
      if (!geom::list_archive_members(a, ".bsp", names, error) || names.empty()) {
        inputs.push_back(a);
        continue;
      }
      for (const std::string& n : names) inputs.push_back(a + ":" + n);
      continue;
    }
    std::error_code ec;
    if (fs::is_directory(a, ec)) {  // recursive, what is skipped said (geombake/tree.h)
      std::vector<std::string> files, warnings;
      walk_directory(a, files, warnings);
      for (const std::string& w : warnings) std::fprintf(stderr, "Warning: %s\n", w.c_str());
      for (const std::string& f : files) inputs.push_back((fs::path(a) / f).string());
      continue;
    }
    inputs.push_back(a);
  }
  return true;
}

}  // namespace geombake
