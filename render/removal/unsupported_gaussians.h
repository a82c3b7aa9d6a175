#pragma once
// Gaussians that no photo supports once the target is gone. Stage 1 fits whatever lies behind the target
// only through the pixels the target covers: space that every view sees through the target is free to
// hold anything (a fog in the wall's colour, the target's colours below the floor, the mirror world
// through the table top where the target stood), since the target hid it in every photo. After the
// removal it shows where the target stood, and none of the fine-tune's photo pixels (all outside the
// target's coverage) can correct it.
//
// Rule: render the scene without the target in every training view; a Gaussian's weight in a pixel is its
// alpha * T there (read as the gradient of an all-ones extra channel). It is unsupported when its weight
// summed over the pixels the target covered (where the selection's coverage in the full render is above
// coverage_threshold: the photo showed the target there, not what is behind it) is at least min_inside_px,
// and its weight over every other pixel of every view is both less than max_outside_share of its total and
// less than max_outside_px: the table at the target's foot, which the removal bares in the target's pixels,
// had its own photo pixels beside the target, a small share of its weight but whole pixels of it. Such Gaussians are deleted with the target; the inpainting masks then
// see the hole they leave and fill it.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/io/camera.h"
#include "core/scene/gaussians.h"
#include "render/raster/raster_types.h"

namespace goris {

struct UnsupportedSettings {
  float max_outside_share = 0.05f;   // weight outside the target's coverage, as a share of the total
  float max_outside_px = 0.5f;       // and in pixels (summed over views)
  float min_inside_px = 0.5f;        // weight inside it (pixels summed over views) below which nothing is said
  float coverage_threshold = 0.5f;   // the selection's rendered coverage that counts as "the target's pixel"
};

struct UnsupportedWeights {
  std::vector<float> inside, outside;  // per Gaussian of the full model (0 for selected ones)
};

// Per-Gaussian weights of the scene without `selected`, inside and outside the target's coverage.
UnsupportedWeights unsupported_weights(const GaussianModel& model, const std::vector<std::uint8_t>& selected,
                                       const std::vector<Camera>& cameras, const RasterSettings& raster,
                                       const UnsupportedSettings& settings = {});

// 1 for the unselected Gaussians that the rule above calls unsupported.
std::vector<std::uint8_t> unsupported_gaussians(const UnsupportedWeights& w, const std::vector<std::uint8_t>& selected,
                                                const UnsupportedSettings& settings = {});

}  // namespace goris
