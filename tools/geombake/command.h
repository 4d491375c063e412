// geombake subcommands register themselves here; main.cpp dispatches.
#pragma once
#include <string>
#include <vector>

namespace geombake {

// argv holds the subcommand's arguments (without "geombake" and the command name).
using CommandFn = int (*)(const std::vector<std::string>& args);

struct Command {
  const char* name;
  const char* summary;  // one line for `geombake --help`
  CommandFn run;
};

bool register_command(const Command& command);
const std::vector<Command>& commands();

}  // namespace geombake

// Use at namespace scope in the same namespace as FN (e.g. inside namespace geombake { namespace { ... } }):
//   GEOMBAKE_COMMAND("info", "one-line summary", run_info);
#define GEOMBAKE_COMMAND(NAME, SUMMARY, FN) \
  static const bool geombake_registered_##FN = ::geombake::register_command({NAME, SUMMARY, FN})
