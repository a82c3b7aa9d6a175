// Stand-ins for the CUDA cube-map drivers in builds without nvcc: a clear error instead of a link failure.
#ifndef GORIS_WITH_CUDA
#include "core/util/error.h"
#include "render/envmap/environment_map_cuda.h"

namespace goris::envmap::cuda {

namespace {
[[noreturn]] void no_cuda() { throw Error("environment map", "CUDA device requested but this build has no CUDA backend"); }
}  // namespace

void build_chain(const float*, float*, float*, int, int) { no_cuda(); }
void backward_chain(float*, float*, const float*, float*, int, int) { no_cuda(); }
void lookup(const CubeMipsT<float>&, const float*, const float*, std::size_t, float*) { no_cuda(); }
void lookup_backward(const CubeMipsT<float>&, const float*, const float*, const float*, std::size_t, float*, float*,
                     float*) {
  no_cuda();
}

}  // namespace goris::envmap::cuda
#endif
