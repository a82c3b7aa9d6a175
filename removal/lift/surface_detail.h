#pragma once
// How much fine detail the glossy surface's own colour has where the removed scene shows it: the texture a
// smooth 2D fill of the hole cannot make.
//
// In one view: over the pixels on the glossy surface (glossy mask >= 0.5) outside the hole grown by
// hole_margin pixels, D minus its Gaussian blur (sigma, normalised by the blur of the same pixel set, so the
// surface's edge and the hole do not darken it), where that blur's support is at least min_support; the RMS
// over those pixels and the three channels. Too few such pixels (min_pixels): no measure.
//
// The fine-tune's material targets (removal_pipeline.h) are the reference views' inpainted maps: on a
// veined or speckled surface their smooth base colour is a wrong target for every pixel of the hole, and
// their weight drops to RemovalOptions::textured_material_weight where this detail exceeds
// SurfaceDetailSettings::textured_above. Measured on the generalization suite's stage-1 runs (medium
// schedule): docs/design/deviations.md, "Material targets on a textured surface".
#include <optional>
#include <vector>

#include "core/inpaint/mask.h"
#include "core/io/image.h"

namespace goris {

struct SurfaceDetailSettings {
  double sigma = 2.0;        // px: the blur whose residual is the detail
  int hole_margin = 3;       // px: the hole grown by this much is left out (its edge is the fill's, not the surface's)
  double min_support = 0.9;  // the blur's weight on measured pixels at least this: the surface's interior
  int min_pixels = 50;       // fewer measured pixels in a view: no measure there
  // The detail above which a surface is textured (colour units, 0-1). Clear and metal tables measured
  // below it, marble ones above (the design note above).
  double textured_above = 0.02;
};

// One view: `rgb` (3 channels, interleaved, the removed scene's colour D), `glossy` (the removed scene's
// glossy mask, one value per pixel), `hole` (the view's inpainting mask). nullopt: too few pixels. Sizes
// must agree (goris::Error otherwise).
std::optional<double> surface_detail_rms(const Image& rgb, const std::vector<float>& glossy, const Mask& hole,
                                         const SurfaceDetailSettings& settings = {});

// The median of the views' measures that exist; nullopt when none does.
std::optional<double> median_surface_detail(const std::vector<std::optional<double>>& per_view);

}  // namespace goris
