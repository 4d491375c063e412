#!/usr/bin/env bash
# tests/install/geomview.sh BUILD_DIR SOURCE_DIR: the installed viewer is
# relocatable and hermetic; ctest test install_geomview (label gl: it renders).
# Installs BUILD_DIR to a temporary prefix and moves it: no installed program
# holds a path of the source or build tree; the moved geomview finds its
# shaders and its default scene beside its own binary (../share/geom), which
# its --help names; GEOMVIEW_SHADERS overrides that, and --shaders both.
set -euo pipefail
build=$(cd "$1" && pwd) src=$(cd "$2" && pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/geom_install_view.XXXXXX")
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
unset GEOMVIEW_SHADERS
scene="$src/data/default_scene.gltf"

cmake --install "$build" --prefix "$work/prefix" >/dev/null
mv "$work/prefix" "$work/moved"
bin="$work/moved/bin/geomview" shaders="$work/moved/share/geom/shaders"
[ -x "$bin" ] || fail "no bin/geomview installed"
[ -f "$shaders/shade.frag" ] || fail "no share/geom/shaders installed"
for tree in "$src" "$build"; do  # hermetic: no path of the build machine in the installed programs
  for prog in "$work/moved/bin/geomview" "$work/moved/bin/geombake"; do
    if grep -qF "$tree" "$prog"; then fail "$(basename "$prog") holds the path $tree"; fi
  done
done
cd "$work"
help=$("$bin" --help)
grep -qF "$shaders" <<<"$help" || fail "the moved geomview's default shaders are not $shaders:
$help"
view() { "$bin" "$scene" --technique ssm --size 64x48 -o "$work/$1.png" "${@:2}"; }
view beside 2>"$work/err" || fail "the moved geomview cannot render: $(cat "$work/err")"
"$bin" --technique ssm --size 64x48 -o "$work/default.png" 2>"$work/err" ||
  fail "the moved geomview does not find its default scene: $(cat "$work/err")"
[ -s "$work/default.png" ] || fail "no image of the default scene written"
[ -s "$work/beside.png" ] || fail "no image written"
mkdir "$work/empty"
if GEOMVIEW_SHADERS="$work/empty" view env 2>"$work/err"; then fail "GEOMVIEW_SHADERS=an empty folder was not used"; fi
grep -qF "$work/empty" "$work/err" || fail "the shader error does not name GEOMVIEW_SHADERS' folder: $(cat "$work/err")"
GEOMVIEW_SHADERS="$work/empty" view flag --shaders "$shaders" 2>"$work/err" ||
  fail "--shaders did not override GEOMVIEW_SHADERS: $(cat "$work/err")"
if view flag2 --shaders "$work/empty" 2>/dev/null; then fail "--shaders an empty folder was not used"; fi
echo "install_geomview: ok ($shaders)"
