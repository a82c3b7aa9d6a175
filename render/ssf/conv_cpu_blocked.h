#pragma once
// CPU fast paths of the convolutions for layers with a multiple of 8 output channels (the net's 8-feature
// layers): 8 output channels x 4 pixels of accumulators stay in registers while the input is read once per
// tap, instead of one read-modify-write of the output row per (channel, tap) as in conv_forward_row. Same
// sums as conv_kernels.h (a unit test compares them); host-only because GPUs take the per-pixel form.
#include <cstddef>

#include "render/ssf/conv_kernels.h"

namespace goris::ssf {

constexpr int kBlock = 8;     // output channels per register block
constexpr int kPixBlock = 4;  // pixels per register block: 8 x 4 accumulators fit the 16 SSE registers

// Output channels [co0, co0 + 8) of row y; s.cout % 8 == 0.
template <class T>
void conv_forward_row_blocked(const ConvShape& s, const T* in, const T* w, const T* b, T* out, int y, int co0) {
  const int r = s.k / 2, kk = s.k * s.k;
  const std::size_t plane = s.plane();
  // Pixels [xa, xb) have every horizontal tap inside the row; the rest take the scalar path.
  const int xa = r, xb = s.w - r;
  int x = 0;
  auto scalar_pixel = [&](int px) {
    T acc[kBlock];
    for (int c = 0; c < kBlock; ++c) acc[c] = b[co0 + c];
    for (int ci = 0; ci < s.cin; ++ci)
      for (int ky = 0; ky < s.k; ++ky) {
        const int yy = y + ky - r;
        if (yy < 0 || yy >= s.h) continue;
        for (int kx = 0; kx < s.k; ++kx) {
          const int xx = px + kx - r;
          if (xx < 0 || xx >= s.w) continue;
          const T v = in[ci * plane + std::size_t(yy) * s.w + xx];
          for (int c = 0; c < kBlock; ++c) acc[c] += w[((co0 + c) * s.cin + ci) * kk + ky * s.k + kx] * v;
        }
      }
    for (int c = 0; c < kBlock; ++c) out[(co0 + c) * plane + std::size_t(y) * s.w + px] = acc[c];
  };
  for (; x < xa && x < s.w; ++x) scalar_pixel(x);
  for (; x + kPixBlock <= xb; x += kPixBlock) {
    T acc[kBlock][kPixBlock];
    for (int c = 0; c < kBlock; ++c)
      for (int l = 0; l < kPixBlock; ++l) acc[c][l] = b[co0 + c];
    for (int ci = 0; ci < s.cin; ++ci)
      for (int ky = 0; ky < s.k; ++ky) {
        const int yy = y + ky - r;
        if (yy < 0 || yy >= s.h) continue;
        const T* irow = in + ci * plane + std::size_t(yy) * s.w + x - r;
        const T* wk = w + (co0 * s.cin + ci) * kk + ky * s.k;
        for (int kx = 0; kx < s.k; ++kx) {
          T v[kPixBlock];
          for (int l = 0; l < kPixBlock; ++l) v[l] = irow[kx + l];
          for (int c = 0; c < kBlock; ++c) {
            const T wv = wk[c * s.cin * kk + kx];
            for (int l = 0; l < kPixBlock; ++l) acc[c][l] += wv * v[l];
          }
        }
      }
    for (int c = 0; c < kBlock; ++c)
      for (int l = 0; l < kPixBlock; ++l) out[(co0 + c) * plane + std::size_t(y) * s.w + x + l] = acc[c][l];
  }
  for (; x < s.w; ++x) scalar_pixel(x);
}

// Weights of the transposed convolution: g_in = conv(g_out, flip) with flip[ci][co][ky][kx] =
// w[co][ci][k-1-ky][k-1-kx], so the input gradient reuses the blocked forward kernel.
template <class T>
void flip_weights(const ConvShape& s, const T* w, T* flip) {
  const int kk = s.k * s.k;
  for (int co = 0; co < s.cout; ++co)
    for (int ci = 0; ci < s.cin; ++ci)
      for (int t = 0; t < kk; ++t) flip[(ci * s.cout + co) * kk + (kk - 1 - t)] = w[(co * s.cin + ci) * kk + t];
}

// Row y's share of every parameter gradient (weights then biases, as conv_param_grad_row) into part[];
// s.cout % 8 == 0. Lane accumulators over 4 pixels keep the dot products vectorisable.
template <class T>
void conv_param_grad_row_blocked(const ConvShape& s, const T* in, const T* g_out, int y, T* part) {
  const int r = s.k / 2, kk = s.k * s.k, nw = s.weight_count();
  const std::size_t plane = s.plane();
  for (int co0 = 0; co0 < s.cout; co0 += kBlock) {
    const T* g = g_out + co0 * plane + std::size_t(y) * s.w;
    for (int c = 0; c < kBlock; ++c) {
      T acc = T(0);
      for (int x = 0; x < s.w; ++x) acc += g[c * plane + x];
      part[nw + co0 + c] = acc;
    }
    for (int ci = 0; ci < s.cin; ++ci)
      for (int ky = 0; ky < s.k; ++ky)
        for (int kx = 0; kx < s.k; ++kx) {
          const int yy = y + ky - r, dx = kx - r;
          T* dst = part + (co0 * s.cin + ci) * kk + ky * s.k + kx;  // + c * cin * kk per channel
          if (yy < 0 || yy >= s.h) {
            for (int c = 0; c < kBlock; ++c) dst[c * s.cin * kk] = T(0);
            continue;
          }
          const T* irow = in + ci * plane + std::size_t(yy) * s.w;
          int x0, x1;
          tap_span(s.w, dx, x0, x1);
          T lanes[kBlock][kPixBlock] = {};
          int x = x0;
          for (; x + kPixBlock <= x1; x += kPixBlock) {
            T v[kPixBlock];
            for (int l = 0; l < kPixBlock; ++l) v[l] = irow[x + dx + l];
            for (int c = 0; c < kBlock; ++c)
              for (int l = 0; l < kPixBlock; ++l) lanes[c][l] += g[c * plane + x + l] * v[l];
          }
          for (int c = 0; c < kBlock; ++c) {
            T acc = T(0);
            for (int l = 0; l < kPixBlock; ++l) acc += lanes[c][l];
            for (int xr = x; xr < x1; ++xr) acc += g[c * plane + xr] * irow[xr + dx];
            dst[c * s.cin * kk] = acc;
          }
        }
  }
}

}  // namespace goris::ssf
