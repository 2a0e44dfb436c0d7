#!/usr/bin/env bash
# The PMC-ER paper's Table 1 comparison at equal seeds: ERPT with 8 and 16 path-traced seeds
# per pixel against PMC-ER whose stratified pool has 8 (and 16) per pixel, each with its
# defaults otherwise; for each, the render time (whole process), MSE, relMSE and
# Eff = 1 / (T MSE) against a reference, as a Markdown table. Runs `runs` seeds per row and
# reports the mean (one render's error scatters).
# Usage: scripts/pmc-vs-erpt.sh SCENE REFERENCE WIDTH HEIGHT FILTER RUNS [extra render options]
set -euo pipefail
cd "$(dirname "$0")/.."
scene=$1 ref=$2 width=$3 height=$4 filter=$5 runs=$6
shift 6
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "| integrator | seeds per pixel | time (s) | MSE | relMSE | Eff = 1/(T MSE) | Eff_rel = 1/(T relMSE) |"
echo "|---|---|---|---|---|---|---|"
for row in "erpt 8" "erpt 16" "pmc-er 8" "pmc-er 16"; do
  read -r integrator spp <<<"$row"
  total_t=0 total_mse=0 total_rel=0
  for ((seed = 1; seed <= runs; ++seed)); do
    start=$(date +%s.%N)
    ./build/erpt render "$scene" -o "$out/img.exr" --integrator "$integrator" --spp "$spp" --width "$width" \
      --height "$height" --filter "$filter" --seed "$seed" -q "$@" 2>/dev/null
    end=$(date +%s.%N)
    read -r mse rel < <(./build/erpt diff "$out/img.exr" "$ref" | awk '/^mse/{m=$2} /^relmse/{r=$2} END{print m, r}')
    read -r total_t total_mse total_rel < <(awk -v a="$total_t" -v b="$total_mse" -v c="$total_rel" -v s="$start" \
      -v e="$end" -v m="$mse" -v r="$rel" 'BEGIN{printf "%.9g %.9g %.9g\n", a + e - s, b + m, c + r}')
  done
  awk -v i="$integrator" -v s="$spp" -v t="$total_t" -v m="$total_mse" -v r="$total_rel" -v n="$runs" \
    'BEGIN{t/=n; m/=n; r/=n; printf "| %s | %d | %.2f | %.3g | %.3g | %.4g | %.4g |\n", i, s, t, m, r, 1/(t*m), 1/(t*r)}'
done
