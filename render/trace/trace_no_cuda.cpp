// Stand-ins for the CUDA tracer in builds without nvcc: a clear error instead of a link failure.
#ifndef GORIS_WITH_CUDA
#include "core/util/error.h"
#include "render/trace/trace_cuda.h"

namespace goris::trace {

namespace {
[[noreturn]] void no_cuda() { throw Error("tracer", "CUDA device requested but this build has no CUDA backend"); }
}  // namespace

void build_cuda(const GaussiansT<float>&, PrimData&, LbvhData&) { no_cuda(); }
void forward_cuda(const TraceScene<float>&, const LbvhView&, const TraceRays&, const TraceOutputs&) { no_cuda(); }
void backward_cuda(const TraceScene<float>&, const LbvhView&, const GaussiansT<float>&, const TraceRays&,
                   const TraceOutputGrads&, const GaussianGradsT<float>&, const TraceRayGrads&, float*,
                   std::size_t) {
  no_cuda();
}

}  // namespace goris::trace
#endif
