// Stand-ins for the CUDA driver in builds without nvcc: a clear error instead of a link failure.
#ifndef GORIS_WITH_CUDA
#include "core/util/error.h"
#include "render/raster/rasterizer_cuda.h"

namespace goris::raster {

void forward_cuda(const GaussiansT<float>&, const Camera&, const RasterSettings&, GBufferT<float>&,
                  RasterStateT<float>&) {
  throw Error("rasterizer", "CUDA device requested but this build has no CUDA backend");
}
void backward_cuda(const GaussiansT<float>&, const RasterStateT<float>&, const GBufferGradT<float>&,
                   const GaussianGradsT<float>&) {
  throw Error("rasterizer", "CUDA device requested but this build has no CUDA backend");
}

}  // namespace goris::raster
#endif
