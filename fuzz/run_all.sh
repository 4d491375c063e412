#!/usr/bin/env bash
# fuzz/run_all.sh SECONDS [PARALLEL]: builds every fuzz target once, then runs
# them all for SECONDS each, PARALLEL at a time (default 2), through
# fuzz/run.sh, and prints one line per target (executions, corpus, findings).
# The lines are kept in build-fuzz/summary.txt. Exit status: non-zero if any
# target had a finding. SKIP_BUILD=1 runs the targets as built.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:?usage: fuzz/run_all.sh SECONDS [PARALLEL]}
parallel=${2:-2}
targets=$(ls fuzz/fuzz_*.cpp | sed 's/.*fuzz_\(.*\)\.cpp/\1/')
# Configure (as fuzz/run.sh does) and build everything once.
[ -f build-fuzz/build.ninja ] || CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DGEOM_FUZZ=ON -DGEOM_BUILD_TESTS=OFF -DGEOM_BUILD_BENCH=OFF -DGEOM_BUILD_VIEWER=OFF >/dev/null
[ -n "${SKIP_BUILD:-}" ] || cmake --build build-fuzz -j"${JOBS:-2}" --target fuzzers geombake
: >build-fuzz/summary.txt
status=0
set -- $targets
while [ $# -gt 0 ]; do
  pids=()
  for _ in $(seq "$parallel"); do
    [ $# -gt 0 ] || break
    (SKIP_BUILD=1 fuzz/run.sh "$1" "$seconds" 2>&1 | grep '^fuzz_' >>build-fuzz/summary.txt) &
    pids+=($!)
    shift
  done
  for p in "${pids[@]}"; do wait "$p" || status=1; done
done
cat build-fuzz/summary.txt
grep -q ', exit 0, 0 new' build-fuzz/summary.txt || status=1
grep -v ', exit 0, 0 new' build-fuzz/summary.txt >/dev/null && status=1
exit $status
