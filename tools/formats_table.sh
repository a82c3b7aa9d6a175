#!/usr/bin/env bash
# The round-trip table of docs/results/formats.md: file size and max / mean error per attribute of each
# standard format, for a demo's cleaned scene, in both directions through PlayCanvas' splat-transform.
#   tools/formats_table.sh DEMO_OUT [GORIS]      (DEMO_OUT: the folder `./dev demo` wrote, e.g. build/demo)
# Source: DEMO_OUT/cleaned_baked.ply (the baked model); ours: DEMO_OUT/cleaned.{spz,compressed.ply,splat}
# (goris export); errors by `goris info FILE --against cleaned_baked.ply` (Gaussians matched by position).
# Prints markdown on stdout; the converted files go to DEMO_OUT/formats_check.
set -euo pipefail
cd "$(dirname "$0")/.."
demo=${1:?usage: tools/formats_table.sh DEMO_OUT [GORIS]}
goris=${2:-build/bin/goris}
st=tools/node_modules/.bin/splat-transform
[ -x "$st" ] || { echo "formats_table: $st is missing (./dev setup installs it)" >&2; exit 1; }
src="$demo/cleaned_baked.ply"
work="$demo/formats_check"
mkdir -p "$work"

# One table row: label, the file compared with the source, how it was made / read, the file whose size counts.
row() {
  local label=$1 file=$2 how=$3 sized=${4:-$2}
  local size
  size=$(stat -c %s "$sized")
  "$goris" info "$file" --against "$src" | awk -v label="$label" -v how="$how" -v size="$size" '
    /^  (position|scale|rotation|opacity|f_dc|f_rest) +max/ { v[$1] = sprintf("%.3g / %.3g", $3, $5) }
    END { printf "| %s | %s | %d | %s | %s | %s | %s | %s | %s |\n", label, how, size, v["position"], v["scale"],
          v["rotation"], v["opacity"], v["f_dc"], v["f_rest"] }'
}

echo "| format | written by / read by | bytes | position | log scale | rotation (deg) | opacity | SH DC | SH rest |"
echo "|---|---|---:|---|---|---|---|---|---|"
row "3DGS PLY (source)" "$src" "goris / goris"
for f in spz compressed.ply splat; do
  ours="$demo/cleaned.$f"
  row "$f" "$ours" "goris / goris"
  node "$st" -q -w "$ours" "$work/ours.$f.ply" >/dev/null
  row "$f" "$work/ours.$f.ply" "goris / splat-transform (to PLY)" "$ours"
done
node "$st" -q -w --spz-version 3 "$src" "$work/theirs.spz" >/dev/null
row "spz" "$work/theirs.spz" "splat-transform / goris"
node "$st" -q -w "$src" "$work/theirs.compressed.ply" >/dev/null
row "compressed.ply" "$work/theirs.compressed.ply" "splat-transform / goris"
