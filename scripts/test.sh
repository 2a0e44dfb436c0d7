#!/usr/bin/env bash
# Installs, builds as needed, and runs every test: the Release build, then the same suite
# under AddressSanitizer + UndefinedBehaviorSanitizer, then the multi-threaded tests under
# ThreadSanitizer (skip both sanitizer runs with --release-only), then the Python module's tests
# (pytest, tests/python).
# Prints the time each step took at the end.
set -euo pipefail
cd "$(dirname "$0")/.."
timings=()
step() {  # step NAME COMMAND...: runs the command and records its wall time
  local name=$1 start=$SECONDS
  shift
  "$@"
  timings+=("$(printf '%-22s %4d s' "$name" $((SECONDS - start)))")
}
report() { printf '\ntime per step:\n'; printf '  %s\n' "${timings[@]}"; }
trap report EXIT

step "release build" bash scripts/build.sh
step "release tests" bash -c 'cd build && ctest --output-on-failure -j2'
if [ "${1:-}" != "--release-only" ]; then
  step "sanitizer build" bash scripts/build.sh --sanitize
  # Leaks are checked too; tests/lsan.supp lists the third-party ones we cannot fix. This
  # build is clang's, and its Fuzz.* tests are 10 s libFuzzer runs of each fuzz target
  # (scripts/fuzz.sh runs them for longer). The long statistical renders of the path tracer
  # (against the references and the scalar tracer), ERPT, PMC-ER, MLT, BDPT (and the others with
  # its seeds), PSSMLT, MMLT, PMC-ER's time budgets and outlier check, the splatting films and exact-vs-tessellated spheres run in the Release suite only (their code paths are covered by
  # the stage, measure, determinism, closed-form and CLI tests here), and so does the table of
  # every integrator x option (200 CLI renders; the option code it checks is plain parsing).
  # intercept_tls_get_addr=0: clang 14's LeakSanitizer guesses the extent of a dlopen'ed
  # library's thread-local block from a header it assumes glibc 2.19 wrote; on some library
  # layouts (the OpenImageIO module's, on some machines) the guess is garbage and its tracer
  # crashes at exit after the test passed. Without the interception dynamic TLS is simply not a
  # root of the leak scan: that can only report more leaks, never hide one of ours.
  step "sanitizer tests" bash -c 'cd build-sanitize && ASAN_OPTIONS=detect_leaks=1:intercept_tls_get_addr=0 \
    LSAN_OPTIONS=suppressions="$PWD/../tests/lsan.supp" ctest --output-on-failure -j2 \
    -E "^Statistical(Erpt|Pmc|PmcTimeBudget|Mlt|Pssmlt|Mmlt|Outliers|Film|Resume|Path|PathVsScalar|Bdpt|BdptSeeds|Strategies|ClosedFormPrecision)\.|^StatisticalTable/|^StatisticalExactSphere\.ExactAndTessellated|^Cli/OptionsTable\."'
  # ThreadSanitizer on the multi-threaded code: the stage kernels and every test that renders
  # one scene on 1 and 2 threads (path, direct, seed store, splat film, erpt, pmc-er, mlt, split
  # renders). In this build the parallel loops run on std::threads (src/core/parallel.cpp).
  step "tsan build" bash scripts/build.sh --tsan
  step "tsan tests" bash -c 'cd build-tsan && TSAN_OPTIONS="halt_on_error=1 ignore_noninstrumented_modules=1 suppressions=$PWD/../tests/tsan.supp" \
    ctest --output-on-failure -j2 -R "^(ErptStages|ErptLanes|ExactFilm|StageCompact|StageShadow|StageGenerate)\.|ThreadCount|^Resume\.Split"'
fi
# The Python module against the Release build (Debian's interpreter: numpy, matplotlib and
# pytest are its packages).
step "python tests" bash -c 'PYTHONPATH="$PWD/build/python" "$(bash scripts/python.sh)" -m pytest -q tests/python'
