#!/usr/bin/env bash
# Heavy-tailed runs: relMSE of ten seeds of each configuration against a scene's reference, with
# the median and the worst run over the median (docs/bdpt.md, "Measurements").
# Usage: scripts/seed-outliers.sh SCENE.xml REFERENCE.exr SIZE SPP [erpt|pmc-er|bdpt|path ...]
set -euo pipefail
cd "$(dirname "$0")/.."
scene=$1 reference=$2 size=$3 spp=$4
shift 4
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for config in "$@"; do
  values=()
  for seed in 1 2 3 4 5 6 7 8 9 10; do
    # shellcheck disable=SC2086  # a configuration is an integrator and its options
    build/erpt render "$scene" -q -D res="$size" --width "$size" --height "$size" --spp "$spp" --seed "$seed" \
      --integrator $config -o "$out/r.exr" 2>/dev/null
    values+=("$(build/erpt diff "$out/r.exr" "$reference" | awk '$1 == "relmse" { print $2 }')")
  done
  printf '%s\n' "${values[@]}" | sort -g | awk -v c="$config" '
    { v[NR] = $1 } END { m = (v[5] + v[6]) / 2; printf "%-32s median %.4g  worst %.4g (%.2fx)\n", c, m, v[NR], v[NR] / m }'
done
