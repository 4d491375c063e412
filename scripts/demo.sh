#!/usr/bin/env bash
# The main job on the bundled default scene (or the mesh file given as $1):
# installs what is missing, builds, then into out/:
#   report.json       the topology report (geombake info --json)
#   NAME.gbake        the baked buffers (geombake bake), verified (geombake inspect)
#   techniques/*.png  every shadow technique rendered headless from the baked file (geomview)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
GEOM_TARGETS="geombake geomview" bash scripts/build.sh  # the tests build with scripts/test.sh
SCENE=${1:-data/default_scene.gltf}
NAME=$(basename "${SCENE##*:}")
NAME=${NAME%.*}
mkdir -p out
./build/tools/geombake info "$SCENE"
./build/tools/geombake info --json -o out/report.json "$SCENE"
./build/tools/geombake bake -v -o "out/$NAME.gbake" "$SCENE"
./build/tools/geombake inspect "out/$NAME.gbake"
./build/viewer/geomview "out/$NAME.gbake" --technique all -o out/techniques
echo "wrote out/report.json, out/$NAME.gbake and out/techniques/*.png"
