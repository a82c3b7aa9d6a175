#pragma once
// The CUDA backend of the tracer (trace_cuda.cu): prims and the LBVH built on the GPU, one thread per ray
// with a fixed-size hit list in registers/local memory, gradients summed in a fixed order. Without CUDA
// the call throws goris::Error (GORIS_CUDA_CALL).
#include "render/raster/raster_types.h"
#include "render/trace/trace_build.h"
#include "render/trace/trace_types.h"

namespace goris::trace {

constexpr int kCudaHitsPerRound = 32;  // hits per round on the GPU (the mean hit count of scenes is ~30)

void build_cuda(const GaussiansT<float>& g, PrimData& prims, LbvhData& bvh);
void forward_cuda(const TraceScene<float>& sc, const LbvhView& bvh, const TraceRays& rays, const TraceOutputs& out);
void backward_cuda(const TraceScene<float>& sc, const LbvhView& bvh, const GaussiansT<float>& g,
                   const TraceRays& rays, const TraceOutputGrads& grad_out, const GaussianGradsT<float>& grads,
                   const TraceRayGrads& ray_grads, float* grad_emit, std::size_t budget_bytes);

}  // namespace goris::trace
