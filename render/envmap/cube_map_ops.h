#pragma once
// Device-generic drivers of the cube map (activation, prefilter and its adjoint, batched lookups), written
// once on parallel_for: environment_map.cpp instantiates them on the CPU (float and double), the .cu twin
// on CUDA. Every pointer lives on `d`. Layouts: cube_map_math.h.
#include <cmath>
#include <cstddef>
#include <type_traits>

#include "core/compute/parallel_for.h"
#include "render/envmap/cube_map_math.h"
#include "render/envmap/cube_prefilter_math.h"
#include "render/envmap/deferred_texel_grads.h"

namespace goris::envmap::ops {
GORIS_BACKEND_NAMESPACE_BEGIN

// Texel values are exp(parameter): Adam's steps on log radiance are relative, which suits lighting that
// spans orders of magnitude (HDR sky vs. shadowed walls), and radiance stays positive without clamps.
template <class T>
void activate(Device d, const T* params, T* level0, std::size_t n) {
  parallel_for(d, n, [=] GORIS_HD(std::size_t i) {
    using std::exp;
    level0[i] = exp(params[i]);
  });
}

// param_grad += dL/dlevel0 * exp(param) (level0 holds exp(param)).
template <class T>
void activate_backward(Device d, const T* level0, const T* level0_grad, T* param_grad, std::size_t n) {
  parallel_for(d, n, [=] GORIS_HD(std::size_t i) { param_grad[i] += level0_grad[i] * level0[i]; });
}

// Fills levels 1..L-1 of `chain` from level 0. scratch holds 6 * R * (R / 2) * 3 values.
template <class T>
void prefilter(Device d, T* chain, T* scratch, int R, int L) {
  for (int k = 0; k + 1 < L; ++k) {
    const int n = level_res(R, k), m = n / 2;
    const T* in = chain + level_offset(R, k);
    T* out = chain + level_offset(R, k + 1);
    // x pass: (face, y, j, c) of scratch [6][n][m][3].
    parallel_for(d, std::size_t(6) * n * m * 3, [=] GORIS_HD(std::size_t e) {
      const int c = int(e % 3), j = int(e / 3 % m);
      const std::size_t line = e / 3 / m;  // face * n + y
      scratch[e] = downsample_at(in + line * n * 3 + c, n, 3, j);
    });
    // y pass: (face, j, x, c) of out [6][m][m][3] reads scratch column x.
    parallel_for(d, std::size_t(6) * m * m * 3, [=] GORIS_HD(std::size_t e) {
      const int c = int(e % 3), x = int(e / 3 % m), j = int(e / 3 / m % m), face = int(e / 3 / m / m);
      out[e] = downsample_at(scratch + (std::size_t(face) * n * m + x) * 3 + c, n, std::ptrdiff_t(m) * 3, j);
    });
  }
}

// Adjoint of prefilter: folds the gradients of levels L-1..1 down into level 0 (chain_grad[level k] +=
// P_k^T chain_grad[level k+1], coarsest first). Afterwards level 0 of chain_grad holds dL/dlevel0.
template <class T>
void prefilter_adjoint(Device d, T* chain_grad, T* scratch, int R, int L) {
  for (int k = L - 2; k >= 0; --k) {
    const int n = level_res(R, k), m = n / 2;
    T* gin = chain_grad + level_offset(R, k);
    const T* gout = chain_grad + level_offset(R, k + 1);
    // Adjoint of the y pass: scratch (face, y, x, c) = sum over the column x of level k+1.
    parallel_for(d, std::size_t(6) * n * m * 3, [=] GORIS_HD(std::size_t e) {
      const int c = int(e % 3), x = int(e / 3 % m), y = int(e / 3 / m % n), face = int(e / 3 / m / n);
      scratch[e] = downsample_adjoint_at(gout + (std::size_t(face) * m * m + x) * 3 + c, n, std::ptrdiff_t(m) * 3, y);
    });
    // Adjoint of the x pass: level k (face, y, i, c) += sum over the scratch row.
    parallel_for(d, std::size_t(6) * n * n * 3, [=] GORIS_HD(std::size_t e) {
      const int c = int(e % 3), i = int(e / 3 % n);
      const std::size_t line = e / 3 / n;
      gin[e] += downsample_adjoint_at(scratch + line * m * 3 + c, n, 3, i);
    });
  }
}

// out[i] = cube_lookup(dirs[i], roughness[i]); dirs [n][3], roughness [n], out [n][3].
template <class T>
void lookup(Device d, const CubeMipsT<T>& mips, const T* dirs, const T* roughness, std::size_t n, T* out) {
  parallel_for(d, n, [=] GORIS_HD(std::size_t i) {
    const Vec3<T> c = cube_lookup(mips, Vec3<T>(dirs[3 * i], dirs[3 * i + 1], dirs[3 * i + 2]), roughness[i]);
    out[3 * i] = c.x, out[3 * i + 1] = c.y, out[3 * i + 2] = c.z;
  });
}

// Backward of lookup: chain_grad += dL/dtexels (in a fixed order on both backends, see
// deferred_texel_grads.h), ddirs / droughness written (null: skipped).
template <class T>
void lookup_backward(Device d, const CubeMipsT<T>& mips, const T* dirs, const T* roughness, const T* dout,
                     std::size_t n, T* chain_grad, std::type_identity_t<T>* ddirs,
                     std::type_identity_t<T>* droughness) {
  DeferredTexelGrads<T> texels(d, chain_grad, n);
  T* const records = texels.records();
  parallel_for(d, n, [=] GORIS_HD(std::size_t i) {
    const Vec3<T> dir(dirs[3 * i], dirs[3 * i + 1], dirs[3 * i + 2]), g(dout[3 * i], dout[3 * i + 1], dout[3 * i + 2]);
    Vec3<T> gd;
    T gr;
    cube_lookup_vjp(mips, dir, roughness[i], g, &gd, &gr);
    DeferredTexelGrads<T>::record(records, i, dir, roughness[i], g);
    if (ddirs) ddirs[3 * i] = gd.x, ddirs[3 * i + 1] = gd.y, ddirs[3 * i + 2] = gd.z;
    if (droughness) droughness[i] = gr;
  });
  texels.flush(mips);
}

GORIS_BACKEND_NAMESPACE_END
}  // namespace goris::envmap::ops
