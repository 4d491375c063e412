#!/usr/bin/env bash
# fuzz/run.sh TARGET SECONDS [libFuzzer options...]
#
# Builds the libFuzzer targets with clang (-fsanitize=fuzzer,address,undefined)
# in build-fuzz/, seeds TARGET's corpus from real files (the vendored tests/data, or
# GEOM_TEST_DATA, Debian's assimp-testmodels, openscad-testing-data,
# openarena-081-maps/-players), runs it for SECONDS, and prints the execution
# count, the corpus size and the findings. TARGET: gltf draco obj ply off stl
# bsp md3 baked viewer_file (fuzz/fuzz_TARGET.cpp). The corpus grows across runs in
# build-fuzz/corpus/TARGET; a crashing input is saved in build-fuzz/artifacts/TARGET/
# and the exit status is non-zero. JOBS=N sets the build's parallelism (default 2);
# SKIP_BUILD=1 uses the targets as built (fuzz/run_all.sh builds them once).
set -euo pipefail
cd "$(dirname "$0")/.."
if [ $# -lt 2 ]; then
  echo "usage: fuzz/run.sh TARGET SECONDS [libFuzzer options...]" >&2
  echo "targets: $(ls fuzz/fuzz_*.cpp | sed 's/.*fuzz_\(.*\)\.cpp/\1/' | tr '\n' ' ')" >&2
  exit 2
fi
target=$1 seconds=$2
shift 2
[ -f "fuzz/fuzz_$target.cpp" ] || { echo "Error: no fuzz target '$target' (fuzz/fuzz_$target.cpp)" >&2; exit 2; }
command -v clang++ >/dev/null || { echo "Error: clang++ not found: apt-get install clang libclang-rt-dev" >&2; exit 2; }

root=$PWD
build=$root/build-fuzz
data=${GEOM_TEST_DATA:-$root/tests/data}
if [ ! -f "$build/build.ninja" ]; then
  CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGEOM_FUZZ=ON \
    -DGEOM_BUILD_TESTS=OFF -DGEOM_BUILD_BENCH=OFF -DGEOM_BUILD_VIEWER=OFF >/dev/null
fi
targets=("fuzz_$target")
[ "$target" = baked ] || [ "$target" = viewer_file ] && targets+=(geombake)
[ -n "${SKIP_BUILD:-}" ] || cmake --build "$build" -j"${JOBS:-2}" --target "${targets[@]}"

# Seeds: real files of the target's format, at most 1 MB each (large inputs slow every execution).
seeds=$build/seeds/$target
rm -rf "$seeds" && mkdir -p "$seeds"
add_found() {  # add_found EXTENSION DIR...: every file with that extension under the dirs
  local ext=$1
  shift
  for d in "$@"; do
    [ -d "$d" ] || continue
    find "$d" -type f -iname "*.$ext" -size -1024k -print0 |
      while IFS= read -r -d '' f; do cp "$f" "$seeds/$(echo "$f" | md5sum | cut -c1-16).$ext"; done
  done
}
assimp=/usr/share/assimp/models
case $target in
  gltf) add_found gltf "$data/gltf-validator" "$data/draco" "$assimp/glTF2"
        add_found glb "$data/gltf-validator" "$data/draco" "$assimp/glTF2" ;;
  draco) add_found drc "$data/draco" ;;
  obj|ply|off) add_found "$target" "$data/draco" "$assimp" ;;
  stl) add_found stl "$data/draco" "$assimp" /usr/share/openscad ;;
  bsp)
    python3 fuzz/tiny_bsp.py "$seeds/tiny.bsp"
    pk3=/usr/share/games/openarena/baseoa/pak1-maps.pk3
    if [ -f "$pk3" ]; then
      for m in $(unzip -l "$pk3" | awk '$4 ~ /\.bsp$/ {print $1, $4}' | sort -n | head -n 2 | cut -d' ' -f2); do unzip -p "$pk3" "$m" >"$seeds/$(basename "$m")"; done
    fi ;;
  md3)
    pk3=/usr/share/games/openarena/baseoa/pak2-players.pk3
    if [ -f "$pk3" ]; then
      for m in $(unzip -Z1 "$pk3" | grep -i '\.md3$' | head -n 12); do
        unzip -p "$pk3" "$m" >"$seeds/$(echo "$m" | tr / _)"
      done
    fi ;;
  baked | viewer_file)  # containers baked here from small real files of every format, after the mode byte
    for f in "$data"/draco/{cube_att.obj,test_nm.obj,Box.ply,deg_faces.obj,non_manifold_wrap.obj} \
             "$data"/draco/Box/glTF_Binary/Box_Draco.glb "$assimp"/OFF/Wuson.off "$assimp"/STL/Spider_ascii.stl \
             /usr/share/games/openarena/baseoa/pak2-players.pk3:models/players/gargoyle/head_2.md3; do
      g=$build/seeds/$(basename "$f").gbake
      "$build/tools/geombake" bake "$f" -o "$g" --light 1,2,3,1 >/dev/null 2>&1 || continue
      { printf '\0'; cat "$g"; } >"$seeds/0_$(basename "$g")"   # mode 0: read as it is
      { printf '\1'; cat "$g"; } >"$seeds/1_$(basename "$g")"   # mode 1: checksums repaired
      rm -f "$g"
    done
    [ "$target" = viewer_file ] && cp "$root"/tests/fuzz_regressions/viewer/* "$seeds"/ ;;
esac
[ -n "$(ls -A "$seeds")" ] || { echo "Error: no seed files found for $target (install the Debian test-data packages: bash scripts/setup.sh)" >&2; exit 2; }

corpus=$build/corpus/$target artifacts=$build/artifacts/$target
mkdir -p "$corpus" "$artifacts"
dict=()
[ "$target" = gltf ] && dict=(-dict=fuzz/gltf.dict)
log=$build/fuzz-$target.log
marker=$build/.fuzz-$target.start
touch "$marker"
start=$(date +%s)
set +e
ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1} "$build/fuzz/fuzz_$target" -max_total_time="$seconds" -timeout=10 \
  -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$artifacts/" "${dict[@]}" "$@" "$corpus" "$seeds" \
  >"$log" 2>&1
status=$?
set -e
elapsed=$(($(date +%s) - start))
execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' | tail -n1)
rss=$(grep -o 'stat::peak_rss_mb: *[0-9]*' "$log" | grep -o '[0-9]*$' | tail -n1)
findings=$(find "$artifacts" -type f -newer "$marker" | wc -l)
echo "fuzz_$target: ${execs:-?} executions in $elapsed s (of $seconds), corpus $(ls "$corpus" | wc -l) files" \
  "(+$(ls "$seeds" | wc -l) seeds), peak RSS ${rss:-?} MB, exit $status, $findings new finding(s) in $artifacts"
if [ "$status" -ne 0 ]; then
  grep -E 'ERROR|SUMMARY|contract broken|Test unit written|#0 |#1 |#2 |#3 ' "$log" | head -n 20 >&2
  echo "log: $log" >&2
fi
exit "$status"
