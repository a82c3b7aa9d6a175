#!/usr/bin/env bash
# Fails when a function that learns the device at run time (a goris::Device, Buffer or RasterStateT
# parameter) is defined as a shared (weak) symbol by both a CUDA object (.cu.o) and a host object (.cpp.o) of the build. The linker
# keeps one of the two copies, and the host copy throws for Device::CUDA (parallel_for.h): CUDA calls would
# then fail or run the wrong code depending on the link order. Such headers belong inside
# GORIS_BACKEND_NAMESPACE_BEGIN/END (core/compute/hd.h). Usage: check_backend_symbols.sh BUILD_DIR
set -euo pipefail
build=${1:?usage: check_backend_symbols.sh BUILD_DIR}
command -v nm >/dev/null || { echo "check_backend_symbols: nm (binutils) is not installed" >&2; exit 2; }
runtime_device_functions() {  # weak goris functions with a Device, Buffer or raster state parameter
  find "$build" -name "*.$1.o" -print0 | xargs -0 -r -n 50 nm -C --defined-only 2>/dev/null |
    awk '$2 == "W" { $1 = ""; $2 = ""; print substr($0, 3) }' |
    grep -E '[(,] ?(goris::Device(,|\)([^0-9]|$))|goris::Buffer<|goris::raster::RasterStateT<)' |
    grep -v -e '{lambda' -e '^tbb::' -e '^void tbb::' -e '^goris::Buffer<' -e 'goris::Buffer<[^>]*>::' | sort -u
}
cu=$(runtime_device_functions cu)
if [ -z "$cu" ]; then
  echo "check_backend_symbols: no CUDA objects with device-generic functions in $build (CUDA off?); nothing to check"
  exit 0
fi
both=$(comm -12 <(echo "$cu") <(runtime_device_functions cpp))
if [ -n "$both" ]; then
  echo "check_backend_symbols: these functions are defined by both nvcc and host objects; wrap their header in"
  echo "GORIS_BACKEND_NAMESPACE_BEGIN/END so a CUDA call cannot land in the host copy:"
  echo "$both" | cut -c1-300
  exit 1
fi
echo "check_backend_symbols: $(echo "$cu" | wc -l) device-generic functions in CUDA objects, none shared with host objects"
