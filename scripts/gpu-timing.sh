#!/usr/bin/env bash
# Packs geombench for a machine with a GPU and runs its timing there:
#
#   scripts/gpu-timing.sh pack [DIR]          the folder DIR (default build/gpu-timing): bin/geombench, the
#                                             non-system shared libraries it needs (lib/), the shaders
#                                             (shaders/) and run.sh; at most 64 MiB, refused above
#   DIR/run.sh [geombench flags]              on the GPU machine: the technique timing, `--time-only` (no
#                                             reference, no errors: times and pipeline counters), through
#                                             EGL, into DIR/out (results.csv, results.json, plot.svg)
#   scripts/gpu-timing.sh [flags]             both, here (llvmpipe where there is no GPU)
#
# The libraries packed are what `ldd` lists, less the C library and the
# loader, and less the GL, EGL and driver libraries, which must be the target
# machine's own (libGL, libEGL, libOpenGL, libGLX, libGLdispatch, libnvidia-*,
# libdrm, libgbm, libX11 / xcb / wayland). EGL finds an NVIDIA GPU by device
# enumeration (EGL_PLATFORM_DEVICE_EXT, render/src/platform.cpp tries it
# first) and falls back to Mesa's surfaceless platform. On a GPU geombench times
# each pass with GL_TIME_ELAPSED queries (time_kind "gpu"); on llvmpipe with
# wall time around glFinish.
# The scenes that read files (default, near-plane, bunny, quake3) read them
# where the build's source tree was; where it is missing they are skipped with
# a warning, the generated scenes run.
set -euo pipefail
cd "$(dirname "$0")/.."
readonly LIMIT=$((64 * 1024 * 1024))

pack() {
  local dir=$1 exe=build/tools/geombench/geombench
  [ -x "$exe" ] || { echo "Error: $exe: not built (bash scripts/build.sh -DGEOM_BUILD_BENCH=ON)" >&2; exit 1; }
  local tmp="$dir.tmp.$$"
  rm -rf "$tmp"
  mkdir -p "$tmp/bin" "$tmp/lib"
  cp "$exe" "$tmp/bin/"
  cp -r shaders "$tmp/shaders"
  mkdir -p "$tmp/data"  # the file scenes (GEOMBENCH_DATA); the Quake 3 map is read from openarena-data where installed
  cp data/default_scene.gltf tests/data/draco/bunny_gltf.drc tests/data/draco/LICENSE.draco-repo "$tmp/data/"
  ldd "$exe" | awk '/=> \// { print $1, $3 }' | while read -r name path; do
    case "$name" in
      libc.so* | libm.so* | libdl.so* | librt.so* | libpthread.so* | ld-linux* | libresolv.so*) continue ;;
      libGL.so* | libEGL.so* | libOpenGL.so* | libGLX*.so* | libGLdispatch.so* | libnvidia* | libdrm* | libgbm*) continue ;;
      libX*.so* | libxcb*.so* | libwayland*.so* | libxshmfence* | libexpat.so* | libz.so* | libffi.so*) continue ;;
    esac
    cp -L "$path" "$tmp/lib/$name"
  done
  cat > "$tmp/run.sh" <<'RUN'
#!/usr/bin/env bash
# geombench's technique timing on this machine's GPU (scripts/gpu-timing.sh packed it).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
export LD_LIBRARY_PATH="$here/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
export GEOMBENCH_DATA="$here/data"
mkdir -p "$here/out"
"$here/bin/geombench" --time-only --no-bake --shaders "$here/shaders" -o "$here/out" "$@"
RUN
  chmod +x "$tmp/run.sh"
  local bytes
  bytes=$(du -sb "$tmp" | cut -f1)
  if [ "$bytes" -gt "$LIMIT" ]; then
    rm -rf "$tmp"
    echo "Error: $dir: the pack is $bytes bytes, over the limit of $LIMIT" >&2
    exit 1
  fi
  rm -rf "$dir"
  mv "$tmp" "$dir"
  echo "packed $dir: $bytes bytes ($(ls "$dir/lib" | wc -l) libraries: $(ls "$dir/lib" | tr '\n' ' '))"
}

case "${1:-}" in
  pack) pack "${2:-build/gpu-timing}" ;;
  *)
    pack build/gpu-timing
    build/gpu-timing/run.sh "$@"
    ;;
esac
