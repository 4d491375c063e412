#!/usr/bin/env bash
# The main job on the bundled default scene: installs what is missing, builds,
# then writes the topology report and the baked buffers of data/default_scene.gltf
# into out/ (and, when the viewer is built, renders every technique there).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
mkdir -p out
SCENE=${1:-data/default_scene.gltf}
./build/tools/geombake info "$SCENE"
./build/tools/geombake info --json -o out/report.json "$SCENE"
echo "wrote out/report.json"
