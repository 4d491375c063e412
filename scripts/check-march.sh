#!/usr/bin/env bash
# scripts/check-march.sh [CORPUS_DIR...]: the same bytes on every CPU. Builds
# geombake alone for -march=$GEOM_MARCH (default x86-64-v3: AVX2 and FMA) into
# build-march/, bakes the test corpus with it and with the default build's
# geombake (build/, or $GEOM_BASE_BUILD; built if missing), and compares the
# two trees of outputs byte for byte, with their stable reports (the error of
# each failed input included). Any difference fails. A compiler free to fuse
# a*b+c into one FMA rounds once where the default build rounds twice, so the
# stored planes and quads differ: CMakeLists.txt sets -ffp-contract=off.
# The corpus: tests/data (glTF), Debian's assimp and OpenSCAD test meshes (the
# packages scripts/setup.sh installs), and any CORPUS_DIR given.
# Run by .ci/run; prints its time.
set -euo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)
march=${GEOM_MARCH:-x86-64-v3}
base=${GEOM_BASE_BUILD:-build}
gen=(); command -v ninja >/dev/null 2>&1 && gen=(-G Ninja)
if [ ! -f "$base/CMakeCache.txt" ]; then
  cmake -S . -B "$base" "${gen[@]}" -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
cmake --build "$base" --target geombake -j"$(nproc)" >/dev/null
if [ ! -f build-march/CMakeCache.txt ]; then
  cmake -S . -B build-march "${gen[@]}" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS="-march=$march" \
    -DCMAKE_C_FLAGS="-march=$march" -DGEOM_BUILD_TESTS=OFF -DGEOM_BUILD_BENCH=OFF -DGEOM_BUILD_VIEWER=OFF >/dev/null
fi
cmake --build build-march --target geombake -j"$(nproc)" >/dev/null
built=$(date +%s)

corpus=(tests/data /usr/share/assimp/models /usr/share/openscad "$@")
work=$(mktemp -d "${TMPDIR:-/tmp}/geom_march.XXXXXX")
trap 'rm -rf "$work"' EXIT
for tag in base march; do
  exe=$base/tools/geombake
  [ "$tag" = march ] && exe=build-march/tools/geombake
  i=0
  for dir in "${corpus[@]}"; do
    [ -d "$dir" ] || { echo "check-march: $dir is missing (scripts/setup.sh installs it)" >&2; exit 1; }
    i=$((i + 1))
    # Failed inputs are part of the comparison (their errors are in the report): exit 1 is fine.
    (cd "$dir" && "$OLDPWD/$exe" bake . -o "$work/$tag/$i" -q --stable-report -r "$work/$tag-$i.json" -j"$(nproc)") \
      || [ $? -eq 1 ] || { echo "check-march: $exe failed on $dir" >&2; exit 1; }
  done
done
files=$(find "$work/base" -type f | wc -l)
same_reports() {  # the reports name their output folder: compared with it made the same
  local j
  for j in "$work"/base-*.json; do
    cmp -s <(sed "s#$work/base/#OUT/#g" "$j") <(sed "s#$work/march/#OUT/#g" "${j/base-/march-}") || return 1
  done
}
if diff -r "$work/base" "$work/march" >"$work/diff.txt" && same_reports; then
  echo "check-march: $files outputs identical between the default build and -march=$march" \
       "(build $((built - start)) s, bake and compare $(($(date +%s) - built)) s)"
else
  cat "$work/diff.txt"
  echo "check-march: FAIL: $(grep -c '^Binary files\|^Only in' "$work/diff.txt" || true) of $files outputs differ" \
       "between the default build and -march=$march" >&2
  same_reports || echo "check-march: FAIL: the reports differ (topology counts or errors)" >&2
  exit 1
fi
