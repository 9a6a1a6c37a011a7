#!/usr/bin/env bash
# Installs every Debian 12 package that building and testing depthtrack needs. Idempotent.
set -euo pipefail
packages=(
  build-essential cmake ninja-build pkg-config git clang-format
  libeigen3-dev libassimp-dev libpng-dev nlohmann-json3-dev libcli11-dev catch2 libnanoflann-dev libmeshoptimizer-dev libqhull-dev
  ocl-icd-opencl-dev opencl-headers opencl-c-headers opencl-clhpp-headers clinfo pocl-opencl-icd
  libegl-dev libgl-dev libgles-dev libosmesa6-dev libegl-mesa0 libgl1-mesa-dri mesa-utils
  pybind11-dev python3-dev python3-numpy python3-pytest python3-matplotlib
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  sudo_cmd=""; [[ $(id -u) -ne 0 ]] && sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
