#!/usr/bin/env bash
# The GPU checks in one call, for a machine that has a GPU but none of our Debian packages (the lent
# device): run from the repository root after `./dev device-bundle` made device-bundle/bundle.tar.xz here
# and the call carried the device-bundle folder. Writes everything to $OUT (default: device-out):
#   gpu.txt, devices.txt, tests/<binary>.{log,xml}   the CUDA tests (CUDA vs CPU agreement, gradients)
#   bench_*.txt                                       compute, raster, trace and intrinsic benchmarks
#   demo/                                             an end-to-end intrinsic demo run on CUDA
# Usage: bash tests/gpu/device_check.sh [tests|bench|all]   (default: all)
# Each step has its own time limit, and a failed step does not stop the next one; the exit status is the
# number of failed steps. The limits of `all` add up to more than one 600 s device call: run `tests` and
# `bench` as two calls (what a cut-off call wrote to $OUT still comes back).
set -uo pipefail
what=${1:-all}
OUT=${OUT:-device-out}
B=device-bundle
mkdir -p "$OUT/tests"
failed=0

step() {  # step NAME SECONDS COMMAND... : run with a time limit, log to $OUT/NAME.txt, count failures
  local name=$1 secs=$2
  shift 2
  echo "== $name (limit ${secs}s)"
  local t0=$SECONDS
  timeout "$secs" "$@" >"$OUT/$name.txt" 2>&1
  local rc=$?
  echo "   rc $rc, $((SECONDS - t0)) s"
  tail -n 3 "$OUT/$name.txt" | sed 's/^/   /'
  [ $rc -eq 0 ] || failed=$((failed + 1))
}

if [ ! -x "$B/bin/goris" ]; then
  [ -f "$B/bundle.tar.xz" ] || { echo "device_check: $B/bundle.tar.xz is missing (run ./dev device-bundle and carry $B)" >&2; exit 2; }
  tar -C "$B" -xJf "$B/bundle.tar.xz" 2>/dev/null ||
    python3 -c "import tarfile, sys; tarfile.open(sys.argv[1]).extractall(sys.argv[2])" "$B/bundle.tar.xz" "$B" ||
    { echo "device_check: cannot unpack $B/bundle.tar.xz (neither xz nor python3)" >&2; exit 2; }
fi
export LD_LIBRARY_PATH="$PWD/$B/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
export GORIS_RESOURCE_DIR="$PWD/resources" GORIS_BINARY_DIR="$PWD/$B/scratch"
[ -d "$B/shared" ] && export GORIS_SHARED_DIR="$PWD/$B/shared"
G="$B/bin/goris"

(nvidia-smi -L; nvidia-smi --query-gpu=name,memory.total,driver_version,clocks.max.sm --format=csv) >"$OUT/gpu.txt" 2>&1
step devices 60 "$G" devices

if [ "$what" = tests ] || [ "$what" = all ]; then
  for t in "$B"/bin/test_*; do
    n=$(basename "$t")
    step "tests/$n" 300 "$t" --gtest_output="xml:$OUT/tests/$n.xml"
  done
fi

if [ "$what" = bench ] || [ "$what" = all ]; then
  step bench_compute 120 "$G" bench compute
  step bench_raster 180 "$G" bench raster --device all --res 512 --gaussians 200000
  [ -n "${GORIS_SHARED_DIR:-}" ] && step bench_trace 180 "$G" bench trace --shared "$GORIS_SHARED_DIR" --image 512
  step demo 420 "$G" demo --data "$PWD/resources/default_scene" --device cuda --mode intrinsic --out "$OUT/demo"
  [ -d "$OUT/demo/run" ] && step bench_intrinsic 180 "$G" bench intrinsic "$OUT/demo/run" --device cuda
fi
echo "device_check: $failed step(s) failed; outputs in $OUT"
exit "$failed"
