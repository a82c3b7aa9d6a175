#pragma once
// Scatter-add in a fixed order, on either backend. Gradient scatters (many rays into one Gaussian, many
// pixels into one cube-map texel) summed with atomics add in whatever order the threads run, so two
// training runs differ in their last bits and drift apart over thousands of iterations. Here every
// contribution is a row with a key (target, order); add_rows_in_key_order sorts the keys and one thread
// per (target, column) adds that target's rows in `order` order. The sums then depend only on the keys and
// rows - not on thread timing, the device or how the work was split - and equal a serial loop that adds
// the rows in that order.
#include <bit>
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/compute/buffer.h"
#include "core/compute/parallel_for.h"
#include "core/compute/primitives.h"
#include "core/util/error.h"

namespace goris {

// Key = target in the high bits, order below it; only end_bit bits are sorted. unused() marks a row that
// adds nothing: it sorts after every real key and is skipped.
struct OrderedKeyLayout {
  std::uint64_t targets = 0;
  int order_bits = 0;
  int end_bit = 0;

  OrderedKeyLayout() = default;
  OrderedKeyLayout(std::uint64_t n_targets, std::uint64_t n_orders)
      : targets(n_targets),
        order_bits(std::bit_width(n_orders > 0 ? n_orders - 1 : 0)),
        end_bit(order_bits + std::bit_width(n_targets)) {
    if (end_bit > 64)
      throw Error("ordered sum: " + std::to_string(n_targets) + " targets x " + std::to_string(n_orders) +
                  " orders do not fit a 64-bit key");
  }
  GORIS_HDI std::uint64_t key(std::uint64_t target, std::uint64_t order) const {
    return (target << order_bits) | order;
  }
  GORIS_HDI std::uint64_t unused() const { return targets << order_bits; }
  GORIS_HDI std::uint64_t target(std::uint64_t key) const { return key >> order_bits; }
};

GORIS_BACKEND_NAMESPACE_BEGIN

// out[t][c] = ((out[t][c] + rows[a][c]) + rows[b][c]) + ... over the rows of target t in increasing order.
// keys [n] (sorted in place) and rows [n][width] live on keys' device, as does out [targets][width].
template <class T>
void add_rows_in_key_order(const OrderedKeyLayout& layout, Buffer<std::uint64_t>& keys, const T* rows, int width,
                           T* out) {
  const Device d = keys.device();
  const std::size_t n = keys.size();
  if (n == 0 || width <= 0) return;
  if (n > 0xffffffffull) throw Error("ordered sum: " + std::to_string(n) + " rows exceed the 32-bit row index");
  Buffer<std::uint32_t> perm(n, d);
  std::uint32_t* const p = perm.data();
  parallel_for(d, n, [=] GORIS_HD(std::size_t i) { p[i] = std::uint32_t(i); });
  sort_by_key(keys, perm, layout.end_bit);
  const std::uint64_t* const k = keys.data();
  const OrderedKeyLayout L = layout;
  const std::size_t w = std::size_t(width);
  // One thread per (sorted row, column); only the first row of each target's run does the work. The run's
  // end comes from a binary search first, so the adds run over a known range whose loads can overlap (a
  // popular target has thousands of rows, and its thread bounds the pass).
  parallel_for(d, n * w, [=] GORIS_HD(std::size_t e) {
    const std::size_t j = e / w, c = e % w;
    const std::uint64_t t = L.target(k[j]);
    if (t >= L.targets || (j > 0 && L.target(k[j - 1]) == t)) return;
    std::size_t lo = j + 1, hi = n;  // first row past the run
    while (lo < hi) {
      const std::size_t mid = lo + (hi - lo) / 2;
      if (L.target(k[mid]) == t)
        lo = mid + 1;
      else
        hi = mid;
    }
    T acc = out[t * w + c];
#if defined(__CUDA_ARCH__)
#pragma unroll 8
#endif
    for (std::size_t m = j; m < lo; ++m) acc += rows[std::size_t(p[m]) * w + c];
    out[t * w + c] = acc;
  });
}

GORIS_BACKEND_NAMESPACE_END
}  // namespace goris
