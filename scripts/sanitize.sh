#!/usr/bin/env bash
# The sanitizer job of CI (.ci/run): builds the project in build-asan/ with
# AddressSanitizer + UndefinedBehaviorSanitizer (GEOM_SANITIZE=ON, no benchmarks,
# no viewer) and runs the CPU tests under them (`ctest -LE gl`). Extra
# arguments go to ctest (e.g. -R sweep). Prints the build and test times.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
GEN=()
command -v ninja >/dev/null 2>&1 && [ ! -f build-asan/Makefile ] && GEN=(-G Ninja)
t0=$(date +%s)
cmake -S . -B build-asan "${GEN[@]}" -DCMAKE_BUILD_TYPE=Release -DGEOM_SANITIZE=ON -DGEOM_BUILD_BENCH=OFF \
  -DGEOM_BUILD_VIEWER=OFF >/dev/null
cmake --build build-asan -j"$(nproc)"
t1=$(date +%s)
export ASAN_OPTIONS=${ASAN_OPTIONS:-halt_on_error=1:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
cd build-asan
ctest --output-on-failure -j"$(nproc)" -LE gl "$@"
t2=$(date +%s)
echo "sanitizer job: build $((t1 - t0)) s, CPU tests $((t2 - t1)) s"
