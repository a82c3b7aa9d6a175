#pragma once
// A linear BVH (Karras 2012, "Maximizing parallelism in the construction of BVHs, octrees and k-d trees")
// over the Gaussians' centres, with the Gaussians' 1/255 boxes, written once as GORIS_HD functions: the
// CUDA backend runs them in kernels, the CPU runs the same code with TBB (tests compare it with Embree).
//
// Nodes: internal nodes 0 .. n-2 (root 0), leaves n-1 .. 2n-2 (leaf j holds the j-th Gaussian in Morton
// order). For n = 1 the root is the single leaf.
#include <cstdint>

#if !defined(__CUDA_ARCH__)
#include <atomic>
#endif

#include "render/trace/trace_ray.h"

namespace goris::trace {

// Device pointers of a built LBVH.
struct LbvhView {
  int n = 0;                          // leaves
  const std::int32_t* left = nullptr;   // [n-1]
  const std::int32_t* right = nullptr;  // [n-1]
  const float* lo = nullptr;            // [2n-1][3]
  const float* hi = nullptr;            // [2n-1][3]
  const std::uint32_t* leaf_prim = nullptr;  // [n] Gaussian of each leaf
};

// 63-bit Morton code of a point in the unit cube (21 bits per axis).
GORIS_HDI std::uint64_t spread_bits21(std::uint64_t v) {
  v &= 0x1fffffull;
  v = (v | (v << 32)) & 0x1f00000000ffffull;
  v = (v | (v << 16)) & 0x1f0000ff0000ffull;
  v = (v | (v << 8)) & 0x100f00f00f00f00full;
  v = (v | (v << 4)) & 0x10c30c30c30c30c3ull;
  v = (v | (v << 2)) & 0x1249249249249249ull;
  return v;
}

GORIS_HDI std::uint64_t morton63(float x, float y, float z) {
  const float s = 2097151.0f;  // 2^21 - 1
  auto q = [s](float u) {
    u = u < 0.0f ? 0.0f : (u > 1.0f ? 1.0f : u);
    return std::uint64_t(u * s);
  };
  return (spread_bits21(q(x)) << 2) | (spread_bits21(q(y)) << 1) | spread_bits21(q(z));
}

GORIS_HDI int clz64(std::uint64_t x) {
#if defined(__CUDA_ARCH__)
  return __clzll((long long)x);
#else
  return x == 0 ? 64 : __builtin_clzll(x);
#endif
}

// Length of the common prefix of sorted keys i and j (ties broken by index), -1 when j is out of range.
GORIS_HDI int common_prefix(const std::uint64_t* keys, int n, int i, int j) {
  if (j < 0 || j >= n) return -1;
  const std::uint64_t a = keys[i], b = keys[j];
  if (a == b) return 64 + clz64(std::uint64_t(std::uint32_t(i) ^ std::uint32_t(j)) << 32);
  return clz64(a ^ b);
}

// Children of internal node i (leaves encoded as n - 1 + j); also sets the children's parents.
GORIS_HDI void build_internal_node(const std::uint64_t* keys, int n, int i, std::int32_t* left, std::int32_t* right,
                                   std::int32_t* parent) {
  const int d = common_prefix(keys, n, i, i + 1) - common_prefix(keys, n, i, i - 1) >= 0 ? 1 : -1;
  const int dmin = common_prefix(keys, n, i, i - d);
  int lmax = 2;
  while (common_prefix(keys, n, i, i + lmax * d) > dmin) lmax *= 2;
  int l = 0;
  for (int t = lmax / 2; t >= 1; t /= 2)
    if (common_prefix(keys, n, i, i + (l + t) * d) > dmin) l += t;
  const int j = i + l * d;
  const int dnode = common_prefix(keys, n, i, j);
  int s = 0;
  for (int div = 2;; div *= 2) {
    const int t = (l + div - 1) / div;
    if (common_prefix(keys, n, i, i + (s + t) * d) > dnode) s += t;
    if (t <= 1) break;
  }
  const int split = i + s * d + (d < 0 ? -1 : 0);
  const int lo = i < j ? i : j, hi = i < j ? j : i;
  const int lc = lo == split ? n - 1 + split : split;
  const int rc = hi == split + 1 ? n - 1 + split + 1 : split + 1;
  left[i] = lc;
  right[i] = rc;
  parent[lc] = i;
  parent[rc] = i;
}

GORIS_HDI int atomic_add_int(int* p, int v) {
#if defined(__CUDA_ARCH__)
  __threadfence();  // this thread's box is visible before the counter says so
  return atomicAdd(p, v);
#else
  return std::atomic_ref<int>(*p).fetch_add(v, std::memory_order_acq_rel);
#endif
}

// From leaf j up: the second child to arrive at a node writes the node's box (union of its children's).
GORIS_HDI void propagate_boxes(int n, int leaf, const std::int32_t* left, const std::int32_t* right,
                               const std::int32_t* parent, int* arrivals, float* lo, float* hi) {
  int node = parent[leaf];
  while (node >= 0) {
    if (atomic_add_int(&arrivals[node], 1) == 0) return;  // the sibling is not done yet
    const volatile float* vlo = lo;
    const volatile float* vhi = hi;
    const int a = left[node], b = right[node];
    for (int k = 0; k < 3; ++k) {
      const float la = vlo[3 * a + k], lb = vlo[3 * b + k], ha = vhi[3 * a + k], hb = vhi[3 * b + k];
      lo[3 * node + k] = la < lb ? la : lb;
      hi[3 * node + k] = ha > hb ? ha : hb;
    }
    node = parent[node];
  }
}

// Entry distance of the ray into a box within [t0, t1]; false when it misses.
GORIS_HDI bool ray_box(const float* lo, const float* hi, const Vec3<float>& o, const Vec3<float>& inv_d, float t0,
                       float t1, float& t_enter) {
  for (int k = 0; k < 3; ++k) {
    float a = (lo[k] - o[k]) * inv_d[k], b = (hi[k] - o[k]) * inv_d[k];
    if (a > b) {
      const float c = a;
      a = b;
      b = c;
    }
    // NaN (0 * inf on a slab face) leaves the interval unchanged: the comparisons below are false.
    t0 = a > t0 ? a : t0;
    t1 = b < t1 ? b : t1;
  }
  t_enter = t0;
  return t0 <= t1;
}

constexpr int kLbvhStack = 128;  // >= tree depth: 63 Morton bits + 32 index bits for equal codes

// Collects a round of hits by walking the LBVH nearest child first, culling beyond the farthest kept hit
// once the list is full.
struct LbvhCollector {
  LbvhView bvh;
  const TracePrim<float>* prims;

  GORIS_HDI void operator()(const Vec3<float>& o, const Vec3<float>& d, float t_min, RoundStart<float> start,
                            HitList<float>& l) const {
    if (bvh.n == 0) return;
    const Vec3<float> inv_d(1.0f / d.x, 1.0f / d.y, 1.0f / d.z);
    const float inf = std::numeric_limits<float>::infinity();
    float t_far = inf;
    const int first_leaf = bvh.n - 1;
    std::int32_t stack[kLbvhStack];
    int sp = 0;
    int node = 0;
    float t_enter;
    if (!ray_box(bvh.lo, bvh.hi, o, inv_d, start.t, t_far, t_enter)) return;
    for (;;) {
      if (node >= first_leaf) {
        const std::uint32_t g = bvh.leaf_prim[node - first_leaf];
        if (consider_hit(prims[g], g, o, d, t_min, start, l)) {
          const float t_last = l.t[l.n - 1];
          t_far = t_last + (t_last > 0.0f ? t_last : -t_last) * 1e-6f + 1e-30f;  // keep equal-t hits
        }
      } else {
        const int a = bvh.left[node], b = bvh.right[node];
        float ta, tb;
        const bool ha = ray_box(bvh.lo + 3 * a, bvh.hi + 3 * a, o, inv_d, start.t, t_far, ta);
        const bool hb = ray_box(bvh.lo + 3 * b, bvh.hi + 3 * b, o, inv_d, start.t, t_far, tb);
        if (ha && hb) {
          const bool a_first = ta <= tb;
          if (sp < kLbvhStack) stack[sp++] = a_first ? b : a;
          node = a_first ? a : b;
          continue;
        }
        if (ha || hb) {
          node = ha ? a : b;
          continue;
        }
      }
      if (sp == 0) return;
      node = stack[--sp];
    }
  }
};

}  // namespace goris::trace
