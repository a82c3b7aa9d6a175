// CUDA twin of the frame layout passes (frame_layout_ops.h on Device::CUDA), checked after each launch.
// No synchronisation here: the frame's depth download (and the interop copy on the default stream) orders them.
#include "ui/display/frame_layout_ops.h"

namespace goris::ui::frame_layout::cuda {

void interleave(const float* planar, int first, int count, std::size_t hw, float* out, int stride, int at) {
  interleave_on<Device::CUDA>(planar, first, count, hw, out, stride, at);
}
void fill(float* out, std::size_t hw, int stride, int at, float value) {
  fill_on<Device::CUDA>(out, hw, stride, at, value);
}
void unit_normals(const float* normal, const float* alpha, std::size_t hw, float min_alpha, float* out, int stride) {
  unit_normals_on<Device::CUDA>(normal, alpha, hw, min_alpha, out, stride);
}
void clamp_unit(const float* in, std::size_t n, float* out) { clamp_unit_on<Device::CUDA>(in, n, out); }

}  // namespace goris::ui::frame_layout::cuda
