#pragma once
// The roughness net's layers over whole images, written once with parallel_for and instantiated on the CPU
// (roughness_net.cpp, float and double) and on CUDA (ssf_cuda.cu, float). The CPU works a row per task (the
// register-blocked kernels of conv_cpu_blocked.h for multiples of 8 channels, else the *_row kernels), CUDA a
// pixel per thread. Parameter gradients are reduced per row into
// partials [H][params] and then summed over rows: deterministic, no atomics.
#include <cmath>
#include <cstddef>
#include <vector>

#include "core/compute/parallel_for.h"
#include "render/ssf/conv_cpu_blocked.h"
#include "render/ssf/conv_kernels.h"
#include "render/ssf/pixel_window.h"

namespace goris::ssf {

template <Device D, class T>
void conv_forward(const ConvShape& s, const T* in, const T* w, const T* b, T* out) {
  if constexpr (D == Device::CPU) {
    if (s.cout % kBlock == 0)
      parallel_for(D, std::size_t(s.h), [=](std::size_t y) {
        for (int co0 = 0; co0 < s.cout; co0 += kBlock) conv_forward_row_blocked(s, in, w, b, out, int(y), co0);
      }, 4);
    else
      parallel_for(D, std::size_t(s.h), [=](std::size_t y) { conv_forward_row(s, in, w, b, out, int(y)); }, 4);
  } else {
    parallel_for(D, s.plane(), [=] GORIS_HD(std::size_t p) {
      conv_forward_pixel(s, in, w, b, out, int(p / s.w), int(p % s.w));
    });
  }
}

// Writes g_in ([cin][H][W]).
template <Device D, class T>
void conv_backward_input(const ConvShape& s, const T* w, const T* g_out, T* g_in) {
  if constexpr (D == Device::CPU) {
    if (s.cin % kBlock == 0) {
      // The transposed convolution as a forward convolution of g_out with flipped weights and no bias.
      std::vector<T> flip(std::size_t(s.weight_count())), zero(std::size_t(s.cin), T(0));
      flip_weights(s, w, flip.data());
      const ConvShape t{s.cout, s.cin, s.k, s.h, s.w};
      conv_forward<D>(t, g_out, flip.data(), zero.data(), g_in);
    } else {
      parallel_for(D, std::size_t(s.h), [=](std::size_t y) { conv_grad_input_row(s, w, g_out, g_in, int(y)); }, 4);
    }
  } else {
    parallel_for(D, s.plane(), [=] GORIS_HD(std::size_t p) {
      conv_grad_input_pixel(s, w, g_out, g_in, int(p / s.w), int(p % s.w));
    });
  }
}

// Adds dL/dw and dL/db into g_w, g_b; row_partials holds H * (weights + cout) values of scratch.
template <Device D, class T>
void conv_backward_params(const ConvShape& s, const T* in, const T* g_out, T* row_partials, T* g_w, T* g_b) {
  const int np = s.weight_count() + s.cout, nw = s.weight_count(), h = s.h;
  if constexpr (D == Device::CPU) {
    if (s.cout % kBlock == 0)
      parallel_for(D, std::size_t(h), [=](std::size_t y) {
        conv_param_grad_row_blocked(s, in, g_out, int(y), row_partials + y * np);
      }, 4);
    else
      parallel_for(D, std::size_t(h), [=](std::size_t y) {
        for (int p = 0; p < np; ++p) row_partials[y * np + p] = conv_param_grad_row(s, in, g_out, p, int(y));
      }, 4);
  } else {
    parallel_for(D, std::size_t(h) * np, [=] GORIS_HD(std::size_t i) {
      row_partials[i] = conv_param_grad_row(s, in, g_out, int(i % np), int(i / np));
    });
  }
  parallel_for(D, std::size_t(np), [=] GORIS_HD(std::size_t p) {
    T acc = T(0);
    for (int y = 0; y < h; ++y) acc += row_partials[std::size_t(y) * np + p];
    if (int(p) < nw)
      g_w[p] += acc;
    else
      g_b[int(p) - nw] += acc;
  }, 16);
}

template <Device D, class T>
void relu_forward(T* x, std::size_t n) {
  parallel_for(D, n, [=] GORIS_HD(std::size_t i) { x[i] = x[i] > T(0) ? x[i] : T(0); }, 8192);
}

// g *= (y > 0) where y is the ReLU's output.
template <Device D, class T>
void relu_backward(const T* y, T* g, std::size_t n) {
  parallel_for(D, n, [=] GORIS_HD(std::size_t i) { g[i] = y[i] > T(0) ? g[i] : T(0); }, 8192);
}

template <Device D, class T>
void sigmoid_forward(const T* z, T* y, std::size_t n) {
  parallel_for(D, n, [=] GORIS_HD(std::size_t i) {
    using std::exp;
    y[i] = T(1) / (T(1) + exp(-z[i]));
  }, 8192);
}

// g *= y (1 - y) where y is the sigmoid's output.
template <Device D, class T>
void sigmoid_backward(const T* y, T* g, std::size_t n) {
  parallel_for(D, n, [=] GORIS_HD(std::size_t i) { g[i] *= y[i] * (T(1) - y[i]); }, 8192);
}

// Between an image ([C][H][W] with row length `width`) and its window ([C][window rows][window columns]):
// CopyOut: window = the image's pixels there; AddIn: the image's pixels there += window.
enum class WindowOp { CopyOut, AddIn };

template <Device D, WindowOp Op, class Image, class Window>
void window_pass(Image* image, int channels, int width, int height, PixelWindow win, Window* window) {
  const int ww = win.width(), wh = win.height();
  const std::size_t plane = std::size_t(width) * std::size_t(height), wplane = std::size_t(ww) * std::size_t(wh);
  // Explicit captures: nvcc's device lambdas may not first capture a variable inside `if constexpr`.
  parallel_for(D, std::size_t(channels) * wplane, [image, window, plane, wplane, ww, win, width] GORIS_HD(std::size_t i) {
    const std::size_t c = i / wplane, p = i % wplane;
    const int y = int(p / std::size_t(ww)), x = int(p % std::size_t(ww));
    const std::size_t at = c * plane + std::size_t(win.y0 + y) * std::size_t(width) + std::size_t(win.x0 + x);
    if constexpr (Op == WindowOp::CopyOut)
      window[i] = image[at];
    else
      image[at] += window[i];
  }, 8192);
}

}  // namespace goris::ssf
