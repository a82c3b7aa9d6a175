#!/usr/bin/env bash
# The round-trip table of docs/results/formats.md: file size and max / mean error per attribute of each
# standard format, for a demo's cleaned scene, in both directions through PlayCanvas' splat-transform.
#   tools/formats_table.sh DEMO_OUT [GORIS]      (DEMO_OUT: the folder `./dev demo` wrote, e.g. build/demo)
# Source: DEMO_OUT/cleaned_baked.ply (the baked model); ours: DEMO_OUT/cleaned.{spz,compressed.ply,splat,glb}
# (goris export; splat-transform reads no GLB); errors by `goris info FILE --against cleaned_baked.ply` (Gaussians matched by position).
# Prints docs/results/formats.md on stdout; the converted files go to DEMO_OUT/formats_check.
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

cat <<'TEXT'
# Standard splat formats: sizes and round-trip errors

What each format `goris export` writes (core/io/splat_formats.h states the versions and quantization)
does to the demo's cleaned scene, read back by our readers and by PlayCanvas' splat-transform 2.7.1
(npm, installed by `./dev setup` into tools/node_modules), in both directions.

Made with (CPU, 2 cores; the demo at a short schedule of 500 iterations):

    ./dev setup
    build/bin/goris demo --out build/demo --iters 500 --device cpu   # its export step writes cleaned.{spz,compressed.ply,splat,glb}
    tools/formats_table.sh build/demo

Source: `cleaned_baked.ply`, the baked model of the cleaned scene (first row). Each cell is max / mean
over the Gaussians (paired by nearest position, as compressed PLY reorders them): position as distance in scene units, log scale, rotation as the largest
angle between corresponding principal axes in degrees (q, -q and half-turns about an axis, which leave the
ellipsoid as it is, count as equal), opacity after the sigmoid, SH DC and SH rest coefficients. "written
by / read by": "goris / splat-transform (to PLY)" is our file converted to a 3DGS PLY by splat-transform;
"splat-transform / goris" is its file, written from our source PLY, read by us. splat-transform reads no
GLB, so our GLB is checked by our reader only; its default SPZ is version 4 (zstd), which we do not read
(the error says so), so its SPZ rows use `--spz-version 3`.

TEXT
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
row "glb" "$demo/cleaned.glb" "goris / goris"
node "$st" -q -w "$src" "$work/theirs.glb" >/dev/null
row "glb" "$work/theirs.glb" "splat-transform / goris"
cat <<'TEXT'
Notes:

- The SH rest errors are the formats' quantization: SPZ stores degrees 2 and 3 in 4-bit buckets (up to about
  0.066), compressed PLY in steps of 1/32 (up to 0.0156). `crosscheck.splat_transform_check` measures the
  same on a random model (SH rest in -0.9..0.9), where our decoders and splat-transform's give the same
  SH values. (A radiance demo shorter than the first SH degree step, 1000 iterations, has all-zero SH rest:
  SPZ stores 0 exactly, compressed PLY's `trunc` quantization reads it back as 1/64.)
- `.splat` keeps the colour as 8-bit RGB and no higher SH: a Gaussian brighter than white (a highlight
  baked into the SH DC) is clamped, which is the large SH DC maximum of its rows.
- An SPZ opacity byte of 255 (alpha 1) is an infinite logit in the PLY splat-transform writes from it; our
  PLY reader takes an infinite opacity as the logit our own 8-bit decoders give alpha 1 (half a byte step
  inside it), so the SPZ rows read by us and through splat-transform agree.
- Our reading and splat-transform's of the same SPZ and compressed PLY files agree to float rounding
  (rows two and three of each format are equal). For `.splat` rotations they differ by up to about a
  degree: antimatter15's viewer decodes a byte v as (v - 128) / 128, as we do, splat-transform as
  v / 127.5 - 1.
TEXT
ply_size=$(stat -c %s "$src")
ratio() { awk -v a="$ply_size" -v b="$(stat -c %s "$1")" 'BEGIN { printf "%.3g", a / b }'; }
echo "- Sizes against the PLY: SPZ $(ratio "$demo/cleaned.spz")x smaller, compressed PLY $(ratio "$demo/cleaned.compressed.ply")x," \
  ".splat $(ratio "$demo/cleaned.splat")x (no higher SH), GLB $(ratio "$demo/cleaned.glb")x (float32: lossless but for" \
  "exp/log and sigmoid/logit rounding)."
