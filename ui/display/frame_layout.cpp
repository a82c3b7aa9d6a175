#include "ui/display/frame_layout.h"

#include "core/compute/cuda_dispatch.h"
#include "ui/display/frame_layout_ops.h"

namespace goris::ui::frame_layout {

namespace {
constexpr const char* kWho = "display";
}  // namespace

void interleave(Device d, const float* planar, int first, int count, std::size_t hw, float* out, int stride, int at) {
  if (d == Device::CPU) return interleave_on<Device::CPU>(planar, first, count, hw, out, stride, at);
  GORIS_CUDA_CALL(kWho, cuda::interleave(planar, first, count, hw, out, stride, at));
}

void fill(Device d, float* out, std::size_t hw, int stride, int at, float value) {
  if (d == Device::CPU) return fill_on<Device::CPU>(out, hw, stride, at, value);
  GORIS_CUDA_CALL(kWho, cuda::fill(out, hw, stride, at, value));
}

void unit_normals(Device d, const float* normal, const float* alpha, std::size_t hw, float min_alpha, float* out,
                  int stride) {
  if (d == Device::CPU) return unit_normals_on<Device::CPU>(normal, alpha, hw, min_alpha, out, stride);
  GORIS_CUDA_CALL(kWho, cuda::unit_normals(normal, alpha, hw, min_alpha, out, stride));
}

void clamp_unit(Device d, const float* in, std::size_t n, float* out) {
  if (d == Device::CPU) return clamp_unit_on<Device::CPU>(in, n, out);
  GORIS_CUDA_CALL(kWho, cuda::clamp_unit(in, n, out));
}

}  // namespace goris::ui::frame_layout
