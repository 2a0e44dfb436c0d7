#!/usr/bin/env bash
# Strong scaling on one machine (issue 14): the same render as 1 process x 1 thread, 1 process x
# T threads and `mpirun -n T` processes x 1 thread, for path, erpt and pmc-er; whole-process wall
# time, the median of RUNS runs of each, interleaved so that the machine's drift hits all alike.
# Prints a Markdown table with the speed-ups over 1 thread.
# Usage: bench/strong_scaling.sh [SCENE] [T] [RUNS] [INTEGRATORS]   (needs the Release build with
# MPI: build/erpt; INTEGRATORS: a space-separated subset of "path erpt pmc-er", the default)
set -euo pipefail
cd "$(dirname "$0")/.."
scene=${1:-scenes/default/scene.xml} threads=${2:-2} runs=${3:-3} integrators=${4:-path erpt pmc-er}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
mpirun=(mpirun --oversubscribe --allow-run-as-root -n "$threads")

seconds() {  # seconds COMMAND...: wall time of one run
  local start end
  start=$(date +%s.%N)
  "$@" >/dev/null 2>&1
  end=$(date +%s.%N)
  awk -v s="$start" -v e="$end" 'BEGIN{printf "%.3f\n", e - s}'
}
median() { sort -n | awk '{v[NR]=$1} END{print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }

echo "| integrator | 1 process x 1 thread | 1 process x $threads threads | $threads ranks x 1 thread | threads speed-up | ranks speed-up |"
echo "|---|---|---|---|---|---|"
for integrator in $integrators; do
  spp=4
  [ "$integrator" = path ] && spp=32
  render=(build/erpt render "$scene" -q --integrator "$integrator" --spp "$spp" --seed 1)
  : >"$out/one" ; : >"$out/threads" ; : >"$out/ranks"
  for ((k = 0; k < runs; ++k)); do
    seconds "${render[@]}" -o "$out/a.exr" --threads 1 >>"$out/one"
    seconds "${render[@]}" -o "$out/b.exr" --threads "$threads" >>"$out/threads"
    seconds "${mpirun[@]}" "${render[@]}" -o "$out/c.exr" --threads 1 >>"$out/ranks"
  done
  one=$(median <"$out/one") t=$(median <"$out/threads") r=$(median <"$out/ranks")
  awk -v i="$integrator $spp spp" -v o="$one" -v t="$t" -v r="$r" \
    'BEGIN{printf "| %s | %.2f s | %.2f s | %.2f s | %.2fx | %.2fx |\n", i, o, t, r, o / t, o / r}'
done
