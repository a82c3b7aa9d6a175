#include "render/ssf/roughness_net.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <type_traits>

#include "core/compute/cuda_dispatch.h"
#include "core/compute/memory.h"
#include "core/compute/primitives.h"
#include "render/ssf/conv_passes.h"
#include "render/ssf/ssf_checks.h"
#include "render/ssf/ssf_cuda.h"

namespace goris::ssf {

namespace {

constexpr const char* kOp = "roughness net";

template <class T>
void ensure(Buffer<T>& b, std::size_t n, Device d) {
  if (b.size() != n || b.device() != d) b = Buffer<T>(n, d);
}

// Scratch of at least n values: the window changes size from one view to the next, and reallocating the
// layers' buffers every iteration would cost more than it saves (a device allocation each on CUDA).
template <class T>
void reserve(Buffer<T>& b, std::size_t n, Device d) {
  if (b.size() < n || b.device() != d) b = Buffer<T>(n, d);
}

// The layer passes on the net's device; CUDA only exists for float.
template <class T>
struct Layers {
  Device d;
  void conv(const ConvShape& s, const T* in, const T* w, const T* b, T* out) const {
    if (d == Device::CPU) return conv_forward<Device::CPU>(s, in, w, b, out);
    if constexpr (std::is_same_v<T, float>) GORIS_CUDA_CALL(kOp, cuda::conv_forward(s, in, w, b, out));
  }
  void conv_input(const ConvShape& s, const T* w, const T* g_out, T* g_in) const {
    if (d == Device::CPU) return conv_backward_input<Device::CPU>(s, w, g_out, g_in);
    if constexpr (std::is_same_v<T, float>) GORIS_CUDA_CALL(kOp, cuda::conv_backward_input(s, w, g_out, g_in));
  }
  void conv_params(const ConvShape& s, const T* in, const T* g_out, T* partials, T* g_w, T* g_b) const {
    if (d == Device::CPU) return conv_backward_params<Device::CPU>(s, in, g_out, partials, g_w, g_b);
    if constexpr (std::is_same_v<T, float>)
      GORIS_CUDA_CALL(kOp, cuda::conv_backward_params(s, in, g_out, partials, g_w, g_b));
  }
  void relu(T* x, std::size_t n) const {
    if (d == Device::CPU) return relu_forward<Device::CPU>(x, n);
    if constexpr (std::is_same_v<T, float>) GORIS_CUDA_CALL(kOp, cuda::relu_forward(x, n));
  }
  void relu_back(const T* y, T* g, std::size_t n) const {
    if (d == Device::CPU) return relu_backward<Device::CPU>(y, g, n);
    if constexpr (std::is_same_v<T, float>) GORIS_CUDA_CALL(kOp, cuda::relu_backward(y, g, n));
  }
  void sigmoid(const T* z, T* y, std::size_t n) const {
    if (d == Device::CPU) return sigmoid_forward<Device::CPU>(z, y, n);
    if constexpr (std::is_same_v<T, float>) GORIS_CUDA_CALL(kOp, cuda::sigmoid_forward(z, y, n));
  }
  void sigmoid_back(const T* y, T* g, std::size_t n) const {
    if (d == Device::CPU) return sigmoid_backward<Device::CPU>(y, g, n);
    if constexpr (std::is_same_v<T, float>) GORIS_CUDA_CALL(kOp, cuda::sigmoid_backward(y, g, n));
  }
  void add(const T* a, T* acc, std::size_t n) const { add_into(d, a, acc, n); }
  void crop(const T* src, int channels, int width, int height, PixelWindow w, T* dst) const {
    if (d == Device::CPU)
      return window_pass<Device::CPU, WindowOp::CopyOut>(src, channels, width, height, w, dst);
    if constexpr (std::is_same_v<T, float>) GORIS_CUDA_CALL(kOp, cuda::copy_window(src, channels, width, height, w, dst));
  }
  void add_to_window(const T* src, int channels, int width, int height, PixelWindow w, T* dst) const {
    if (d == Device::CPU)
      return window_pass<Device::CPU, WindowOp::AddIn>(dst, channels, width, height, w, src);
    if constexpr (std::is_same_v<T, float>) GORIS_CUDA_CALL(kOp, cuda::add_window(src, channels, width, height, w, dst));
  }
};

}  // namespace

template <class T>
RoughnessNet<T>::RoughnessNet(NetConfig cfg, Device device, std::uint64_t seed) : cfg_(cfg), device_(device) {
  if (cfg.in_channels < 1 || cfg.in_channels > kMaxConvChannels || cfg.features < 1 ||
      cfg.features > kMaxConvChannels || cfg.hidden_layers < 0)
    throw Error(kOp, "channels must be in [1, " + std::to_string(kMaxConvChannels) +
                         "] and hidden_layers >= 0 (got in_channels " + std::to_string(cfg.in_channels) +
                         ", features " + std::to_string(cfg.features) + ", hidden_layers " +
                         std::to_string(cfg.hidden_layers) + ")");
  if (device == Device::CUDA && !std::is_same_v<T, float>) throw Error(kOp, "double precision runs on the CPU only");
  layers_.push_back(ConvShape{cfg.in_channels, cfg.features, 1});
  for (int i = 0; i < cfg.hidden_layers; ++i) layers_.push_back(ConvShape{cfg.features, cfg.features, 3});
  layers_.push_back(ConvShape{cfg.features, 1, 1});
  std::size_t n = 0;
  for (const ConvShape& s : layers_) {
    offsets_.push_back(n);
    n += std::size_t(s.weight_count() + s.cout);
  }
  params_ = Buffer<T>(n, device);
  grads_ = Buffer<T>(n, device);
  grads_.fill_zero();
  init(seed);
}

template <class T>
void RoughnessNet<T>::init(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<T> host(params_.size(), T(0));
  for (std::size_t l = 0; l < layers_.size(); ++l) {
    const ConvShape& s = layers_[l];
    std::normal_distribution<double> normal(0.0, std::sqrt(2.0 / double(s.cin * s.k * s.k)));
    for (int i = 0; i < s.weight_count(); ++i) host[offsets_[l] + std::size_t(i)] = T(normal(rng));
  }
  params_.upload(host.data(), host.size());
}

template <class T>
ConvShape RoughnessNet<T>::shape(int l) const {
  ConvShape s = layers_[std::size_t(l)];
  s.h = window_.height();
  s.w = window_.width();
  return s;
}

template <class T>
int RoughnessNet<T>::receptive_radius() const {
  int r = 0;
  for (const ConvShape& s : layers_) r += s.k / 2;
  return r;
}

template <class T>
void RoughnessNet<T>::forward(const Buffer<T>& input, int height, int width, Buffer<T>& rs, const PixelWindow* window) {
  if (height < 1 || width < 1)
    throw Error(kOp, "image size " + std::to_string(width) + "x" + std::to_string(height) + " is empty");
  const std::size_t plane = std::size_t(height) * std::size_t(width);
  check_buffer(kOp, "input", input, std::size_t(cfg_.in_channels) * plane, device_);
  check_finite(kOp, "input", input);
  check_finite(kOp, "parameters", params_);
  PixelWindow win{0, 0, width, height};
  if (window && !window->covers(width, height)) {
    if (window->empty() || window->x0 < 0 || window->y0 < 0 || window->x1 > width || window->y1 > height)
      throw Error(kOp, "window [" + std::to_string(window->x0) + ", " + std::to_string(window->x1) + ") x [" +
                           std::to_string(window->y0) + ", " + std::to_string(window->y1) +
                           ") is empty or outside the " + std::to_string(width) + "x" + std::to_string(height) +
                           " image");
    win = *window;
  }
  const bool whole = win.covers(width, height);
  full_h_ = height;
  full_w_ = width;
  window_ = win;
  const std::size_t wplane = std::size_t(win.height()) * std::size_t(win.width());
  const Layers<T> run{device_};
  const int L = layer_count();
  acts_.resize(std::size_t(L) + 1);
  reserve(acts_[0], std::size_t(cfg_.in_channels) * wplane, device_);
  if (whole)
    device_copy(acts_[0].data(), device_, input.data(), device_, input.bytes());
  else
    run.crop(input.data(), cfg_.in_channels, width, height, win, acts_[0].data());
  for (int l = 0; l < L; ++l) {
    const ConvShape s = shape(l);
    Buffer<T>& out = acts_[std::size_t(l) + 1];
    const std::size_t n = std::size_t(s.cout) * wplane;
    reserve(out, n, device_);
    const T* w = params_.data() + offsets_[std::size_t(l)];
    run.conv(s, acts_[std::size_t(l)].data(), w, w + s.weight_count(), out.data());
    if (l + 1 < L) {
      run.relu(out.data(), n);
      continue;
    }
    run.sigmoid(out.data(), out.data(), n);
  }
  ensure(rs, plane, device_);
  if (whole) {
    device_copy(rs.data(), device_, acts_.back().data(), device_, rs.bytes());
    return;
  }
  rs.fill_zero();
  run.add_to_window(acts_.back().data(), 1, width, height, win, rs.data());
}

template <class T>
void RoughnessNet<T>::backward(const Buffer<T>& grad_rs, Buffer<T>* grad_input) {
  if (acts_.empty()) throw Error(kOp, "backward() called before forward()");
  const std::size_t full_plane = std::size_t(full_h_) * std::size_t(full_w_);
  check_buffer(kOp, "screen roughness gradient", grad_rs, full_plane, device_);
  if (grad_input)
    check_buffer(kOp, "input gradient", *grad_input, std::size_t(cfg_.in_channels) * full_plane, device_);
  const bool whole = window_.covers(full_w_, full_h_);
  const std::size_t plane = std::size_t(window_.height()) * std::size_t(window_.width());
  const Layers<T> run{device_};
  const int L = layer_count();
  std::size_t widest = 0, most_params = 0;
  for (int l = 0; l < L; ++l) {
    widest = std::max(widest, std::size_t(std::max(layers_[std::size_t(l)].cin, layers_[std::size_t(l)].cout)));
    most_params = std::max(most_params, std::size_t(layers_[std::size_t(l)].weight_count() + layers_[std::size_t(l)].cout));
  }
  reserve(g_a_, widest * plane, device_);
  reserve(g_b_, widest * plane, device_);
  reserve(partials_, most_params * std::size_t(window_.height()), device_);
  // g_a_ holds dL/d(output of layer l) before its activation is undone; g_b_ receives dL/d(its input).
  if (whole)
    device_copy(g_a_.data(), device_, grad_rs.data(), device_, grad_rs.bytes());
  else
    run.crop(grad_rs.data(), 1, full_w_, full_h_, window_, g_a_.data());
  run.sigmoid_back(acts_.back().data(), g_a_.data(), plane);
  for (int l = L - 1; l >= 0; --l) {
    const ConvShape s = shape(l);
    const std::size_t off = offsets_[std::size_t(l)];
    const T* w = params_.data() + off;
    T* gw = grads_.data() + off;
    run.conv_params(s, acts_[std::size_t(l)].data(), g_a_.data(), partials_.data(), gw, gw + s.weight_count());
    if (l == 0 && !grad_input) break;
    run.conv_input(s, w, g_a_.data(), g_b_.data());
    if (l > 0) {
      run.relu_back(acts_[std::size_t(l)].data(), g_b_.data(), std::size_t(s.cin) * plane);
      std::swap(g_a_, g_b_);
    } else if (whole) {
      run.add(g_b_.data(), grad_input->data(), grad_input->size());
    } else {
      run.add_to_window(g_b_.data(), cfg_.in_channels, full_w_, full_h_, window_, grad_input->data());
    }
  }
}

template class RoughnessNet<float>;
template class RoughnessNet<double>;

}  // namespace goris::ssf
