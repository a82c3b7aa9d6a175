#pragma once
// The CUDA rasterizer driver (rasterizer_cuda.cu). Without CUDA the call throws goris::Error (GORIS_CUDA_CALL).
#include "render/raster/raster_types.h"

namespace goris::raster {

void forward_cuda(const GaussiansT<float>& g, const Camera& cam, const RasterSettings& settings, GBufferT<float>& out,
                  RasterStateT<float>& st);
void backward_cuda(const GaussiansT<float>& g, const RasterStateT<float>& st, const GBufferGradT<float>& grad_out,
                   const GaussianGradsT<float>& out);

}  // namespace goris::raster
