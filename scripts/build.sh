#!/usr/bin/env bash
# Installs dependencies if needed and builds. Usage: scripts/build.sh [--sanitize | --tsan]
#   (default: Release in build/ with g++; --sanitize: Debug + ASan + UBSan with clang in
#   build-sanitize/, with the fuzz targets built for libFuzzer; --tsan: ThreadSanitizer with
#   clang in build-tsan/, the renderer and the multi-threaded tests only)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
if [ "${1:-}" = "--sanitize" ]; then
  # clang, so that the same build also makes the libFuzzer targets the suite runs; llvm brings
  # llvm-symbolizer, without which clang's sanitizers print no function names (and the leak
  # suppressions in tests/lsan.supp, which match them, cannot apply).
  bash scripts/setup.sh clang libclang-rt-14-dev llvm
  dir=build-sanitize
  # Without MPI: Open MPI unloads its plugins at MPI_Finalize, so LeakSanitizer reports their
  # allocations from unknown modules that no suppression can name. The MPI glue
  # (src/cli/process_group.cpp) is tested in the Release suite; the split render itself here too
  # (Resume.SplitRenders*, in one process).
  cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Debug -DERPT_SANITIZE=ON -DERPT_BUILD_BENCHMARKS=OFF \
    -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DERPT_LIBFUZZER=ON -DERPT_MPI=OFF -DERPT_PYTHON=OFF >/dev/null
elif [ "${1:-}" = "--tsan" ]; then
  bash scripts/setup.sh clang libclang-rt-14-dev llvm
  dir=build-tsan
  cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Debug -DERPT_TSAN=ON -DERPT_BUILD_BENCHMARKS=OFF \
    -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DERPT_MPI=OFF -DERPT_PYTHON=OFF >/dev/null
  cmake --build "$dir" --target erpt_tests
  exit 0
else
  dir=build
  cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DPython_EXECUTABLE="$(bash scripts/python.sh)" >/dev/null
fi
cmake --build "$dir"
