#pragma once
// One splat evaluated on a group of pixel lanes of a row, the 3DGS hit rule shared by the CPU forward and
// backward loops: offsets to the mean, the Gaussian G = exp(power) (power <= 0), alpha = min(0.99, o G),
// and the lanes that blend (inside `cols`, alpha >= 1/255).
#include "render/raster/blend.h"
#include "render/raster/lanes_cpu.h"
#include "render/raster/tile_loop.h"

namespace goris::raster {

template <class T>
struct LaneHit {
  LaneV<T> dx, dy, G, oG, alpha;
  LaneM<T> m;  // lanes that blend
};

template <class T>
inline LaneHit<T> lane_hit(const SplatView<T>& s, T px0, T py, unsigned cols) {
  using V = LaneV<T>;
  LaneHit<T> h;
  h.dx = s.mean.x - lane_iota(px0);
  h.dy = lane_splat(s.mean.y - py);
  const V power = hit_power(s.conic, h.dx, h.dy);
  h.m = lane_mask<T>(cols) & ~(power > T(0));
  h.G = lane_exp(lane_select(h.m, power, V{}));
  h.oG = s.opacity * h.G;
  h.alpha = lane_select(h.oG < BlendConst<T>::alpha_max, h.oG, lane_splat(BlendConst<T>::alpha_max));
  h.m &= ~(h.alpha < BlendConst<T>::alpha_min);
  return h;
}

}  // namespace goris::raster
