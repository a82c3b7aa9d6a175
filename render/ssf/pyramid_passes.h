#pragma once
// The glossy filter's passes over whole images, written once with parallel_for and instantiated on the CPU
// (glossy_filter.cpp, float and double) and on CUDA (glossy_filter_cuda.cu, float). Every pass is a gather:
// one work item writes its own outputs, so there are no atomics and both backends are deterministic.
#include <cstddef>

#include "core/compute/parallel_for.h"
#include "render/ssf/pyramid_kernels.h"

namespace goris::ssf {

// Raw pointers of one pyramid on one device: images [C][h_k][w_k], unit normals [3][h_k][w_k], for k >= 1 the
// inverse weight sums [h_k][w_k] of the blur that made level k, and for a weighted pyramid the masses
// [h_k][w_k] (mass[0] is the caller's) and, for k >= 1, the full-resolution lookup normalisations [H][W]
// (all null when unweighted).
template <class T>
struct PyramidPtrs {
  int levels = 0, channels = 0, power = 0;
  LevelDims d[kMaxLevels];
  T* image[kMaxLevels] = {};
  T* normal[kMaxLevels] = {};
  T* inv_sum[kMaxLevels] = {};
  T* mass[kMaxLevels] = {};
  T* norm[kMaxLevels] = {};
  LevelSet<T> level_set() const {
    LevelSet<T> s{};
    s.levels = levels;
    for (int k = 0; k < levels; ++k) {
      s.p[k] = image[k];
      s.m[k] = mass[k];
      s.norm[k] = norm[k];
      s.d[k] = d[k];
    }
    return s;
  }
};

// Level 0's unit normals from the caller's (possibly unnormalised) normals.
template <Device D, class T>
void normalise_normals(const T* n_in, T* n_out, std::size_t plane) {
  parallel_for(D, plane, [=] GORIS_HD(std::size_t p) {
    T x = n_in[p], y = n_in[plane + p], z = n_in[2 * plane + p];
    unit3(x, y, z);
    n_out[p] = x;
    n_out[plane + p] = y;
    n_out[2 * plane + p] = z;
  }, 4096);
}

// The weighted lookups' normalisations (norm[k], k >= 1) from the levels' masses; nothing when unweighted.
template <Device D, class T>
void sample_norms(const PyramidPtrs<T>& P) {
  if (!P.mass[0]) return;
  const int W = P.d[0].w;
  for (int k = 1; k < P.levels; ++k) {
    const T* m = P.mass[k];
    T* norm = P.norm[k];
    const LevelDims d = P.d[k];
    parallel_for(D, std::size_t(P.d[0].h) * W, [=] GORIS_HD(std::size_t p) {
      norm[p] = footprint_inv_mass(m, d, k, int(p / W), int(p % W));
    }, 1024);
  }
}

// Levels 1.. from level 0 (image[0], normal[0] and, when weighted, mass[0] filled by the caller), then the
// weighted lookups' normalisations.
template <Device D, class T>
void build_levels(const PyramidPtrs<T>& P) {
  for (int k = 0; k + 1 < P.levels; ++k) {
    const LevelDims in = P.d[k], out = P.d[k + 1];
    const T* n = P.normal[k];
    T* n_next = P.normal[k + 1];
    const std::size_t m = std::size_t(out.h) * out.w;
    parallel_for(D, m, [=] GORIS_HD(std::size_t p) {
      down_normal(n, in, out, int(p / out.w), int(p % out.w), n_next);
    }, 1024);
    const T* x = P.image[k];
    const T* mk = P.mass[k];
    T* x_next = P.image[k + 1];
    T* inv = P.inv_sum[k + 1];
    T* m_next = P.mass[k + 1];
    const int C = P.channels, power = P.power;
    parallel_for(D, m, [=] GORIS_HD(std::size_t p) {
      down_pixel(x, mk, n, n_next, in, out, C, power, int(p / out.w), int(p % out.w), x_next, inv, m_next);
    }, 256);
  }
  sample_norms<D>(P);
}

template <Device D, class T>
void sample_all(const PyramidPtrs<T>& P, const T* rs, T* out) {
  const LevelSet<T> L = P.level_set();
  const int W = P.d[0].w, C = P.channels;
  parallel_for(D, std::size_t(P.d[0].h) * W, [=] GORIS_HD(std::size_t p) {
    sample_pixel(L, rs, C, int(p / W), int(p % W), out);
  }, 1024);
}

// dL/dR_s added into grad_rs.
template <Device D, class T>
void backward_rs(const PyramidPtrs<T>& P, const T* rs, const T* g_out, T* grad_rs) {
  const LevelSet<T> L = P.level_set();
  const int W = P.d[0].w, C = P.channels;
  parallel_for(D, std::size_t(P.d[0].h) * W, [=] GORIS_HD(std::size_t p) {
    grad_rs[p] += sample_grad_rs(L, rs, g_out, C, int(p / W), int(p % W));
  }, 1024);
}

// Gradients of every level (scratch.image[k], same layout as image[k]) from the sampling, then carried down the
// pyramid from the coarsest level to level 0 through the blur adjoints; level 0's gradient is added into
// grad_x.
template <Device D, class T>
void backward_x(const PyramidPtrs<T>& P, const PyramidPtrs<T>& scratch, const T* rs, const T* g_out, T* grad_x) {
  const int H = P.d[0].h, W = P.d[0].w, C = P.channels, levels = P.levels, power = P.power;
  T* s0 = scratch.image[0];
  const T* m0 = P.mass[0];
  parallel_for(D, std::size_t(H) * W, [=] GORIS_HD(std::size_t p) {
    sample_adjoint_level0(rs, g_out, m0, H, W, levels, C, int(p / W), int(p % W), s0);
  }, 1024);
  for (int k = 1; k < levels; ++k) {
    const LevelDims d = P.d[k];
    const T *mk = P.mass[k], *norm = P.norm[k];
    T* g = scratch.image[k];
    parallel_for(D, std::size_t(d.h) * d.w, [=] GORIS_HD(std::size_t p) {
      sample_adjoint_texel(rs, g_out, H, W, levels, k, d, mk, norm, C, int(p / d.w), int(p % d.w), g);
    }, 16);
  }
  for (int k = levels - 2; k >= 0; --k) {
    const LevelDims in = P.d[k], out = P.d[k + 1];
    const T *mk = P.mass[k], *n = P.normal[k], *n_next = P.normal[k + 1], *inv = P.inv_sum[k + 1],
            *g_next = scratch.image[k + 1];
    T* g = scratch.image[k];
    parallel_for(D, std::size_t(in.h) * in.w, [=] GORIS_HD(std::size_t p) {
      down_adjoint_pixel(mk, n, n_next, inv, g_next, in, out, C, power, int(p / in.w), int(p % in.w), g);
    }, 256);
  }
  const T* g0 = s0;
  parallel_for(D, std::size_t(C) * H * W, [=] GORIS_HD(std::size_t i) { grad_x[i] += g0[i]; }, 4096);
}

}  // namespace goris::ssf
