// Test fixture: a scratch folder under the system's temp directory, named for
// the test and the process (so parallel ctest runs never share one), removed
// with everything in it when the fixture goes; and a file's bytes read and
// written whole.
#pragma once
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <system_error>
#include <vector>

namespace testfs {

struct Scratch {
  std::filesystem::path dir;
  explicit Scratch(const std::string& name)
      : dir(std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(dir);
  }
  ~Scratch() {
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
  }
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;
  std::string operator/(const std::string& name) const { return (dir / name).string(); }
};

inline std::vector<unsigned char> read_all(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::vector<unsigned char>(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

inline void write_all(const std::string& path, const std::vector<unsigned char>& bytes) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

// The CLI tests' folders: one per process (PREFIX_PID under the temp
// directory, removed when the process exits) holding one folder per test
// case, emptied on each call. The first call names the process folder.
inline std::filesystem::path case_dir(const std::string& prefix, const std::string& tag) {
  struct Root {
    std::filesystem::path dir;
    ~Root() {
      std::error_code ec;
      std::filesystem::remove_all(dir, ec);
    }
  };
  static const Root root{std::filesystem::temp_directory_path() / (prefix + "_" + std::to_string(::getpid()))};
  std::filesystem::path d = root.dir / tag;
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

// Writes `text` to `path`, making its folder first.
inline void write_text(const std::filesystem::path& path, const std::string& text) {
  std::filesystem::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

}  // namespace testfs
