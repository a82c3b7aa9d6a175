#pragma once
// Metrics of what an object removal must fix, on one test view. Images are planar [3][H][W] floats in
// [0, 1] (sRGB-encoded, channel-major, row-major per channel):
//   render  our cleaned render,
//   after   the ground truth after removal (the scene without the target),
//   before  the ground truth with the target still in it.
// The changed region is where before and after differ, i.e. the pixels the removal has to repaint; the
// metrics inside it are the ones a whole-image average dilutes with the untouched background.
#include <cstdint>
#include <vector>

#include "core/metrics/flip.h"

namespace goris {

struct ChangedRegionOptions {
  float threshold = 0.04f;  // a pixel changed when max over channels |before - after| (after the median) > this
  int median = 3;           // median window side (odd; even rounds up) on before and after per channel; <= 1: off
  int dilate = 2;           // grow the thresholded region by this many pixels (square element); 0 disables it
};

// The changed region as a [H][W] mask (1 = changed) and its fraction of the image. The median makes
// single-pixel path-tracing noise in either image no change; its window clamps to the edge.
struct ChangedRegion {
  std::vector<uint8_t> mask;
  double fraction = 0;
};
ChangedRegion changed_region(const float* before, const float* after, int width, int height,
                             const ChangedRegionOptions& options = {});

// Per-pixel SSIM ([H][W], the mean over `channels` planar channels) as 3DGS computes it: 11x11 Gaussian
// window of sigma 1.5 applied as two separable passes with zero padding, C1 = 0.01^2, C2 = 0.03^2. Its
// mean over all pixels is the usual SSIM.
std::vector<float> ssim_map(const float* a, const float* b, int width, int height, int channels = 3);

struct RemovalMetrics {
  double region_fraction = 0;  // share of the image in the changed region
  double region_psnr = 0;      // PSNR (dB) of render vs after over the region's pixels and 3 channels; +inf if equal
  double region_ssim = 0;      // mean of the render-vs-after SSIM map over the region's pixels
  // sum |render - after| / sum |before - after| over the region, each image after the region's median (so
  // that the ground truth's path-tracing noise is no ghost): 1 = nothing removed, 0 = all of it.
  double ghost_ratio = 0;
  double ghost_residual = 0, ghost_imprint = 0;  // its numerator and denominator, to pool over views
  double flip = 0;             // LDR-FLIP mean of render vs after over the whole image
  double region_flip = 0;      // LDR-FLIP mean over the region's pixels
  std::vector<uint8_t> region;  // the changed region, [H][W], 1 = changed
};

// sum |a - b| over the region's pixels and 3 channels, each image after a median of side `median` (as the
// ghost ratio compares them; <= 1: none). The ghost's residual is region_residual(render, after), its
// imprint region_residual(before, after); the same sum between the render of the model a removal started from
// and `before` is how far that model was from the photos where the target changed them (its ghost floor).
double region_residual(const float* a, const float* b, const std::vector<uint8_t>& region, int width, int height,
                       int median = ChangedRegionOptions{}.median);

// Every region metric is NaN when the region is empty; ghost_ratio is also NaN when before and after are
// (nearly) equal over the region. Throws std::invalid_argument on null images or a non-positive size.
RemovalMetrics removal_metrics(const float* render, const float* after, const float* before, int width, int height,
                               const ChangedRegionOptions& options = {}, double ppd = kFlipDefaultPpd);

}  // namespace goris
