#!/usr/bin/env bash
# tests/install/run.sh BUILD_DIR SOURCE_DIR: the relocatable install (issue 17),
# run by ctest (test install_consumer). Installs BUILD_DIR with `cmake --install`
# to a temporary prefix, checks that the installed CMake config and geom.pc hold
# no absolute path (of this machine's libraries, the source or the build tree),
# then builds the consumer project tests/install/consumer through find_package(geom)
# and through pkg-config, runs both; moves the prefix elsewhere and does it again.
set -euo pipefail
build=$(cd "$1" && pwd) src=$(cd "$2" && pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/geom_install.XXXXXX")
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
mesh="$src/tests/data/draco/Box/glTF_Binary/Box.glb"
[ -f "$mesh" ] || fail "$mesh is missing"

cmake --install "$build" --prefix "$work/prefix" >/dev/null
libdir=$(cd "$work/prefix" && ls -d lib*/pkgconfig | head -1 | xargs dirname)
[ -f "$work/prefix/$libdir/cmake/geom/geomConfig.cmake" ] || fail "no geomConfig.cmake under $libdir/cmake/geom"
[ -f "$work/prefix/$libdir/pkgconfig/geom.pc" ] || fail "no geom.pc"
[ -f "$work/prefix/include/geom/version.h" ] || fail "no geom/version.h installed"
grep -q '#define GEOM_VERSION "' "$work/prefix/include/geom/version.h" || fail "geom/version.h has no GEOM_VERSION"
for bad in "$src" "$build" "$work" /usr/lib /usr/local; do
  if grep -rlF "$bad" "$work/prefix/$libdir/cmake/geom" "$work/prefix/$libdir/pkgconfig/geom.pc"; then
    fail "an absolute path ($bad) in the installed package files above"
  fi
done

consume() {  # consume PREFIX TAG: builds and runs the consumer both ways against PREFIX
  local prefix=$1 tag=$2
  cmake -S "$src/tests/install/consumer" -B "$work/$tag-cmake" -DCMAKE_PREFIX_PATH="$prefix" \
    -DCMAKE_BUILD_TYPE=Release >"$work/$tag-cmake.log" 2>&1 || { cat "$work/$tag-cmake.log"; fail "$tag: configure"; }
  cmake --build "$work/$tag-cmake" >>"$work/$tag-cmake.log" 2>&1 || { cat "$work/$tag-cmake.log"; fail "$tag: build"; }
  local out
  out=$("$work/$tag-cmake/consumer" "$mesh") || fail "$tag: the find_package consumer failed"
  echo "$tag find_package: $out"
  [[ $out == "geom "*" triangles, "*" sections"* ]] || fail "$tag: unexpected output: $out"
  local flags
  flags=$(PKG_CONFIG_PATH="$prefix/$libdir/pkgconfig" pkg-config --cflags --libs geom) || fail "$tag: pkg-config geom"
  # shellcheck disable=SC2086
  ${CXX:-c++} -std=c++17 -O1 "$src/tests/install/consumer/main.cpp" -o "$work/$tag-pc" $flags ||
    fail "$tag: the pkg-config build (flags: $flags)"
  out=$("$work/$tag-pc" "$mesh") || fail "$tag: the pkg-config consumer failed"
  echo "$tag pkg-config:   $out"
  local version
  version=$(PKG_CONFIG_PATH="$prefix/$libdir/pkgconfig" pkg-config --modversion geom)
  [[ $out == "geom $version:"* ]] || fail "$tag: pkg-config's version $version differs from GEOM_VERSION"
}
consume "$work/prefix" installed
mv "$work/prefix" "$work/moved"
consume "$work/moved" moved
echo "install: ok"
