#pragma once
// How much of each Gaussian a set of pixels shows: per view, a Gaussian's weight in a pixel is its
// alpha * T there (how much of the pixel's colour it makes), read as the gradient of an all-ones extra
// channel; summed over the pixels inside a per-view mask and over the others.
#include <vector>

#include "core/inpaint/mask.h"
#include "core/io/camera.h"
#include "core/scene/gaussians.h"
#include "render/raster/raster_types.h"

namespace goris {

struct PixelWeights {
  std::vector<float> inside, outside;  // per Gaussian, summed over views (pixels)
};

// `masks[v]` is camera v's mask at its size (non-zero = inside). Throws goris::Error when the counts or sizes
// differ.
PixelWeights gaussian_pixel_weights(const GaussianModel& model, const std::vector<Camera>& cameras,
                                    const std::vector<Mask>& masks, const RasterSettings& raster);

}  // namespace goris
