#!/usr/bin/env bash
# Builds and runs every test (CPU tests and, labelled gl, the headless OpenGL
# tests on Mesa llvmpipe through EGL). `scripts/test.sh -LE gl` skips the GL ones.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh -DGEOM_BUILD_BENCH=ON
cd build
ctest --output-on-failure -j"$(nproc)" "$@"
