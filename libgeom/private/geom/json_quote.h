// geom/json_quote.h (private to the project: not installed): the library's
// JSON string quoting, for the tools' file names.
#pragma once
#include <string>

namespace geom {

// `s` as a JSON string literal, quotes included, valid whatever bytes `s`
// holds (the report's own strings, geombake's file names): valid UTF-8 is kept
// as it is ('"', '\\', \n, \r, \t and other control characters escaped);
// each byte that is not part of valid UTF-8 becomes \udcXX, the lone low
// surrogate U+DC00 + byte (PEP 383's "surrogateescape"), so no name is lost and
// none is confused with another: Python's
// json.loads(text).encode("utf-8", "surrogateescape") gives the bytes back.
std::string json_quote(const std::string& s);

}  // namespace geom
