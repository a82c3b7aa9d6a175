#pragma once
// Do a run's materials tell the glossy surface from the rest of the scene? (Does the roughness map separate
// table and objects?) Needs no intrinsic ground truth, only the data set's glossy masks: every
// training view is rasterized with its material channels, and the opaque pixels (alpha >= 0.5) are split
// into glossy (mask >= 0.5) and the rest (mask < 0.5: the objects and any rough surface). Per side: median
// and mean of the alpha-normalised roughness, F0 (mean over RGB) and region weight M. The separation is
// the ROC AUC of roughness as a glossy/rest classifier: the probability that a random "rest" pixel is
// rougher than a random glossy one (ties count half): 0.5 = no separation, 1 = every rest pixel rougher.
#include <cstddef>
#include <vector>

#include "core/scene/gaussians.h"
#include "render/raster/raster_types.h"
#include "train/loop/trainer.h"

namespace goris {

struct MaterialStats {
  std::size_t pixels = 0;
  double roughness_median = 0, roughness_mean = 0;
  double f0_median = 0, f0_mean = 0;
  double region_median = 0, region_mean = 0;
};

struct MaterialSeparation {
  std::size_t views = 0;
  MaterialStats glossy, rest;
  double roughness_auc = 0.5;
};

// `views` carry their glossy masks (TrainView::glossy_mask); views without one are skipped. Throws
// goris::Error when the model has no material channels or either side has no opaque pixel.
MaterialSeparation measure_material_separation(const GaussianView& gaussians, const std::vector<TrainView>& views,
                                               const RasterSettings& raster, Device device);

// P(rest > glossy) + P(rest == glossy) / 2 over all pairs, from the two samples (sorted internally).
double probability_greater(std::vector<float> rest, std::vector<float> glossy);

}  // namespace goris
