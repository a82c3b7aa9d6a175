#pragma once
// Building the tracer's per-Gaussian prims and the LBVH on one device, written once with parallel_for and
// the compute primitives: instantiated for the CPU in gaussian_tracer.cpp and for CUDA in trace_cuda.cu
// (templates on the device, so the two translation units never share a definition).
#include <cstdint>

#include "core/compute/buffer.h"
#include "core/compute/parallel_for.h"
#include "core/compute/primitives.h"
#include "render/raster/raster_types.h"
#include "render/trace/lbvh.h"

namespace goris::trace {

// Prims and their boxes ([N][3]) on one device.
struct PrimData {
  Buffer<TracePrim<float>> prims;
  Buffer<float> lo, hi;
};

struct LbvhData {
  int n = 0;
  Buffer<std::int32_t> left, right, parent;
  Buffer<float> lo, hi;
  Buffer<std::uint32_t> leaf_prim;
  Buffer<int> arrivals;
  LbvhView view() const {
    return LbvhView{n, left.data(), right.data(), lo.data(), hi.data(), leaf_prim.data()};
  }
};

template <Device D>
void build_prims(const GaussiansT<float>& g, PrimData& out) {
  const std::size_t n = std::size_t(g.count);
  if (out.prims.size() != n || out.prims.device() != D) {
    out.prims = Buffer<TracePrim<float>>(n, D);
    out.lo = Buffer<float>(3 * n, D);
    out.hi = Buffer<float>(3 * n, D);
  }
  TracePrim<float>* prims = out.prims.data();
  float* lo = out.lo.data();
  float* hi = out.hi.data();
  const GaussiansT<float> gv = g;
  parallel_for(D, n, [=] GORIS_HD(std::size_t i) {
    prims[i] = make_prim(gv.positions + 3 * i, gv.log_scales + 3 * i, gv.rotations + 4 * i, gv.opacity_logits[i],
                         gv.filter3d_var ? gv.filter3d_var[i] : 0.0f, lo + 3 * i, hi + 3 * i);
  });
}

// Karras LBVH over the prims' centres (Morton order) with their boxes.
template <Device D>
void build_lbvh(const PrimData& pd, LbvhData& out) {
  const int n = int(pd.prims.size());
  out.n = n;
  if (n == 0) return;
  const std::size_t nodes = 2 * std::size_t(n) - 1;
  if (out.leaf_prim.size() != std::size_t(n) || out.leaf_prim.device() != D) {
    out.left = Buffer<std::int32_t>(std::size_t(n - 1), D);
    out.right = Buffer<std::int32_t>(std::size_t(n - 1), D);
    out.parent = Buffer<std::int32_t>(nodes, D);
    out.lo = Buffer<float>(3 * nodes, D);
    out.hi = Buffer<float>(3 * nodes, D);
    out.leaf_prim = Buffer<std::uint32_t>(std::size_t(n), D);
    out.arrivals = Buffer<int>(std::size_t(n - 1), D);
  }
  const TracePrim<float>* prims = pd.prims.data();

  // Box of the centres (Morton cube).
  Buffer<float> tmp(std::size_t(n), D);
  float* t = tmp.data();
  float bmin[3], bmax[3];
  for (int k = 0; k < 3; ++k) {
    parallel_for(D, std::size_t(n), [=] GORIS_HD(std::size_t i) { t[i] = prims[i].mean[k]; });
    bmax[k] = reduce_max(tmp);
    parallel_for(D, std::size_t(n), [=] GORIS_HD(std::size_t i) { t[i] = -prims[i].mean[k]; });
    bmin[k] = -reduce_max(tmp);
  }
  const float ox = bmin[0], oy = bmin[1], oz = bmin[2];
  const float sx = bmax[0] > bmin[0] ? 1.0f / (bmax[0] - bmin[0]) : 0.0f;
  const float sy = bmax[1] > bmin[1] ? 1.0f / (bmax[1] - bmin[1]) : 0.0f;
  const float sz = bmax[2] > bmin[2] ? 1.0f / (bmax[2] - bmin[2]) : 0.0f;

  Buffer<std::uint64_t> keys(std::size_t(n), D);
  std::uint64_t* kp = keys.data();
  std::uint32_t* leaf_prim = out.leaf_prim.data();
  parallel_for(D, std::size_t(n), [=] GORIS_HD(std::size_t i) {
    const float* m = prims[i].mean;
    kp[i] = morton63((m[0] - ox) * sx, (m[1] - oy) * sy, (m[2] - oz) * sz);
    leaf_prim[i] = std::uint32_t(i);
  });
  sort_by_key(keys, out.leaf_prim, 63);

  std::int32_t* left = out.left.data();
  std::int32_t* right = out.right.data();
  std::int32_t* parent = out.parent.data();
  int* arrivals = out.arrivals.data();
  float* lo = out.lo.data();
  float* hi = out.hi.data();
  const float* plo = pd.lo.data();
  const float* phi = pd.hi.data();
  const std::uint64_t* ck = keys.data();
  parallel_for(D, 1, [=] GORIS_HD(std::size_t) { parent[0] = -1; });  // the root
  parallel_for(D, std::size_t(n - 1), [=] GORIS_HD(std::size_t i) {
    build_internal_node(ck, n, int(i), left, right, parent);
  });
  out.arrivals.fill_zero();
  parallel_for(D, std::size_t(n), [=] GORIS_HD(std::size_t j) {
    const int leaf = n - 1 + int(j);
    const std::uint32_t g = leaf_prim[j];
    for (int k = 0; k < 3; ++k) {
      lo[3 * leaf + k] = plo[3 * g + k];
      hi[3 * leaf + k] = phi[3 * g + k];
    }
    propagate_boxes(n, leaf, left, right, parent, arrivals, lo, hi);
  });
}

}  // namespace goris::trace
