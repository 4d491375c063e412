#!/usr/bin/env bash
# The sanitizer job of CI (.ci/run): builds the project in build-asan/ as a
# Debug build with the asserts on (no NDEBUG; -O1, as AddressSanitizer advises)
# and AddressSanitizer + UndefinedBehaviorSanitizer (GEOM_SANITIZE=ON, no
# benchmarks, no viewer) and runs the CPU tests under them (`ctest -LE gl`):
# the Debug job beside scripts/test.sh's Release one, so the asserts the
# headers promise for caller bugs run in every CI run; then the
# ThreadSanitizer job: geombake and the batch tests (test_batch_bake,
# test_hostile) built in build-tsan/ with GEOM_TSAN=ON and run under it (any
# data race fails them). Extra arguments go to the ASan job's ctest (e.g.
# -R sweep). SANITIZE_JOBS=asan or tsan runs one job only. Prints the build
# and test times.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
GEN=()
command -v ninja >/dev/null 2>&1 && [ ! -f build-asan/Makefile ] && GEN=(-G Ninja)
t0=$(date +%s)
JOBS=${SANITIZE_JOBS:-asan,tsan}
if [[ $JOBS == *asan* ]]; then
  cmake -S . -B build-asan "${GEN[@]}" -DCMAKE_BUILD_TYPE=Debug "-DCMAKE_CXX_FLAGS_DEBUG=-O1 -g" \
    "-DCMAKE_C_FLAGS_DEBUG=-O1 -g" -DGEOM_SANITIZE=ON -DGEOM_BUILD_BENCH=OFF -DGEOM_BUILD_VIEWER=OFF >/dev/null
  cmake --build build-asan -j"$(nproc)"
fi
t1=$(date +%s)
export ASAN_OPTIONS=${ASAN_OPTIONS:-halt_on_error=1:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
if [[ $JOBS == *asan* ]]; then
  (cd build-asan && ctest --output-on-failure -j"$(nproc)" -LE gl "$@")
fi
t2=$(date +%s)
echo "sanitizer job (Debug, asserts on): build $((t1 - t0)) s, CPU tests $((t2 - t1)) s"
if [[ $JOBS == *tsan* ]]; then
  cmake -S . -B build-tsan "${GEN[@]}" -DCMAKE_BUILD_TYPE=Release -DGEOM_TSAN=ON -DGEOM_BUILD_BENCH=OFF \
    -DGEOM_BUILD_VIEWER=OFF >/dev/null
  cmake --build build-tsan -j"$(nproc)" --target geombake test_batch_bake test_hostile
  t3=$(date +%s)
  export TSAN_OPTIONS=${TSAN_OPTIONS:-halt_on_error=1:second_deadlock_stack=1}
  (cd build-tsan && ctest --output-on-failure -j"$(nproc)" -R '^(BatchBake|Hostile)\.')
  t4=$(date +%s)
  echo "thread sanitizer job: build $((t3 - t2)) s, batch tests $((t4 - t3)) s"
fi
