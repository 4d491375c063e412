// The checks of `geombake bake`'s outputs against its inputs and each other,
// and of the output folders, before any work (bake_plan.h): a build step must
// never write a file it reads, and must fail at once, not after an hour of
// baking, when it cannot write its report or depfile.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>
#include <utility>

#include "geom/atomic_file.h"
#include "geom/import.h"
#include "geombake/bake_plan.h"
#include "geombake/tree.h"

namespace geombake {
namespace fs = std::filesystem;
namespace {

// Where a path leads: its absolute form with every symlink and `..` resolved
// as far as it exists (weakly_canonical), and its device and inode when it
// exists (a hard link is the same file under another name).
struct Place {
  std::string path;
  std::pair<dev_t, ino_t> id{0, 0};
  bool exists = false;
};

Place place_of(const std::string& p) {
  Place place;
  std::error_code ec;
  fs::path abs = fs::absolute(p, ec);
  fs::path resolved = fs::weakly_canonical(abs, ec);
  place.path = (ec ? abs.lexically_normal() : resolved).string();
  struct stat st {};
  if (::stat(p.c_str(), &st) == 0) place.id = {st.st_dev, st.st_ino}, place.exists = true;
  return place;
}

// Every place named so far, and what names it ("the input X", "-r").
struct Places {
  std::map<std::string, std::string> by_path;
  std::map<std::pair<dev_t, ino_t>, std::string> by_id;

  // What already names `p` ("" if nothing).
  std::string find(const Place& p) const {
    auto a = by_path.find(p.path);
    if (a != by_path.end()) return a->second;
    auto b = p.exists ? by_id.find(p.id) : by_id.end();
    return b != by_id.end() ? b->second : "";
  }
  void add(const Place& p, const std::string& what) {
    by_path.emplace(p.path, what);
    if (p.exists) by_id.emplace(p.id, what);
  }
};

// The folder that a file at `path` would be created in, or its nearest
// ancestor that exists (the rest is created on the way).
std::string existing_folder(const std::string& path) {
  std::error_code ec;
  fs::path dir = fs::absolute(path, ec).parent_path();
  while (!dir.empty() && !fs::exists(dir, ec) && dir != dir.root_path()) dir = dir.parent_path();
  return dir.empty() ? "." : dir.string();
}

// A name of the importers' formats or of an archive (.pk3, .zip): an asset,
// which no output of geombake replaces even when this run does not read it.
bool is_asset_name(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return is_mesh_name(path) || ext == ".pk3" || ext == ".zip";
}

// The folder a file at `path` is created in.
std::string folder_of(const std::string& path) {
  const std::string dir = fs::path(path).parent_path().string();
  return dir.empty() ? "." : dir;
}

// Whether a file can be created in `dir`: a real probe (an unnamed O_TMPFILE,
// else a named one removed at once), which root's permissions, read-only
// mounts and virtual file systems answer truly; "" if so, else why not.
std::string folder_problem(const std::string& dir) {
  struct stat st {};
  if (::stat(dir.c_str(), &st) != 0) return std::strerror(errno);
  if (!S_ISDIR(st.st_mode)) return "not a directory";
  int fd = ::open(dir.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0600);
  if (fd >= 0) {
    ::close(fd);
    return "";
  }
  if (errno != EOPNOTSUPP && errno != EISDIR && errno != EINVAL) return std::strerror(errno);
  std::string probe = dir + "/" + geom::kTempPrefix + "probeXXXXXX";
  fd = ::mkstemp(probe.data());
  if (fd < 0) return std::strerror(errno);
  ::close(fd);
  ::unlink(probe.c_str());
  return "";
}

}  // namespace

namespace {

// The checks of bake_plan.h over `writes` (path, what it is, who writes it),
// against the files `inputs` read.
struct Write {
  std::string path, what, who;
  bool makes_folders = false;  // its missing folders are created (outputs under -o DIR)
};
// `inputs`: each input's name and the files it reads.
bool check_writes(const std::vector<std::pair<std::string, std::vector<std::string>>>& input_files,
                  const std::vector<Write>& writes) {
  Places inputs;
  for (const auto& [input, files] : input_files)
    for (const std::string& file : files)
      inputs.add(place_of(file), file == input ? "the input " + file : "a file of the input " + input);
  bool ok = true;
  Places outputs;
  std::map<std::string, std::string> folders;  // folder -> the first write in it ("-r PATH")
  for (const auto& [path, what, who, makes_folders] : writes) {
    const Place p = place_of(path);
    std::string clash = inputs.find(p);
    if (!clash.empty() && clash == "the input " + who) {
      std::fprintf(stderr, "Error: %s: is its own output (-o %s): refused (inputs are never written)\n", who.c_str(),
                   path.c_str());
      ok = false;
    } else if (!clash.empty()) {
      std::fprintf(stderr, "Error: %s: %s %s is %s: refused (inputs are never written)\n", who.c_str(), what.c_str(),
                   path.c_str(), clash.c_str());
      ok = false;
    } else if (p.exists && (is_asset_name(path) || is_asset_name(p.path))) {
      std::fprintf(stderr, "Error: %s: %s %s is a mesh file, an input to read, never written: refused\n", who.c_str(),
                   what.c_str(), path.c_str());
      ok = false;
    } else if (!(clash = outputs.find(p)).empty()) {
      std::fprintf(stderr, "Error: %s: %s %s is also %s: refused\n", who.c_str(), what.c_str(), path.c_str(),
                   clash.c_str());
      ok = false;
    }
    outputs.add(p, what + " " + path);
    folders.emplace(makes_folders ? existing_folder(path) : folder_of(path), who + ": " + what + " " + path);
  }
  for (const auto& [dir, write] : folders) {
    const std::string problem = folder_problem(dir);
    if (problem.empty()) continue;
    std::fprintf(stderr, "Error: %s: cannot write in its folder %s: %s (nothing baked)\n", write.c_str(), dir.c_str(),
                 problem.c_str());
    ok = false;
  }
  return ok;
}

}  // namespace

bool check_outputs(const std::vector<Job>& jobs, const BakeConfig& config) {
  std::vector<std::pair<std::string, std::vector<std::string>>> inputs;
  std::vector<Write> writes;
  for (const Job& job : jobs) {
    inputs.push_back({job.input, job.reads});
    if (job.error.empty()) writes.push_back({job.output, "its output", job.input, config.out_is_dir});
  }
  if (!config.report.empty()) writes.push_back({config.report, "the report", "-r"});
  if (!config.depfile.empty()) writes.push_back({config.depfile, "the depfile", "--depfile"});
  return check_writes(inputs, writes);
}

bool check_output_file(const std::vector<std::string>& inputs, const std::string& flag, const std::string& path) {
  std::vector<std::pair<std::string, std::vector<std::string>>> files;
  for (const std::string& input : inputs) files.push_back({input, geom::input_dependencies(input)});
  return check_writes(files, {{path, "the output", flag}});
}

}  // namespace geombake
