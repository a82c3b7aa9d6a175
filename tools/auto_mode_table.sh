#!/usr/bin/env bash
# What `--mode auto` decides on trained radiance runs: `goris detect` on each, as a Markdown table (the
# view-dependent share, the planes found, the share of the evidence in front of each plane, the share of what
# lies behind the mirror-world plane that mirrors what stands in front of it, the decision).
# Usage: tools/auto_mode_table.sh GORIS BENCH_OUT [EXTRA_RUN ...]
#   BENCH_OUT: a `goris bench pipeline --suite generalization --out DIR` folder (its stage1_radiance runs);
#   EXTRA_RUN: further run folders with checkpoints (e.g. a radiance run of a real capture).
set -euo pipefail
goris=$1 out=$2
shift 2
echo "| run | view-dependent % | planes kept | in front of each plane found | mirror world: behind mirrored | decision |"
echo "|---|--:|--:|---|--:|---|"
for run in "$out"/runs/*/medium/stage1_radiance/run "$@"; do
  [ -d "$run" ] || continue
  case $run in
    "$out"/runs/*) name=$(basename "$(dirname "$(dirname "$(dirname "$run")")")") ;;
    */run) name=$(basename "$(dirname "$run")") ;;
    *) name=$(basename "$run") ;;
  esac
  text=$("$goris" detect "$run")
  head=$(grep -m1 'look view-dependent' <<<"$text")
  pct=$(sed -E 's/.*: ([0-9.]+) % of the covered pixels.*/\1/' <<<"$head")
  kept=$(sed -E 's/.* ([0-9]+) plane\(s\).*/\1/' <<<"$head")
  decision=$(sed -E 's/.*-> ([a-z]+)$/\1/' <<<"$head")
  front=$(grep 'plane fit' <<<"$text" | sed -E 's/plane fit [0-9]+: ([0-9.]+) %.*/\1 %/' | paste -sd, - || true)
  mirror=$(grep -m1 '^mirror world' <<<"$text" | grep 'of those behind it' |
           sed -E 's/.*, ([0-9]+) % of those behind it.*-> ([a-z]+).*/\1 % (\2)/' || true)
  echo "| $name | $pct | $kept | ${front:--} | ${mirror:--} | $decision |"
done
