#!/usr/bin/env bash
# Installs what surge needs on Debian 12, from Debian's packages only.
# The CUDA toolkit is not installed here (it is optional; see README).
set -euo pipefail
pkgs=(build-essential cmake git libyaml-cpp-dev libthrust-dev libgtest-dev googletest
      python3 python3-numpy python3-matplotlib python3-vtk9 clang clang-format clang-tidy libomp-dev libclang-rt-dev
      openmpi-bin libopenmpi-dev libgdal-dev python3-gdal python3-yaml)
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "installing: ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
