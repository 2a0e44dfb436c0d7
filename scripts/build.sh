#!/usr/bin/env bash
# Installs dependencies if needed and builds. Usage: scripts/build.sh [--sanitize]
#   (default: Release in build/; --sanitize: Debug + ASan + UBSan in build-sanitize/)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
if [ "${1:-}" = "--sanitize" ]; then
  dir=build-sanitize
  cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Debug -DERPT_SANITIZE=ON -DERPT_BUILD_BENCHMARKS=OFF >/dev/null
else
  dir=build
  cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
cmake --build "$dir"
