#include "geombake/tree.h"

#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <utility>

#include "geom/import.h"

namespace geombake {
namespace fs = std::filesystem;
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

bool is_archive(const std::string& arg) {
  const std::string l = lower(arg);
  return l.size() > 4 && (ends_with(l, ".pk3") || ends_with(l, ".zip"));
}

std::string base_name(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

// "dir/maps.pk3:maps/x.bsp" -> {"dir/maps.pk3", "maps/x.bsp"}; {"", ""} if not a member.
std::pair<std::string, std::string> split_member(const std::string& input) {
  const std::string l = lower(input);
  for (const char* ext : {".pk3:", ".zip:"}) {
    const size_t at = l.find(ext);
    if (at != std::string::npos) return {input.substr(0, at + 4), input.substr(at + 5)};
  }
  return {"", ""};
}

using DirId = std::pair<dev_t, ino_t>;

struct Walk {
  std::string root;
  std::vector<std::string>& files;
  std::vector<std::string>& warnings;
  std::set<DirId> seen;
  std::map<std::string, size_t> other;  // extension -> files of no mesh format skipped

  void dir(const fs::path& abs, const std::string& rel) {
    struct stat st {};
    if (::stat(abs.c_str(), &st) != 0) return;
    if (!seen.insert({st.st_dev, st.st_ino}).second) {
      warnings.push_back(abs.string() +
                         ": a directory already walked (a symlink loop or a second link to it), skipped");
      return;
    }
    std::error_code ec;
    std::vector<std::string> names;
    for (fs::directory_iterator it(abs, ec), end; !ec && it != end; it.increment(ec))
      names.push_back(it->path().filename().string());
    if (ec) {
      warnings.push_back(abs.string() + ": cannot read the directory (" + ec.message() + "), skipped");
      return;
    }
    std::sort(names.begin(), names.end());
    for (const std::string& n : names) {
      const fs::path p = abs / n;
      const std::string r = rel.empty() ? n : rel + "/" + n;
      const fs::file_status s = fs::status(p, ec);  // follows symlinks
      if (ec || s.type() == fs::file_type::not_found) {
        warnings.push_back(p.string() + ": " +
                           (fs::is_symlink(fs::symlink_status(p, ec)) ? "a broken symlink" : "cannot be read") +
                           ", skipped");
      } else if (s.type() == fs::file_type::directory) {
        dir(p, r);
      } else if (s.type() != fs::file_type::regular) {
        if (is_mesh_name(n)) warnings.push_back(p.string() + ": not a regular file, skipped");
      } else if (is_mesh_name(n) || is_archive(n)) {
        files.push_back(r);
      } else {
        const size_t dot = n.find_last_of('.');
        ++other[dot == std::string::npos || dot == 0 ? "no extension" : lower(n.substr(dot))];
      }
    }
  }
};

// Every map of the archive at `path`: rel = rel_prefix + its path inside,
// stored name = name + ":" + its path inside. An archive that cannot be listed,
// or holds no map, stays one input: its import says why (`Error: FILE:
// cause`), and the other inputs go on.
void add_archive(const std::string& path, const std::string& rel_prefix, const std::string& name,
                 std::vector<TreeInput>& inputs) {
  std::vector<std::string> members;
  std::string error;
  if (!geom::list_archive_members(path, ".bsp", members, error) || members.empty()) {
    const std::string rel = rel_prefix.empty() ? base_name(path) : rel_prefix.substr(0, rel_prefix.size() - 1);
    inputs.push_back({path, rel, name});
    return;
  }
  for (const std::string& m : members) inputs.push_back({path + ":" + m, rel_prefix + m, name + ":" + m});
}

}  // namespace

bool is_mesh_name(const std::string& name) { return geom::is_supported_name(name); }

void walk_directory(const std::string& dir, std::vector<std::string>& rel_files, std::vector<std::string>& warnings) {
  Walk w{dir, rel_files, warnings, {}, {}};
  const size_t first = rel_files.size();
  w.dir(fs::path(dir), "");
  std::sort(rel_files.begin() + std::ptrdiff_t(first), rel_files.end());
  if (w.other.empty()) return;
  size_t total = 0;
  std::string kinds;
  for (const auto& [ext, n] : w.other) {
    total += n;
    kinds += (kinds.empty() ? "" : ", ") + std::to_string(n) + " " + ext;
  }
  warnings.push_back(dir + ": " + std::to_string(total) + " files of no mesh format skipped (" + kinds + ")");
}

bool expand_tree_inputs(const std::vector<std::string>& args, std::vector<TreeInput>& inputs,
                        std::vector<std::string>& warnings, bool& folder) {
  for (const std::string& a : args) {
    if (is_archive(a)) {
      folder = true;
      add_archive(a, "", base_name(a), inputs);
      continue;
    }
    std::error_code ec;
    if (fs::is_directory(a, ec)) {
      folder = true;
      std::vector<std::string> files;
      walk_directory(a, files, warnings);
      const std::string dir = ends_with(a, "/") ? a : a + "/";
      for (const std::string& f : files) {
        if (is_archive(f))
          add_archive(dir + f, f + "/", f, inputs);  // as an ARCHIVE.pk3 argument, under its path in the tree
        else
          inputs.push_back({dir + f, f, f});
      }
      continue;
    }
    const auto [archive, member] = split_member(a);
    if (!archive.empty()) {
      inputs.push_back({a, base_name(member), base_name(archive) + ":" + member});
      continue;
    }
    const fs::path norm = fs::path(a).lexically_normal();
    const std::string n = norm.generic_string();
    const bool inside = norm.is_relative() && !n.empty() && n != "." && *norm.begin() != ".." && n.back() != '/';
    inputs.push_back({a, inside ? n : base_name(a), base_name(a)});
  }
  return true;
}

}  // namespace geombake
