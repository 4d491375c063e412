#!/usr/bin/env bash
# Installs the Debian 12 packages the project needs, only those that are missing.
# Idempotent and non-interactive; run as root or with sudo available.
# Used by README's first command and by .ci/run.
set -euo pipefail
PKGS=(
  build-essential cmake ninja-build pkg-config
  libopenmesh-dev libcgal-dev libglm-dev libtinygltf-dev libdraco-dev
  libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri libgbm-dev libglfw3-dev
  libembree-dev libmeshoptimizer-dev libcli11-dev nlohmann-json3-dev libstb-dev
  libgmp-dev libmpfr-dev libeigen3-dev libgtest-dev libbenchmark-dev libzip-dev
  assimp-testmodels openarena-081-maps openarena-081-players openscad-testing-data xvfb xauth libimgui-dev
)
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#PKGS[@]} packages present"
  exit 0
fi
echo "setup: installing ${missing[*]}"
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
$SUDO apt-get update -q
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
