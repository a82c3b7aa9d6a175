#pragma once
// Adaptive density control (3DGS; docs/design/maths.md, Stage 1): accumulate each Gaussian's screen-space
// mean gradient over the views that see it; every `interval` iterations clone small Gaussians and split large
// ones whose average exceeds the threshold, prune transparent (and, after the first opacity reset, oversized)
// ones, and periodically reset opacities. Parameters and Adam moments stay row-aligned through every change:
// surviving rows keep their moments, new rows start with zero moments (as 3DGS's optimizer surgery does).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/compute/buffer.h"
#include "core/scene/gaussians.h"

namespace goris {

struct DensifySettings {
  int from_iter = 500;      // first densification at this iteration
  int until_iter = 12000;   // none after this iteration (the paper's 12K)
  // Density control also stops at this fraction of the run, so that a shortened schedule ends with pure
  // optimisation: see TrainConfig::densify_until. 3DGS's proportion (15K of 30K) is 0.5; 0.75 lets short runs
  // of both modes densify while they learn (docs/design/deviations.md, Densification window of short runs);
  // full runs stop at until_iter.
  float until_fraction = 0.75f;
  int interval = 500;
  float grad_threshold = 2e-4f;  // on the view-averaged |dL/dmean2d| in 3DGS's NDC units
  float percent_dense = 0.01f;   // clone when max scale <= percent_dense * extent, else split
  int split_count = 2;           // children per split Gaussian, scale / (0.8 * split_count)
  float min_opacity = 0.05f;     // prune below (the paper's; 3DGS uses 0.005)
  // Opacity resets, every this many iterations of a full densification window (until_iter). A window that
  // a short run cuts shorter keeps the same number of resets per window: the interval shrinks with it, to
  // a multiple of `interval` (TrainConfig::opacity_reset_every). A reset is what dissolves the semi-opaque
  // fog a random start leaves between high cameras and a floor; a 2K run without one kept that fog
  // (docs/design/deviations.md, Opacity resets of short runs).
  int opacity_reset_interval = 3000;
  float reset_opacity = 0.01f;      // opacities are clamped to this at a reset
  float max_screen_radius = 20.0f;  // pixels; prune above after the first reset (0 = never)
  float max_world_scale = 0.1f;     // x extent; prune above after the first reset (0 = never)
};

// The densification statistic per Gaussian, on the model's device.
struct DensifyStats {
  Buffer<float> grad_accum;  // sum over views of |dL/dmean2d| (NDC units)
  Buffer<float> denom;       // number of views that saw the Gaussian (radius > 0)
  Buffer<float> max_radii;   // largest screen radius seen (pixels)

  void reset(size_t n, Device d);
  // Adds one view: for every Gaussian with radii > 0, grad_accum += view_grad_norm * ndc_scale,
  // denom += 1, max_radii = max(max_radii, radii). Pointers on device d, n = the model's count.
  void add_view(const float* view_grad_norm, const std::int32_t* radii, float ndc_scale, size_t n, Device d);
};

// The factor turning a pixel-space |dL/dmean2d| of a width x height view into 3DGS's NDC-space one:
// exact (W/2) for square images, sqrt((W/2)(H/2)) in general.
float ndc_gradient_scale(int width, int height);

struct DensifyCounts {
  size_t before = 0, cloned = 0, split = 0, pruned = 0, after = 0;
};

// One densification step on `model` (any device; a CUDA model makes a round trip through host memory,
// which is cheap at this frequency). Per Gaussian i with average gradient g_i = accum / denom:
//   g_i >= threshold and max scale <= percent_dense * extent  -> clone (an identical copy);
//   g_i >= threshold and larger                               -> split into split_count children sampled
//        from N(mu, R S^2 R^T), log scales - log(0.8 * split_count), the parent removed;
//   opacity < min_opacity, or (prune_large and (max_radii > max_screen_radius or
//        max scale > max_world_scale * extent))                -> removed (with its clone / children).
// Row order afterwards: surviving originals in order, then clones and children in parent order. The 3D
// filter is carried along (recompute it afterwards), `stats` must be reset by the caller. `seed` makes
// the split samples deterministic.
DensifyCounts densify_and_prune(GaussianModel& model, const DensifyStats& stats, const DensifySettings& settings,
                                float extent, bool prune_large, std::uint64_t seed);

// Keeps the rows where keep[i] != 0 (moments carried along); returns the number removed.
size_t prune_gaussians(GaussianModel& model, const std::vector<std::uint8_t>& keep);

// opacity = min(opacity, max_opacity) for every Gaussian, and the opacity moments zeroed.
void reset_opacity(GaussianModel& model, float max_opacity);

}  // namespace goris
