#pragma once
// Maths of the roughness net's layers (paper S1.3): 2D convolution with a 1x1 or 3x3 kernel and zero padding
// ("same" size), on planar [C][H][W] images, with its vector-Jacobian products. Weights are [cout][cin][k][k]
// followed elsewhere by biases [cout]. Templated on the scalar so that the gradient tests run it in double.
//
// Two forms of the same sums: *_row computes one output row with the innermost loop running along x over
// contiguous memory (vectorised by the host compiler: the CPU path); *_pixel computes one pixel with the
// accumulators in registers (one GPU thread each). A unit test checks that they agree.
#include <cstddef>

#include "core/compute/hd.h"

namespace goris::ssf {

constexpr int kMaxConvChannels = 32;  // bound of the per-pixel accumulators

struct ConvShape {
  int cin = 0, cout = 0, k = 1;  // k = 1 or 3
  int h = 0, w = 0;
  GORIS_HD std::size_t plane() const { return std::size_t(h) * std::size_t(w); }
  GORIS_HD int weight_count() const { return cout * cin * k * k; }
};

// Columns [x0, x1) of the row where the tap at horizontal offset dx stays inside the image.
GORIS_HDI void tap_span(int w, int dx, int& x0, int& x1) {
  x0 = dx < 0 ? -dx : 0;
  x1 = dx > 0 ? w - dx : w;
}

// out[co][y][*] = b[co] + sum_ci sum_taps w * in[ci][y + dy][* + dx].
template <class T>
GORIS_HDI void conv_forward_row(const ConvShape& s, const T* in, const T* w, const T* b, T* out, int y) {
  const int r = s.k / 2;
  for (int co = 0; co < s.cout; ++co) {
    T* o = out + co * s.plane() + std::size_t(y) * s.w;
    for (int x = 0; x < s.w; ++x) o[x] = b[co];
    for (int ci = 0; ci < s.cin; ++ci)
      for (int ky = 0; ky < s.k; ++ky) {
        const int yy = y + ky - r;
        if (yy < 0 || yy >= s.h) continue;
        const T* irow = in + ci * s.plane() + std::size_t(yy) * s.w;
        for (int kx = 0; kx < s.k; ++kx) {
          const T wv = w[((co * s.cin + ci) * s.k + ky) * s.k + kx];
          const int dx = kx - r;
          int x0, x1;
          tap_span(s.w, dx, x0, x1);
          for (int x = x0; x < x1; ++x) o[x] += wv * irow[x + dx];
        }
      }
  }
}

template <class T>
GORIS_HDI void conv_forward_pixel(const ConvShape& s, const T* in, const T* w, const T* b, T* out, int y, int x) {
  const int r = s.k / 2;
  T acc[kMaxConvChannels];
  for (int co = 0; co < s.cout; ++co) acc[co] = b[co];
  for (int ci = 0; ci < s.cin; ++ci)
    for (int ky = 0; ky < s.k; ++ky) {
      const int yy = y + ky - r;
      if (yy < 0 || yy >= s.h) continue;
      for (int kx = 0; kx < s.k; ++kx) {
        const int xx = x + kx - r;
        if (xx < 0 || xx >= s.w) continue;
        const T v = in[ci * s.plane() + std::size_t(yy) * s.w + xx];
        for (int co = 0; co < s.cout; ++co) acc[co] += w[((co * s.cin + ci) * s.k + ky) * s.k + kx] * v;
      }
    }
  for (int co = 0; co < s.cout; ++co) out[co * s.plane() + std::size_t(y) * s.w + x] = acc[co];
}

// g_in[ci][y][*] = sum_co sum_taps w * g_out[co][y - dy][* - dx] (the transposed convolution). Writes.
template <class T>
GORIS_HDI void conv_grad_input_row(const ConvShape& s, const T* w, const T* g_out, T* g_in, int y) {
  const int r = s.k / 2;
  for (int ci = 0; ci < s.cin; ++ci) {
    T* gi = g_in + ci * s.plane() + std::size_t(y) * s.w;
    for (int x = 0; x < s.w; ++x) gi[x] = T(0);
    for (int co = 0; co < s.cout; ++co)
      for (int ky = 0; ky < s.k; ++ky) {
        const int yy = y - (ky - r);
        if (yy < 0 || yy >= s.h) continue;
        const T* grow = g_out + co * s.plane() + std::size_t(yy) * s.w;
        for (int kx = 0; kx < s.k; ++kx) {
          const T wv = w[((co * s.cin + ci) * s.k + ky) * s.k + kx];
          const int dx = -(kx - r);
          int x0, x1;
          tap_span(s.w, dx, x0, x1);
          for (int x = x0; x < x1; ++x) gi[x] += wv * grow[x + dx];
        }
      }
  }
}

template <class T>
GORIS_HDI void conv_grad_input_pixel(const ConvShape& s, const T* w, const T* g_out, T* g_in, int y, int x) {
  const int r = s.k / 2;
  T acc[kMaxConvChannels];
  for (int ci = 0; ci < s.cin; ++ci) acc[ci] = T(0);
  for (int co = 0; co < s.cout; ++co)
    for (int ky = 0; ky < s.k; ++ky) {
      const int yy = y - (ky - r);
      if (yy < 0 || yy >= s.h) continue;
      for (int kx = 0; kx < s.k; ++kx) {
        const int xx = x - (kx - r);
        if (xx < 0 || xx >= s.w) continue;
        const T g = g_out[co * s.plane() + std::size_t(yy) * s.w + xx];
        for (int ci = 0; ci < s.cin; ++ci) acc[ci] += w[((co * s.cin + ci) * s.k + ky) * s.k + kx] * g;
      }
    }
  for (int ci = 0; ci < s.cin; ++ci) g_in[ci * s.plane() + std::size_t(y) * s.w + x] = acc[ci];
}

// Row y's share of parameter gradient `p` (p < weight_count(): that weight; else bias p - weight_count()):
// sum_x g_out[co][y][x] * in[ci][y + dy][x + dx], or sum_x g_out[co][y][x].
template <class T>
GORIS_HDI T conv_param_grad_row(const ConvShape& s, const T* in, const T* g_out, int p, int y) {
  const int r = s.k / 2, nw = s.weight_count();
  const int co = p < nw ? p / (s.cin * s.k * s.k) : p - nw;
  const T* grow = g_out + co * s.plane() + std::size_t(y) * s.w;
  T acc = T(0);
  if (p >= nw) {
    for (int x = 0; x < s.w; ++x) acc += grow[x];
    return acc;
  }
  const int rem = p % (s.cin * s.k * s.k), ci = rem / (s.k * s.k), ky = (rem / s.k) % s.k, kx = rem % s.k;
  const int yy = y + ky - r, dx = kx - r;
  if (yy < 0 || yy >= s.h) return T(0);
  const T* irow = in + ci * s.plane() + std::size_t(yy) * s.w;
  int x0, x1;
  tap_span(s.w, dx, x0, x1);
  for (int x = x0; x < x1; ++x) acc += grow[x] * irow[x + dx];
  return acc;
}

}  // namespace goris::ssf
