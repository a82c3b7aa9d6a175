#pragma once
// Gradient sums into the environment map's texels in a fixed order, on both backends. Many pixels look up
// the same texels; adding their gradients with atomics would make every training run differ in the last
// bits from the one before. So the parallel pass records each pixel's lookup (direction, roughness,
// upstream gradient) and flush() expands the records into one row per texel tap and adds them with
// add_rows_in_key_order, in pixel order: the same sums as a serial loop over the pixels, on the CPU and
// on CUDA alike, and a run repeats bit for bit.
#include <cstddef>
#include <cstdint>

#include "core/compute/buffer.h"
#include "core/compute/ordered_sum.h"
#include "render/envmap/cube_map_math.h"

namespace goris::envmap {
GORIS_BACKEND_NAMESPACE_BEGIN

template <class T>
class DeferredTexelGrads {
 public:
  static constexpr int kStride = 7;  // direction (3), roughness, upstream gradient (3)
  static constexpr int kTaps = 8;    // lookup_taps' most

  // grad_texels: the chain's gradient on d (null: nothing is recorded or added).
  DeferredTexelGrads(Device d, T* grad_texels, std::size_t n) : grad_(grad_texels) {
    if (!grad_texels) return;
    records_ = Buffer<T>(kStride * n, d);
    records_.fill_zero();  // pixels that look nothing up keep a zero gradient: no taps
  }
  // Where the parallel pass records lookups (null: not recording).
  T* records() { return records_.empty() ? nullptr : records_.data(); }

  static GORIS_HDI void record(T* records, std::size_t i, const Vec3<T>& dir, T roughness, const Vec3<T>& dout) {
    if (!records) return;
    T* r = records + kStride * i;
    r[0] = dir.x, r[1] = dir.y, r[2] = dir.z, r[3] = roughness, r[4] = dout.x, r[5] = dout.y, r[6] = dout.z;
  }

  // Adds the recorded lookups' texel gradients, texel by texel in record order.
  void flush(const CubeMipsT<T>& mips) {
    const std::size_t n = records_.size() / kStride;
    if (n == 0) return;
    const Device d = records_.device();
    const OrderedKeyLayout layout(std::uint64_t(chain_size(mips.resolution, mips.levels) / 3), kTaps * n);
    Buffer<std::uint64_t> keys(kTaps * n, d);
    Buffer<T> rows(3 * kTaps * n, d);
    std::uint64_t* const key = keys.data();
    T* const row = rows.data();
    const T* const rec = records_.data();
    const CubeMipsT<T> m = mips;
    parallel_for(d, n, [=] GORIS_HD(std::size_t i) {
      const T* r = rec + kStride * i;
      const Vec3<T> dout(r[4], r[5], r[6]);
      LookupTaps<T> taps;
      if (dout.x != T(0) || dout.y != T(0) || dout.z != T(0)) taps = lookup_taps(m, Vec3<T>(r[0], r[1], r[2]), r[3]);
      for (int t = 0; t < kTaps; ++t) {
        const std::size_t j = kTaps * i + t;
        key[j] = t < taps.n ? layout.key(std::uint64_t(taps.idx[t] / 3), j) : layout.unused();
        for (int ch = 0; ch < 3; ++ch) row[3 * j + ch] = t < taps.n ? taps.w[t] * dout[ch] : T(0);
      }
    });
    add_rows_in_key_order(layout, keys, rows.data(), 3, grad_);
  }

 private:
  T* grad_;
  Buffer<T> records_;
};

GORIS_BACKEND_NAMESPACE_END
}  // namespace goris::envmap
