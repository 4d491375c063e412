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

namespace {

bool is_archive_name(const std::string& a) {
  const std::string l = lower(a);
  return l.size() > 4 && (l.compare(l.size() - 4, 4, ".pk3") == 0 || l.compare(l.size() - 4, 4, ".zip") == 0);
}

// Every .bsp map inside the archive `a`; an archive that cannot be listed, or
// holds no map, stays one input: the import says why (its `Error:`), and the
// other inputs go on.
void add_archive(const std::string& a, std::vector<std::string>& inputs) {
  std::vector<std::string> names;
  std::string error;
  if (!geom::list_archive_members(a, ".bsp", names, error) || names.empty()) {
    inputs.push_back(a);
    return;
  }
  for (const std::string& n : names) inputs.push_back(a + ":" + n);
}

}  // namespace

bool expand_inputs(const std::vector<std::string>& args, std::vector<std::string>& inputs) {
  namespace fs = std::filesystem;
  for (const std::string& a : args) {
    if (is_archive_name(a)) {
      add_archive(a, inputs);
      continue;
    }
    std::error_code ec;
    if (fs::is_directory(a, ec)) {  // recursive, what is skipped said (geombake/tree.h)
      std::vector<std::string> files, warnings;
      walk_directory(a, files, warnings);
      for (const std::string& w : warnings) std::fprintf(stderr, "Warning: %s\n", w.c_str());
      for (const std::string& f : files) {
        const std::string path = (fs::path(a) / f).string();
        if (is_archive_name(f))
          add_archive(path, inputs);  // as an archive argument
        else
          inputs.push_back(path);
      }
      continue;
    }
    inputs.push_back(a);
  }
  return true;
}

}  // namespace geombake
