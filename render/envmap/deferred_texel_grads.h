#pragma once
// Gradient sums into the environment map's texels in a fixed order on the CPU. Many pixels look up the same
// texels; on CUDA they add atomically (order free), but on the CPU the same atomics would make every
// training run differ in the last bits from the one before. So the CPU's parallel pass records each pixel's
// lookup (direction, roughness, upstream gradient) and flush() adds them on one thread in pixel order: a few
// ms next to the tracing, and a run repeats bit for bit on the same machine.
#include <cstddef>
#include <vector>

#include "core/compute/device.h"
#include "render/envmap/cube_map_math.h"

namespace goris::envmap {

template <class T>
class DeferredTexelGrads {
 public:
  static constexpr int kStride = 7;  // direction (3), roughness, upstream gradient (3)

  DeferredTexelGrads(Device d, T* grad_texels, std::size_t n) : grad_(grad_texels) {
    if (d == Device::CPU && grad_texels) records_.assign(kStride * n, T(0));
  }
  // What the parallel pass hands cube_lookup_vjp: the texel gradient when it may add atomically (CUDA),
  // null when its lookups are recorded instead.
  T* direct() const { return records_.empty() ? grad_ : nullptr; }
  // Where the parallel pass records lookups (null: not deferring).
  T* records() { return records_.empty() ? nullptr : records_.data(); }

  static GORIS_HDI void record(T* records, std::size_t i, const Vec3<T>& dir, T roughness, const Vec3<T>& dout) {
    if (!records) return;
    T* r = records + kStride * i;
    r[0] = dir.x, r[1] = dir.y, r[2] = dir.z, r[3] = roughness, r[4] = dout.x, r[5] = dout.y, r[6] = dout.z;
  }

  // Adds the recorded lookups' texel gradients, in index order (no-op when not deferring).
  void flush(const CubeMipsT<T>& mips) const {
    const std::size_t n = records_.size() / kStride;
    for (std::size_t i = 0; i < n; ++i) {
      const T* r = records_.data() + kStride * i;
      const Vec3<T> dout(r[4], r[5], r[6]);
      if (dout.x == T(0) && dout.y == T(0) && dout.z == T(0)) continue;
      Vec3<T> ddir;
      T drough;
      cube_lookup_vjp(mips, Vec3<T>(r[0], r[1], r[2]), r[3], dout, grad_, &ddir, &drough);
    }
  }

 private:
  T* grad_;
  std::vector<T> records_;
};

}  // namespace goris::envmap
