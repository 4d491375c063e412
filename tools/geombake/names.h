// File names as geombake writes and checks them: JSON strings valid
// for any name, Makefile depfile escaping, and the checks of inputs against
// outputs.
#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "geom/json_quote.h"
#include "geom/report.h"

namespace geombake {

// `s` as a JSON string literal, valid whatever bytes `s` holds: libgeom's
// (geom/report.h), one escaper for the report and the file names.
using geom::json_quote;

// `path` escaped for a Makefile rule as GCC's -MD writes it, which Make and
// Ninja both read: a space or tab becomes "\ " (the backslashes before it
// doubled), '#' "\#", '$' "$$", and other backslashes stay as they are. A
// newline or carriage return cannot be written in a Make rule at all: false.
bool make_escape(const std::string& path, std::string& out);

// Why `output` cannot be written ("" if it can): an empty path, an existing
// directory, device, FIFO or socket, or a folder that does not exist.
std::string output_problem(const std::string& output);

// A JSON text made elsewhere (libgeom's reports), to be held in an
// ordered_json: parsed when nlohmann can read it, else (a name escaped as
// \udcXX, which nlohmann refuses) kept as it is, to be written as it is by dump_json.
nlohmann::ordered_json json_text(const std::string& text);

// `j` as JSON text, as j.dump(indent) writes it, but valid whatever bytes its
// strings hold (json_quote) and with json_text() values written as they are.
std::string dump_json(const nlohmann::ordered_json& j, int indent = -1);

// True when `a` and `b` name the same existing file (same device and inode).
bool same_file(const std::string& a, const std::string& b);

}  // namespace geombake
