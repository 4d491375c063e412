#include "geombake/bake_output.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>

namespace geombake {

bool make_parent_directories(const std::string& path, std::string& error) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path parent = fs::path(path).parent_path();
  if (parent.empty() || fs::is_directory(parent, ec)) return true;
  fs::create_directories(parent, ec);
  if (fs::is_directory(parent)) return true;
  error = "cannot create the directory " + parent.string() + (ec ? ": " + ec.message() : "");
  return false;
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
