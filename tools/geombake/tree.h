// geombake's input trees: what each input is named in its output
// and where its output goes under `-o DIR`.
//
//   a file named on the command line or in a --list file:
//       rel = its path if relative and inside the working directory (lexically
//       normalized: "./a/x.obj" -> "a/x.obj"), else its base name; the name
//       stored in the output is its base name alone, so the bytes do not depend
//       on how the path was typed or from where;
//   a directory D: walked recursively (symlinks followed, a directory reached
//       twice, e.g. through a symlink loop, skipped with a warning, so are
//       entries that are not regular files or cannot be read; files of other
//       formats are counted in one warning); each mesh file's rel and stored
//       name are its path relative to D; an archive found there (.pk3, .zip)
//       is baked as an ARCHIVE.pk3 argument is, each map's rel being
//       "PATH.pk3/member" and its stored name "PATH.pk3:member", PATH the
//       archive's path relative to D;
//   ARCHIVE.pk3 (a whole archive): each .bsp member's rel is its path inside
//       the archive; ARCHIVE.pk3:member one member, rel = the member's base
//       name; both store "ARCHIVE.pk3:member" with the archive's base name.
// The output of an input under -o DIR is DIR/rel.gbake: the input's extension
// is kept (pig.off -> pig.off.gbake, pig.stl -> pig.stl.gbake).
#pragma once
#include <string>
#include <vector>

namespace geombake {

struct TreeInput {
  std::string path;  // what the importer opens, as given or found
  std::string rel;   // the output's path under -o DIR, less ".gbake"
  std::string name;  // the source name stored in the output
};

// Expands `args` as above. `warnings` gets one line per skipped thing (without
// "Warning: "); `folder` is set when an argument is a directory or a whole
// archive. An archive that cannot be listed or holds no map stays one input
// (its import reports why). Returns true.
bool expand_tree_inputs(const std::vector<std::string>& args, std::vector<TreeInput>& inputs,
                        std::vector<std::string>& warnings, bool& folder);

// The mesh files and archives (.pk3, .zip) under `dir`, recursively, as paths
// relative to it, sorted.
void walk_directory(const std::string& dir, std::vector<std::string>& rel_files, std::vector<std::string>& warnings);

// True if the file name has one of the importers' extensions (any case).
bool is_mesh_name(const std::string& name);

}  // namespace geombake
