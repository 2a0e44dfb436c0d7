#!/bin/bash
# PMC-ER's parameters at equal time (docs/pmc-er.md, "Defaults by measurement"): every
# configuration on four scenes, SEEDS renders of TIME seconds each, relMSE against the
# scenes' references, one CSV line per render (scene,config,seed,relMSE).
#
#   scripts/pmc-sweep.sh TIME SEEDS OUT.csv ['name|render options' ...]
#
# Without configurations it runs ERPT and the PMC-ER defaults. Run from the repository root
# after scripts/build.sh; ../shared/scenes holds the Cornell box.
set -euo pipefail
if [ $# -lt 3 ]; then
  echo "usage: $0 TIME SEEDS OUT.csv ['name|render options' ...]" >&2
  exit 2
fi
time_budget=$1 seeds=$2 out=$3
shift 3
configs=("$@")
[ ${#configs[@]} -gt 0 ] || configs=("erpt|--integrator erpt" "pmc-er|--integrator pmc-er")
# name|scene|reference|width|height|filter|spp (ERPT's and PMC-ER's --spp fix their direct
# pass's share under --time)
scenes=(
  "cornell|../shared/scenes/cornell-box/scene.xml|../shared/scenes/cornell-box/reference-box-128.exr|128|128|box|16"
  "default|scenes/default/scene.xml|tests/data/default-scene-path-64.exr|64|64|tent|32"
  "lamp-in-glass|bench/scenes/lamp-in-glass/scene.xml|bench/scenes/lamp-in-glass/reference-path-64.exr|64|64|box|16"
  "sun-caustic|bench/scenes/sunsky-glass/scene.xml|bench/scenes/sunsky-glass/reference-path-64x48.exr|64|48|box|16"
)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for scene in "${scenes[@]}"; do
  IFS='|' read -r name file reference width height filter spp <<< "$scene"
  for config in "${configs[@]}"; do
    IFS='|' read -r label options <<< "$config"
    for seed in $(seq 1 "$seeds"); do
      # shellcheck disable=SC2086  # options are words
      build/erpt render "$file" $options --spp "$spp" --width "$width" --height "$height" --filter "$filter" \
        --time "$time_budget" --seed "$seed" -q -o "$work/image.exr" > /dev/null 2>&1
      relmse=$(build/erpt diff "$work/image.exr" "$reference" | awk '/^relmse/ {print $2}')
      echo "$name,\"$label\",$seed,$relmse" >> "$out"
    done
  done
done
