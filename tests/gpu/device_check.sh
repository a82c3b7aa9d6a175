#!/usr/bin/env bash
# The GPU checks in one call, for a machine that has a GPU but none of our Debian packages (the lent
# device): run from the repository root after `./dev device-bundle` made device-bundle/bundle.tar.xz here
# and the call carried the device-bundle folder. Data sets for the pipeline bench are optional: put
# half-size copies under device-bundle/data/ (tests/gpu/half_size_dataset.py; the carry limit is 64 MiB).
#
# Usage: DEADLINE=SECONDS bash tests/gpu/device_check.sh [tests] [bench] [big] [pipeline] [all]
#   (default: all, 560 s; steps run in this order)
#   tests     the CUDA tests (CUDA vs CPU agreement, gradients, repeatability), in 8 shards side by side
#   bench     the raster (512 px, 200K Gaussians), trace (512 px) and compute benchmarks
#   big       the pipeline bench on CUDA over device-bundle/big/* at the data's own resolution (BIG_CONFIGS,
#             default full; BIG_SCHEDULE, default medium), then the intrinsic benchmark on its `full` run:
#             a 512 px, 100-view glossy-table scene end to end (make it here with `goris synth
#             --preset glossy-table --res 512 --train 100 --test 20 --spp 32 --no-gt --out
#             device-bundle/big/glossy_table_512`; the bundle, data/ and big/ together come close to the
#             64 MiB a device call may carry: carry bundle.tar.xz with one of them if it grows)
#   pipeline  the pipeline bench on CUDA over device-bundle/data/* (PIPELINE_CONFIGS, default
#             baseline,full,auto; medium schedule), then the intrinsic benchmark on a `full` run at its
#             resolution and at 512 px, its parallel_for launch sites (--kernels) and, where ncu exists,
#             a table of every kernel of one 512 px iteration
#
# Durations seen on an H200 (docs/lab/bench/cuda_h200.md), for planning a 15-minute device budget: machine
# start and carry about 35 s; tests 2 s (side by side); bench 90 s (trace 85 of it); pipeline with baseline,
# full, auto and distilled on the three 128 px scenes 221 s, with all configurations about 600 s. Ask for
# everything in one call: the machine is handed back after 30 s idle, so a second call usually pays for a new
# start.
#
# Every step gets its own time limit, cut to what is left before DEADLINE, and a failed step does not stop
# the next. The device returns at most 8 files from $OUT, so the logs go to a work folder that is packed
# into $OUT/device_check.tgz after every step (a call cut off still returns what had finished); the step
# summary is $OUT/summary.txt. The exit status is the number of failed steps.
# The archive holds gpu.txt, devices.txt, tests/<binary>.<shard>.{txt,xml}, bench_*.txt and pipeline/ (results,
# charts and each run's result.json).
set -uo pipefail
what=" ${*:-all} "
wants() { [[ $what == *" $1 "* || $what == *" all "* ]]; }
OUT=${OUT:-device-out}
DEADLINE=${DEADLINE:-560}
B=device-bundle
W=$(mktemp -d)
mkdir -p "$OUT" "$W/tests"
failed=0

pack() {  # the small files of the work folder into one archive in $OUT (a returned file has at most 16 MiB):
  # no checkpoints or PLYs, and of the pipeline's run folders only each run's result.json and logs
  (cd "$W" && find . -type f -size -4M ! -name '*.ckpt*' ! -name '*.ply' \
    \( ! -path './*/runs/*' -o -name result.json -o -name '*.log' \) -print0 |
    tar -czf "$OUT/device_check.tgz.tmp" --null -T - && mv "$OUT/device_check.tgz.tmp" "$OUT/device_check.tgz")
}
left() { echo $((DEADLINE - SECONDS)); }
note() { echo "$*" | tee -a "$OUT/summary.txt"; }

step() {  # step NAME SECONDS COMMAND... : run with a time limit (cut to the deadline), log to NAME.txt
  local name=$1 secs=$2
  shift 2
  local l
  l=$(left)
  [ "$secs" -gt $((l - 10)) ] && secs=$((l - 10))
  if [ "$secs" -lt 5 ]; then
    note "== $name: skipped, the deadline is near"
    return
  fi
  local t0=$SECONDS
  timeout "$secs" "$@" >"$W/$name.txt" 2>&1
  local rc=$?
  note "== $name (limit ${secs}s): rc $rc, $((SECONDS - t0)) s"
  tail -n 3 "$W/$name.txt" | sed 's/^/   /' | tee -a "$OUT/summary.txt"
  [ $rc -eq 0 ] || failed=$((failed + 1))
  pack
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
G="$PWD/$B/bin/goris"

(nvidia-smi -L; nvidia-smi --query-gpu=name,memory.total,driver_version,clocks.max.sm --format=csv; nproc) >"$W/gpu.txt" 2>&1
cp "$W/gpu.txt" "$OUT/gpu.txt"
step devices 60 "$G" devices

if wants tests; then
  # Side by side: the tests are mostly CPU reference work and the device has 16 cores, so every test binary
  # runs as 8 GoogleTest shards at once (the bundle has one binary, test_gpu_all).
  t0=$SECONDS
  limit=$(($(left) - 20 < 200 ? $(left) - 20 : 200))
  shards=8
  for t in "$B"/bin/test_*; do
    for i in $(seq 0 $((shards - 1))); do
      n=$(basename "$t").$i
      (GTEST_TOTAL_SHARDS=$shards GTEST_SHARD_INDEX=$i timeout "$limit" "$t" --gtest_output="xml:$W/tests/$n.xml" \
        >"$W/tests/$n.txt" 2>&1; echo $? >"$W/tests/$n.rc") &
    done
  done
  wait
  for rc in "$W"/tests/*.rc; do
    n=$(basename "$rc" .rc)
    note "== tests/$n: rc $(cat "$rc"), $(grep -E '^\[  (PASSED|FAILED|SKIPPED) ' "$W/tests/$n.txt" | tr '\n' ' ')"
    [ "$(cat "$rc")" = 0 ] || failed=$((failed + 1))
  done
  note "   tests took $((SECONDS - t0)) s side by side (limit ${limit}s each)"
  pack
fi

if wants bench; then
  step bench_raster 90 "$G" bench raster --device all --res 512 --gaussians 200000
  [ -n "${GORIS_SHARED_DIR:-}" ] && step bench_trace 90 "$G" bench trace --shared "$GORIS_SHARED_DIR" --image 512
  step bench_compute 60 "$G" bench compute
fi

# The time split of one intrinsic iteration on a `full` run under $1 at the run's resolution (step names
# get $2 appended), and at 512 px (the traced shading frame rate).
bench_intrinsic_of() {
  local run
  run=$(find "$1" -path '*/full/run' -type d 2>/dev/null | sort -r | head -n 1)
  [ -n "$run" ] || return 0
  step "bench_intrinsic$2" 30 "$G" bench intrinsic "$run" --device cuda
  step "bench_intrinsic_512$2" 30 "$G" bench intrinsic "$run" --device cuda --resolution 512
  LAST_FULL_RUN=$run
}

if wants big; then
  big=()
  for d in "$B"/big/*/; do [ -f "$d/transforms_train.json" ] && big+=("$PWD/${d%/}"); done
  if [ ${#big[@]} -gt 0 ]; then
    step big $(($(left) - 60)) "$G" bench pipeline --data "${big[@]}" --configs "${BIG_CONFIGS:-full}" \
      --schedule "${BIG_SCHEDULE:-medium}" --device cuda --out "$W/big"
    bench_intrinsic_of "$W/big/runs" _big
  fi
fi

if wants pipeline; then
  data=()
  for d in "$B"/data/*/; do [ -f "$d/transforms_train.json" ] && data+=("$PWD/${d%/}"); done
  if [ ${#data[@]} -gt 0 ]; then
    step pipeline $(($(left) - 150)) "$G" bench pipeline --data "${data[@]}" --configs "${PIPELINE_CONFIGS:-baseline,full,auto}" \
      --schedule medium --init-points 30000 --device cuda --out "$W/pipeline"
    # The intrinsic benchmark on a `full` run (steel_snowman's when there is one), the time of each
    # parallel_for launch site at 512 px (--kernels), and where ncu exists a table of every kernel.
    LAST_FULL_RUN=
    bench_intrinsic_of "$W/pipeline/runs" ""
    run=$LAST_FULL_RUN
    if [ -n "$run" ]; then
      step kernels_512 30 "$G" bench intrinsic "$run" --device cuda --resolution 512 --repeats 2 --kernels
      if command -v ncu >/dev/null; then
        step profile_512 80 ncu --csv --metrics gpu__time_duration.sum --log-file "$W/profile_512.csv" \
          "$G" bench intrinsic "$run" --device cuda --resolution 512 --repeats 1
        python3 "$PWD/tests/gpu/kernel_table.py" "$W/profile_512.csv" >"$W/profile_512_kernels.md" 2>&1
      fi
    fi
  fi
fi
note "device_check: $failed step(s) failed; $((SECONDS)) s"
pack
exit "$failed"
