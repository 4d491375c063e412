// geombake bake's build-step manners (issue 17): outputs rewritten only when
// their bytes change, and a progress line that fits the terminal.
#pragma once
#include <string>
#include <vector>

#include "geom/baked_writer.h"

namespace geombake {

enum class Written { New, Unchanged, Failed };

// Serializes `sections` and writes them atomically to `path`, unless the file
// there already holds exactly those bytes and `force` is false: then it is left
// untouched (its mtime kept, so downstream build steps need not rerun).
// `make_parents`: create the missing directories above `path` first (an output
// mirrored under -o DIR). Failed: `error` says why ("what is wrong").
// `crcs`, when given, receives each section's CRC-32C as the writer computed
// it (New or Unchanged), for the report: never computed a second time.
Written write_if_changed(const std::string& path, const std::vector<geom::BakedSection>& sections, bool force,
                         bool make_parents, std::string& error, std::vector<uint32_t>* crcs = nullptr);

// The width of the terminal on `fd` (TIOCGWINSZ), else $COLUMNS, else 80.
int terminal_width(int fd);

// `text` cut to at most `width` characters (bytes), keeping its head up to
// `keep` characters and the end of the rest behind "...": the end of a long
// path is what tells inputs apart.
std::string fit_line(const std::string& text, size_t width, size_t keep);

}  // namespace geombake
