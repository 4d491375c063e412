// geombake bake's build-step manners: outputs rewritten only when
// their bytes change, and a progress line that fits the terminal.
#pragma once
#include <string>
#include <vector>

#include "geom/baked_writer.h"

namespace geombake {

enum class Written { New, Unchanged, Failed };

// The missing directories above `path` (an output mirrored under -o DIR),
// created before its bake streams into it (geom/bake.h); the output itself is
// written by geom::BakedFileWriter, left untouched (mtime kept, so downstream
// build steps need not rerun) when it already holds those bytes, unless
// --force. False: `error` says why ("what is wrong").
bool make_parent_directories(const std::string& path, std::string& error);

// The width of the terminal on `fd` (TIOCGWINSZ), else $COLUMNS, else 80.
int terminal_width(int fd);

// `text` cut to at most `width` characters (bytes), keeping its head up to
// `keep` characters and the end of the rest behind "...": the end of a long
// path is what tells inputs apart.
std::string fit_line(const std::string& text, size_t width, size_t keep);

}  // namespace geombake
