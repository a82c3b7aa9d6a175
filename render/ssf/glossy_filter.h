#pragma once
// Screen-space glossy filter (docs/design/maths.md, Screen-space glossy filter; paper S1.3): a pyramid of an
// image X ([C][H][W] planar, e.g. L_ind rgb and V) where each level is a normal-weighted blur of the previous
// one then x1/2 (odd sizes round up), sampled per pixel at the continuous level l = R_s (L - 1) with bilinear
// upsampling and a linear blend of the two nearest levels. Differentiable in X and R_s; the camera-space
// normals ([3][H][W], any length, zero where empty) only steer the blur weights and are treated as constants
// (no gradient). An optional mass image ([H][W], >= 0) makes it a weighted pyramid (normalised convolution,
// see pyramid_kernels.h): pixels of mass 0 (coarse tracing's untraced pixels) do not enter any level; the
// masses are constants.
//
// T = float on CPU or CUDA; T = double on the CPU (gradient tests). Maths: pyramid_kernels.h.
#include <vector>

#include "core/compute/buffer.h"
#include "render/ssf/pyramid_kernels.h"

namespace goris::ssf {

struct PyramidConfig {
  int levels = 5;        // paper: 5 (level 0 = the input); 2..kMaxLevels
  int normal_power = 8;  // exponent P of max(0, n_p . n_q)^P in the blur weights; 0 = plain Gaussian
};

template <class T>
class GlossyFilter {
 public:
  explicit GlossyFilter(PyramidConfig cfg = {});

  // out = filter(x, normals, rs); out is (re)allocated as [C][H][W] on x's device. Keeps the pyramid and a
  // copy of rs (and of the mass) for backward(). mass: null = unweighted. Throws goris::Error on sizes that do
  // not match C, H, W, buffers on other devices, non-finite values in x, normals, rs or mass, or a negative
  // mass.
  void forward(const Buffer<T>& x, int channels, int height, int width, const Buffer<T>& normals,
               const Buffer<T>& rs, Buffer<T>& out, const Buffer<T>* mass = nullptr);

  // Adds dL/dx ([C][H][W]) and dL/dR_s ([H][W]) for dL/dout = grad_out into the given buffers (either may be
  // null). R_s is clamped to [0, 1]; outside that range its gradient is zero.
  void backward(const Buffer<T>& grad_out, Buffer<T>* grad_x, Buffer<T>* grad_rs);

  const PyramidConfig& config() const { return cfg_; }
  int levels() const { return cfg_.levels; }
  LevelDims dims(int k) const { return dims_.at(size_t(k)); }
  const Buffer<T>& level(int k) const { return image_.at(size_t(k)); }  // [C][h_k][w_k]
  bool weighted() const { return weighted_; }
  const Buffer<T>& mass(int k) const;  // [h_k][w_k] of the last weighted forward (throws when unweighted)

 private:
  PyramidConfig cfg_;
  Device device_ = Device::CPU;
  int channels_ = 0;
  bool weighted_ = false;
  std::vector<LevelDims> dims_;
  std::vector<Buffer<T>> image_, normal_, inv_sum_, mass_, norm_, grad_scratch_;  // norm_[0] unused
  Buffer<T> rs_;
};

extern template class GlossyFilter<float>;
extern template class GlossyFilter<double>;

}  // namespace goris::ssf
