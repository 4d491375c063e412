#include "geombake/bake_output.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>

namespace geombake {

Written write_if_changed(const std::string& path, const std::vector<geom::BakedSection>& sections, bool force,
                         bool make_parents, std::string& error, std::vector<uint32_t>* crcs) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (make_parents) {
    const fs::path parent = fs::path(path).parent_path();
    if (!parent.empty() && !fs::is_directory(parent, ec)) {
      fs::create_directories(parent, ec);
      if (!fs::is_directory(parent)) {
        error = "cannot create the directory " + parent.string() + (ec ? ": " + ec.message() : "");
        return Written::Failed;
      }
    }
  }
  // No output there yet (or --force): the writer's own path.
  // A symlink there is replaced, never compared through (issue 15).
  if (force || !fs::is_regular_file(fs::symlink_status(path, ec)))
    return geom::write_baked(path, sections, error, crcs) ? Written::New : Written::Failed;
  // An output there: compared with what would be written, piece by piece.
  bool unchanged = false;
  if (!geom::write_baked_if_changed(path, sections, unchanged, error, crcs)) return Written::Failed;
  return unchanged ? Written::Unchanged : Written::New;
}

int terminal_width(int fd) {
  winsize ws{};
  if (::ioctl(fd, TIOCGWINSZ, &ws) == 0 && ws.ws_col > 0) return ws.ws_col;
  const char* columns = std::getenv("COLUMNS");
  const int c = columns ? std::atoi(columns) : 0;
  return c > 0 ? c : 80;
}

std::string fit_line(const std::string& text, size_t width, size_t keep) {
  if (text.size() <= width) return text;
  if (width <= keep + 3) return text.substr(0, width);
  size_t from = text.size() - (width - keep - 3);
  while (from < text.size() && (static_cast<unsigned char>(text[from]) & 0xC0) == 0x80)
    ++from;  // not inside a UTF-8 character
  return text.substr(0, keep) + "..." + text.substr(from);
}

}  // namespace geombake
