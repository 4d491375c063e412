#!/usr/bin/env bash
# Configures and builds the project into build/ (Release). Extra arguments go to cmake's configure step;
# GEOM_TARGETS="a b" builds those targets alone (scripts/demo.sh: the two programs it runs).
set -euo pipefail
cd "$(dirname "$0")/.."
GEN=()
command -v ninja >/dev/null 2>&1 && [ ! -f build/Makefile ] && GEN=(-G Ninja)
cmake -S . -B build "${GEN[@]}" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
targets=()
for t in ${GEOM_TARGETS:-}; do targets+=(--target "$t"); done
cmake --build build -j"$(nproc)" "${targets[@]}"
