#!/usr/bin/env bash
# Coverage-guided fuzzing of the scene loader and the mesh readers with clang's libFuzzer,
# under AddressSanitizer + UndefinedBehaviorSanitizer. Usage: scripts/fuzz.sh [SECONDS per
# target, default 60] [targets..., default: scene_xml scene_camera obj ply serialized]
# Builds in build-fuzz/ (clang); each target starts from tests/fuzz/corpus/<target> and keeps
# what it learns in build-fuzz/corpus/<target>; a crashing input is written to build-fuzz/
# (crash-*) and the script fails. The sanitizer suite runs each target for 60 s the same way.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(scene_xml scene_camera obj ply serialized)
bash scripts/setup.sh clang libclang-rt-14-dev llvm
flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fsanitize=fuzzer-no-link -fno-omit-frame-pointer"
cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang \
  -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS="$flags" -DERPT_LIBFUZZER=ON >/dev/null
cmake --build build-fuzz --target "${targets[@]/#/fuzz_}"
for t in "${targets[@]}"; do
  mkdir -p "build-fuzz/corpus/$t"
  echo "fuzz: $t for ${seconds}s"
  (cd build-fuzz && ASAN_OPTIONS=detect_leaks=0 "./tests/fuzz_$t" -max_total_time="$seconds" -max_len=65536 \
    "corpus/$t" "../tests/fuzz/corpus/$t")
done
