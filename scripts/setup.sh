#!/usr/bin/env bash
# Installs every build and test dependency from Debian 12 packages. Idempotent: installs
# only what is missing, so it is cheap to run before every build. Extra packages may be
# named as arguments (scripts/fuzz.sh adds clang and libFuzzer).
set -euo pipefail

packages=(
  g++ cmake ninja-build pkg-config
  libembree-dev libtbb-dev libopenimageio-dev libopenexr-dev libpng-dev libxsimd-dev
  libpugixml-dev libtinyobjloader-dev libcli11-dev zlib1g-dev
  libgtest-dev libbenchmark-dev
  libopenmpi-dev openmpi-bin
  pybind11-dev python3-dev python3-numpy python3-matplotlib python3-pytest
  python3-venv python3-setuptools python3-wheel
  "$@"
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "setup: installing ${missing[*]}" >&2
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "setup: need root (or sudo) to install: ${missing[*]}" >&2; exit 1; }
  SUDO=sudo
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
