// Test fixture: a scratch folder under the system's temp directory, named for
// the test and the process (so parallel ctest runs never share one), removed
// with everything in it when the fixture goes.
#pragma once
#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>

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

}  // namespace testfs
