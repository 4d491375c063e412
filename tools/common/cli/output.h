// cli/output.h (tools/common, library geom::cli): the apps' output files,
// written as geombake writes its own (geom/atomic_file.h): each to a
// temporary file in its target's folder, every write and the close checked,
// renamed over the target at the end; a target that is a FIFO, a device or a
// folder is refused, never opened. An OutputSet is all or nothing: the files
// are staged in memory and written together at the end of the run; when one
// cannot be written, the ones this set already wrote and the folders it
// created are removed again, so a failed run leaves nothing behind.
#pragma once
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "geom/atomic_file.h"

namespace cli {

// Checks, before any work, that `path` can become a file: when it exists it is
// a regular file (or a symlink to one), and its nearest existing folder is a
// writable folder. `folder`: `path` is a folder the run writes into instead.
// False with `error` = "PATH: what is wrong".
inline bool check_output_path(const std::string& path, bool folder, std::string& error) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (path.empty()) return error = "an empty output path", false;
  const fs::file_status st = fs::status(path, ec);
  if (fs::exists(st)) {
    if (folder && !fs::is_directory(st)) return error = path + ": exists and is not a folder", false;
    if (!folder && !fs::is_regular_file(st))
      return error = path + ": not a regular file (a folder, FIFO or device): not written", false;
  }
  fs::path dir = fs::exists(st) && folder ? fs::path(path) : fs::path(path).parent_path();
  if (dir.empty()) dir = ".";
  while (!fs::exists(dir, ec) && dir.has_parent_path() && dir.parent_path() != dir) dir = dir.parent_path();
  if (!fs::is_directory(dir, ec)) return error = path + ": " + dir.string() + " is not a folder", false;
  if (::access(dir.c_str(), W_OK | X_OK) != 0)
    return error = path + ": cannot write in " + dir.string() + " (" + std::strerror(errno) + ")", false;
  return true;
}

class OutputSet {
 public:
  void add(std::string path, std::string bytes) { files_.emplace_back(std::move(path), std::move(bytes)); }
  bool empty() const { return files_.empty(); }

  // Creates the missing folders, then writes every file atomically, in order.
  // False with `error` ("PATH: cause") after removing what it wrote.
  bool commit(std::string& error) {
    namespace fs = std::filesystem;
    std::vector<fs::path> made;  // folders created, outermost first
    std::vector<std::string> written;
    auto undo = [&] {
      std::error_code ec;
      for (const std::string& p : written) fs::remove(p, ec);
      for (auto it = made.rbegin(); it != made.rend(); ++it) fs::remove(*it, ec);  // only if left empty
    };
    for (const auto& [path, bytes] : files_) {
      std::vector<fs::path> missing;
      std::error_code ec;
      for (fs::path d = fs::path(path).parent_path(); !d.empty() && !fs::exists(d, ec); d = d.parent_path()) {
        missing.push_back(d);
        if (d.parent_path() == d) break;
      }
      for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
        if (!fs::create_directory(*it, ec) || ec) {
          error = it->string() + ": cannot create the folder" + (ec ? " (" + ec.message() + ")" : std::string());
          return undo(), false;
        }
        made.push_back(*it);
      }
      std::string problem;
      if (!geom::write_file_atomically(path, bytes, problem)) {
        error = problem.rfind(path, 0) == 0 ? problem : path + ": " + problem;
        return undo(), false;
      }
      written.push_back(path);
    }
    return true;
  }

 private:
  std::vector<std::pair<std::string, std::string>> files_;
};

}  // namespace cli
