#pragma once
// The screen-roughness translation net R_s = Net(R, depth, ...) of paper S1.3: a 1x1 convolution from the
// input channels to `features`, `hidden_layers` 3x3 convolutions of `features` channels, each followed by a
// ReLU (the 1x1 input layer too), a 1x1 convolution to one channel and a sigmoid. The default input is
// (roughness, traced reflection depth, 1 / view depth), as in the authors' code; the paper has 2 channels.
//
// All parameters live in ONE flat buffer (and one gradient buffer of the same layout) so that an optimiser
// treats the net as a single group: see train/optimizer/flat_adam.h. Per layer: weights [cout][cin][k][k], then biases.
// T = float on CPU or CUDA; T = double on the CPU (gradient tests).
#include <cstdint>
#include <vector>

#include "core/compute/buffer.h"
#include "render/ssf/conv_kernels.h"
#include "render/ssf/pixel_window.h"

namespace goris::ssf {

struct NetConfig {
  int in_channels = 3;
  int features = 8;
  int hidden_layers = 6;  // paper: 8 layers in all = 1x1 in + 6 x 3x3 + 1x1 out
};

template <class T>
class RoughnessNet {
 public:
  // Parameters are He-initialised from `seed` (normal, std sqrt(2 / fan_in); biases zero).
  RoughnessNet(NetConfig cfg, Device device, std::uint64_t seed);

  void init(std::uint64_t seed);
  const NetConfig& config() const { return cfg_; }
  Device device() const { return device_; }
  int layer_count() const { return int(layers_.size()); }
  std::size_t param_count() const { return params_.size(); }
  // Offset of layer l's weights in the flat buffer; its biases follow the weights.
  std::size_t weight_offset(int l) const { return offsets_.at(std::size_t(l)); }
  int kernel_size(int l) const { return layers_.at(std::size_t(l)).k; }

  Buffer<T>& params() { return params_; }
  const Buffer<T>& params() const { return params_; }
  Buffer<T>& grads() { return grads_; }
  const Buffer<T>& grads() const { return grads_; }
  void zero_grad() { grads_.fill_zero(); }

  // rs ([H][W], in (0, 1)) from input ([in_channels][H][W]); rs is (re)allocated on the net's device. Keeps
  // the activations for backward(). With a window (pixel_window.h; null = the whole image) the net runs on the
  // window alone: rs is exact at the pixels the window was made for and 0 outside the window. Throws
  // goris::Error on a size or device mismatch, a window outside the image, or a NaN/Inf in the input or the
  // parameters.
  void forward(const Buffer<T>& input, int height, int width, Buffer<T>& rs, const PixelWindow* window = nullptr);

  // Adds dL/dparams into grads() and, when grad_input is given, dL/dinput into it, for dL/drs = grad_rs
  // ([H][W], read inside the last forward's window only: zero elsewhere for exact gradients).
  void backward(const Buffer<T>& grad_rs, Buffer<T>* grad_input);

  // How far (in pixels) an input reaches in the output: one per 3x3 layer.
  int receptive_radius() const;

 private:
  ConvShape shape(int l) const;

  NetConfig cfg_;
  Device device_;
  std::vector<ConvShape> layers_;  // h, w filled at forward()
  std::vector<std::size_t> offsets_;
  Buffer<T> params_, grads_;
  int full_h_ = 0, full_w_ = 0;  // the image's size
  PixelWindow window_;           // where the layers run (their images are its size)
  std::vector<Buffer<T>> acts_;  // acts_[0] = input, acts_[l + 1] = output of layer l after its activation
  Buffer<T> g_a_, g_b_, partials_;
};

extern template class RoughnessNet<float>;
extern template class RoughnessNet<double>;

}  // namespace goris::ssf
