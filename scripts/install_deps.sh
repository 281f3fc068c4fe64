#!/usr/bin/env bash
# Installs what the project needs from Debian 12 (run as root); does nothing if all is present.
set -euo pipefail
packages=(
  build-essential binutils cmake git
  libeigen3-dev pybind11-dev python3-dev python3-numpy python3-pytest libgtest-dev
  blender xvfb xauth
  clang libclang-rt-14-dev
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "== installing: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -q
  apt-get install -y -q --no-install-recommends "${missing[@]}"
fi
