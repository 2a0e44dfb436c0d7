#!/usr/bin/env bash
# Quick start: installs, builds as needed, and renders the built-in default scene to
# out/default.exr (linear) and out/default.png (tone-mapped). Extra arguments go to
# `erpt render` (e.g. --spp 16).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
mkdir -p out
./build/erpt render scenes/default/scene.xml -o out/default.exr "$@"
