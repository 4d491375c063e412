#!/usr/bin/env bash
# tests/install/run.sh BUILD_DIR SOURCE_DIR: the relocatable install, by
# component, run by ctest (test install_consumer). Installs BUILD_DIR with
# `cmake --install` to a temporary prefix and checks:
#  - the installed CMake config and geom.pc hold no absolute path (of this
#    machine's libraries, the source or the build tree);
#  - no installed archive defines a global stbi_* symbol (an engine's own
#    stb_image links beside geom), and geom::core's archive holds no CGAL code;
#  - geom::core's and geom::reader's link interfaces name no third-party library;
# then, from the prefix and again after moving it elsewhere, builds and runs a
# consumer (tests/install/consumer) of each component through
# find_package(geom COMPONENTS <it>) with every package the component does not
# need disabled (so the config must not look for them), the whole package
# through find_package(geom) and pkg-config, the reader's consumer with the
# include path alone, and the samples of examples/; a library bake_file and the
# installed geombake's bake of one mesh must be byte-identical.
set -euo pipefail
build=$(cd "$1" && pwd) src=$(cd "$2" && pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/geom_install.XXXXXX")
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
mesh="$src/tests/data/draco/Box/glTF_Binary/Box.glb"
[ -f "$mesh" ] || fail "$mesh is missing"

cmake --install "$build" --prefix "$work/prefix" >/dev/null
libdir=$(cd "$work/prefix" && ls -d lib*/pkgconfig | head -1 | xargs dirname)
cmakedir="$work/prefix/$libdir/cmake/geom"
[ -f "$cmakedir/geomConfig.cmake" ] || fail "no geomConfig.cmake under $libdir/cmake/geom"
[ -f "$work/prefix/$libdir/pkgconfig/geom.pc" ] || fail "no geom.pc"
[ -f "$work/prefix/include/geom/version.h" ] || fail "no geom/version.h installed"
grep -q '#define GEOM_VERSION "' "$work/prefix/include/geom/version.h" || fail "geom/version.h has no GEOM_VERSION"
for bad in "$src" "$build" "$work" /usr/lib /usr/local; do
  if grep -rlF "$bad" "$cmakedir" "$work/prefix/$libdir/pkgconfig/geom.pc"; then
    fail "an absolute path ($bad) in the installed package files above"
  fi
done
for private in atomic_file.h crc32c.h json_quote.h process.h; do
  [ ! -e "$work/prefix/include/geom/$private" ] || fail "the private header geom/$private is installed"
done

# Symbols: no global stbi_* anywhere, no CGAL (GPL) in geom::core.
archives=$(find "$work/prefix" -name '*.a')
[ -n "$archives" ] || fail "no archive installed"
for a in $archives; do
  if nm -g --defined-only "$a" 2>/dev/null | awk '{print $NF}' | grep -E '^stbi'; then
    fail "$(basename "$a") defines the global stb symbols above"
  fi
done
core_a=$(find "$work/prefix" -name libgeom_core.a)
[ -n "$core_a" ] || fail "no libgeom_core.a installed"
if nm -C "$core_a" | grep -m3 -E 'CGAL|OpenMesh|draco|tinygltf|zip_'; then
  fail "libgeom_core.a holds third-party code (above)"
fi
# The link interfaces, as exported: core and reader name geom targets only.
for c in core reader; do
  f="$cmakedir/geom_${c}Targets.cmake"
  [ -f "$f" ] || fail "no geom_${c}Targets.cmake"
  links=$( (grep -o 'INTERFACE_LINK_LIBRARIES "[^"]*"' "$f" || true) | sed 's/^INTERFACE_LINK_LIBRARIES "//; s/"$//' | tr ';' '\n')
  for l in $links; do
    [[ $l == geom::* || $l == '\$<LINK_ONLY:geom::'* ]] || fail "geom::$c's link interface names $l"
  done
  echo "geom::$c links: ${links:-nothing}" | tr '\n' ' '
  echo
done

# Each component with the packages it does not need disabled.
declare -A not_needed=(
  [reader]="CGAL draco ZLIB PkgConfig OpenMesh" [core]="CGAL draco ZLIB PkgConfig OpenMesh"
  [import]="CGAL OpenMesh" [focus]="draco ZLIB PkgConfig OpenMesh" [bake]="CGAL OpenMesh" [geom]="OpenMesh")
build_consumer() {  # build_consumer PREFIX TAG COMPONENT: configures and builds; prints the binary's path
  local prefix=$1 tag=$2 c=$3 dir="$work/$2-$3" disable=()
  for p in ${not_needed[$c]}; do disable+=("-DCMAKE_DISABLE_FIND_PACKAGE_$p=ON"); done
  cmake -S "$src/tests/install/consumer" -B "$dir" -DCMAKE_PREFIX_PATH="$prefix" -DCOMPONENT="$c" \
    -DCMAKE_BUILD_TYPE=Release "${disable[@]}" >"$dir.log" 2>&1 || { cat "$dir.log" >&2; fail "$tag $c: configure"; }
  cmake --build "$dir" >>"$dir.log" 2>&1 || { cat "$dir.log" >&2; fail "$tag $c: build"; }
  echo "$dir/consumer"
}

consume() {  # consume PREFIX TAG: builds and runs every consumer against PREFIX
  local prefix=$1 tag=$2 out bin
  bin=$(build_consumer "$prefix" "$tag" geom)
  out=$("$bin" "$mesh") || fail "$tag: the find_package consumer failed"
  echo "$tag find_package: $out"
  [[ $out == "geom "*" triangles, "*" sections"* ]] || fail "$tag: unexpected output: $out"
  local flags
  flags=$(PKG_CONFIG_PATH="$prefix/$libdir/pkgconfig" pkg-config --cflags --libs geom) || fail "$tag: pkg-config geom"
  # shellcheck disable=SC2086
  ${CXX:-c++} -std=c++17 -O1 "$src/tests/install/consumer/geom.cpp" -o "$work/$tag-pc" $flags ||
    fail "$tag: the pkg-config build (flags: $flags)"
  out=$("$work/$tag-pc" "$mesh") || fail "$tag: the pkg-config consumer failed"
  echo "$tag pkg-config:   $out"
  local version
  version=$(PKG_CONFIG_PATH="$prefix/$libdir/pkgconfig" pkg-config --modversion geom)
  [[ $out == "geom $version:"* ]] || fail "$tag: pkg-config's version $version differs from GEOM_VERSION"

  # The installed CLI and the library bake one mesh to the same bytes (geom::bake
  # alone links no hull function: the CLI is asked for no caster hull either).
  "$prefix/bin/geombake" bake -q --no-caster-hull "$mesh" -o "$work/$tag-cli.gbake" || fail "$tag: the installed geombake"
  bin=$(build_consumer "$prefix" "$tag" bake)
  out=$("$bin" "$mesh" "$work/$tag-lib.gbake") || fail "$tag: the bake consumer failed"
  cmp "$work/$tag-cli.gbake" "$work/$tag-lib.gbake" || fail "$tag: bake_file and geombake bake differ"
  echo "$tag bake: $out, byte-identical to geombake's"

  bin=$(build_consumer "$prefix" "$tag" reader)
  out=$("$bin" "$work/$tag-cli.gbake") || fail "$tag: the reader consumer failed"
  [[ $out == *"shaders in $prefix/share/geom/shaders" ]] || fail "$tag: the reader's shader folder: $out"
  echo "$tag reader: $out"
  # The reader alone: the include path, nothing to link.
  ${CXX:-c++} -std=c++17 -O1 -I"$prefix/include" "$src/tests/install/consumer/reader.cpp" -o "$work/$tag-reader-only" ||
    fail "$tag: the reader consumer does not build with the include path alone"
  out=$("$work/$tag-reader-only" "$work/$tag-cli.gbake") || fail "$tag: the include-path reader consumer failed"
  echo "$tag reader (-I only): $out"

  bin=$(build_consumer "$prefix" "$tag" core)
  out=$("$bin") || fail "$tag: the core consumer failed"
  echo "$tag $out"
  bin=$(build_consumer "$prefix" "$tag" import)
  out=$("$bin" "$mesh") || fail "$tag: the import consumer failed"
  echo "$tag $out"
  bin=$(build_consumer "$prefix" "$tag" focus)
  out=$("$bin") || fail "$tag: the focus consumer failed"
  echo "$tag $out"
}
consume "$work/prefix" installed
mv "$work/prefix" "$work/moved"
consume "$work/moved" moved

# The samples (examples/) against the moved prefix: the engine sample links
# geom::reader alone (and GL), the bake sample geom::core alone.
if [ -f "$src/examples/CMakeLists.txt" ]; then
  cmake -S "$src/examples" -B "$work/examples" -DCMAKE_PREFIX_PATH="$work/moved" -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_DISABLE_FIND_PACKAGE_CGAL=ON -DCMAKE_DISABLE_FIND_PACKAGE_draco=ON \
    -DCMAKE_DISABLE_FIND_PACKAGE_OpenMesh=ON >"$work/examples.log" 2>&1 || { cat "$work/examples.log"; fail "examples: configure"; }
  cmake --build "$work/examples" >>"$work/examples.log" 2>&1 || { cat "$work/examples.log"; fail "examples: build"; }
  out=$("$work/examples/bake_in_memory") || fail "examples: bake_in_memory failed"
  echo "examples: bake_in_memory: $out"
  [ -x "$work/examples/engine_sample" ] || fail "examples: no engine_sample built"
fi
echo "install: ok"
