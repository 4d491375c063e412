// geombake: turns triangle meshes into the static GPU buffers of silhouette-based
// shadow techniques, and reports on their topology. `geombake --help` lists the
// subcommands; each prints `Error: FILE: what is wrong` and exits non-zero on bad input.
#include <cstdio>
#include <cstring>
#include <new>
#include <string>
#include <vector>

#include "cli/args.h"
#include "geom/atomic_file.h"
#include "geom/version.h"
#include "geombake/command.h"

namespace geombake {

static std::vector<Command>& registry() {
  static std::vector<Command> r;
  return r;
}
bool register_command(const Command& command) {
  registry().push_back(command);
  return true;
}
const std::vector<Command>& commands() { return registry(); }

}  // namespace geombake

static void usage(FILE* f) {
  std::fprintf(f, "geombake %s\nusage: geombake COMMAND [options] FILE...\n       geombake --version\n\ncommands:\n",
               GEOM_VERSION);
  for (const auto& c : geombake::commands()) std::fprintf(f, "  %-10s %s\n", c.name, c.summary);
  std::fprintf(f, "\n`geombake COMMAND --help` for a command's options.\n");
}

int main(int argc, char** argv) {
  geom::remove_temp_files_on_signal();  // Ctrl-C or SIGTERM mid-write leaves no temporary file
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h")) {
    usage(argc < 2 ? stderr : stdout);
    return argc < 2 ? cli::kExitUsage : cli::kExitOk;
  }
  if (!std::strcmp(argv[1], "--version") || !std::strcmp(argv[1], "-V")) {
    std::printf("geombake %s\n", GEOM_VERSION);
    return 0;
  }
  for (const auto& c : geombake::commands()) {
    if (c.name == std::string(argv[1])) {
      std::vector<std::string> args(argv + 2, argv + argc);
      try {
        return c.run(args);
      } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "Error: out of memory\n");
        return 1;
      } catch (const std::exception& e) {
        cli::error("%s", e.what());
        return cli::kExitFailure;
      }
    }
  }
  cli::error("unknown command '%s'", argv[1]);
  usage(stderr);
  return cli::kExitUsage;
}
