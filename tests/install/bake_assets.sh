#!/usr/bin/env bash
# tests/install/bake_assets.sh BUILD_DIR SOURCE_DIR: geom_bake_assets() from the
# installed, moved package, with Ninja and with Unix Makefiles (ctest
# install_bake_assets). Installs BUILD_DIR to a temporary prefix, moves it, then
# for each generator builds tests/install/assets (three assets: an OFF, a glTF
# with an external .bin, an OBJ; a packing step that depends on the baked
# files) and checks, counting the bake commands each build runs:
#   the first build bakes 3 and packs; a no-op rebuild runs nothing;
#   a touched input is rebaked once, and nothing runs on the next build;
#   a touched .bin (named by the glTF, known from the depfile alone) rebakes it once;
#   a broken .bin fails the build, removes that output, fails the next build
#   too (retried, not "nothing to do"), and a repaired one bakes again;
#   a changed input's new bytes reach the packing step.
set -euo pipefail
build=$(cd "$1" && pwd) src=$(cd "$2" && pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/geom_assets.XXXXXX")
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
command -v ninja >/dev/null || fail "ninja is missing (Debian: ninja-build)"

cmake --install "$build" --prefix "$work/prefix" >/dev/null
libdir=$(cd "$work/prefix" && ls -d lib*/cmake/geom | head -1)
[ -f "$work/prefix/$libdir/GeomBakeAssets.cmake" ] || fail "GeomBakeAssets.cmake is not installed beside geomConfig.cmake"
mv "$work/prefix" "$work/moved"

tetra="v 0 0 0
v 1 0 0
v 0 1 0
v 0 0 1
f 1 3 2
f 1 2 4
f 2 3 4
f 3 1 4"
cube="OFF
8 12 0
0 0 0
1 0 0
1 1 0
0 1 0
0 0 1
1 0 1
1 1 1
0 1 1
3 0 2 1
3 0 3 2
3 4 5 6
3 4 6 7
3 0 1 5
3 0 5 4
3 1 2 6
3 1 6 5
3 2 3 7
3 2 7 6
3 3 0 4
3 3 4 7"

run() {  # run GEN: the whole sequence with one generator
  local gen=$1 tag=${1// /_}
  local s="$work/$tag-src" b="$work/$tag-build" log="$work/$tag.log"
  mkdir -p "$s/Box" "$s/sub"
  cp "$src/tests/install/assets/CMakeLists.txt" "$src/tests/install/assets/manifest.cmake" "$s/"
  cp "$src/tests/data/draco/Box/glTF/Box.gltf" "$src/tests/data/draco/Box/glTF/Box0.bin" "$s/Box/"
  printf '%s\n' "$cube" >"$s/cube.off"
  printf '%s\n' "$tetra" >"$s/sub/tetra.obj"
  cmake -S "$s" -B "$b" -G "$gen" -DCMAKE_PREFIX_PATH="$work/moved" >"$log" 2>&1 || { cat "$log"; fail "$gen: configure"; }
  grep -q "geombake: $work/moved/bin/geombake" "$log" || { cat "$log"; fail "$gen: not the installed, moved geombake"; }
  step() {  # step WHAT BAKES [PACKS]: a build runs BAKES bakes (and PACKS packing steps when given)
    local what=$1 bakes=$2 packs=${3:-}
    cmake --build "$b" >"$log" 2>&1 || { cat "$log"; fail "$gen: $what: the build failed"; }
    local n p
    n=$(grep -c "Baking " "$log" || true) p=$(grep -c "Packing the baked assets" "$log" || true)
    echo "$gen: $what: $n bakes, $p packs"
    [ "$n" -eq "$bakes" ] || { cat "$log"; fail "$gen: $what: $n bake commands ran, expected $bakes"; }
    [ -z "$packs" ] || [ "$p" -eq "$packs" ] || { cat "$log"; fail "$gen: $what: $p packing steps, expected $packs"; }
  }
  step "first build" 3 1
  for f in cube.off Box/Box.gltf sub/tetra.obj; do [ -f "$b/baked/$f.gbake" ] || fail "$gen: no $b/baked/$f.gbake"; done
  [ "$(wc -l <"$b/manifest.txt")" -eq 3 ] || fail "$gen: the packing step did not see the 3 outputs"
  step "no-op rebuild" 0 0
  sleep 1.1; touch "$s/cube.off"
  step "touched cube.off" 1
  step "the build after it" 0 0
  sleep 1.1; touch "$s/Box/Box0.bin"  # the glTF names it: a dependency through the depfile alone
  step "touched Box0.bin" 1
  step "the build after it" 0 0
  cp "$s/Box/Box0.bin" "$work/Box0.bin"
  sleep 1.1; head -c 100 "$work/Box0.bin" >"$s/Box/Box0.bin"
  if cmake --build "$b" >"$log" 2>&1; then cat "$log"; fail "$gen: a truncated .bin built"; fi
  grep -q "Error: .*Box.gltf" "$log" || { cat "$log"; fail "$gen: no Error: line for the broken glTF"; }
  [ ! -e "$b/baked/Box/Box.gltf.gbake" ] || fail "$gen: the failed glTF's stale output stays"
  if cmake --build "$b" >"$log" 2>&1; then cat "$log"; fail "$gen: the next build did not retry the failed glTF"; fi
  grep -q "Baking Box/Box.gltf" "$log" || { cat "$log"; fail "$gen: the failed glTF was not retried"; }
  sleep 1.1; cp "$work/Box0.bin" "$s/Box/Box0.bin"
  step "repaired Box0.bin" 1
  [ -f "$b/baked/Box/Box.gltf.gbake" ] || fail "$gen: no output after the repair"
  local before
  before=$(cat "$b/manifest.txt")
  sleep 1.1; printf '%s\n' "$cube" | sed 's/^1 1 1$/2 2 2/' >"$s/cube.off"  # a vertex moved: new bytes
  step "changed cube.off" 1 1
  [ "$(cat "$b/manifest.txt")" != "$before" ] || fail "$gen: the packing step did not see the new bytes"
  step "the build after it" 0 0
}
run Ninja
run "Unix Makefiles"
echo "bake_assets: ok"
