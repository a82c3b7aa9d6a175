#pragma once
// The lighting-aware mask (paper Sec. 3.3; docs/design/maths.md, Lighting-aware mask): where the target shows
// up in reflections. The intrinsic renderer traces each glossy pixel's reflection ray carrying the object
// label, filters it like the glossy term and weights it by (1 - M) F (IntrinsicRenderer::reflected_label:
// E_obj); pixels with E_obj > tau (0.1) are the target's reflections, dilated a little so the soft edge of a
// blurred reflection is covered too.
//
// Why F is taken relative to the scene's own F0 (our change to the paper, default of `goris remove`;
// `--lighting-fresnel absolute` restores the paper's weighting): stage 1 learns F0 and the environment's
// brightness only up to a trade-off (the synthesised glossy table's metal, true F0 0.94, came out ~0.4 with a
// brighter environment; steel_snowman's steel table ~0.15), so an absolute tau on (1 - M) F x label found
// 15,040 px of reflection on steel_snowman with one set of learning rates and 28 px with another. Dividing
// F by the 90th percentile of the glossy Gaussians' F0 (capped at 1) keeps what the weighting is for - weak
// reflectors and normal incidence count less than strong ones and grazing angles - without the scale.
#include <cstdint>
#include <optional>
#include <vector>

#include "core/inpaint/mask.h"
#include "core/scene/selection_points.h"

namespace goris {

class GaussianModel;

struct LightingMaskSettings {
  float tau = 0.1f;
  // Dilation radius in pixels; < 0 = automatic: 1 pixel per 128 pixels of image width (at least 1).
  int dilate = -1;
};

// The mask from an E_obj image [H][W]. Throws goris::Error for a size mismatch or non-finite values.
Mask lighting_aware_mask(const std::vector<float>& reflected_label, int width, int height,
                         const LightingMaskSettings& settings = {});

// The Fresnel scale that reflected_label() divides F by: the opacity-weighted `quantile` of mean-RGB F0
// over the glossy Gaussians (region < 0.5) that are not in `target`. 1 (the paper's absolute weighting)
// when no Gaussian is glossy. Throws goris::Error when the model has no material channels or the mask's
// size differs.
float glossy_fresnel_reference(const GaussianModel& model, const SelectionMask& target, float quantile = 0.9f);

// The opacity-weighted `quantile` of mean-RGB F0 over the Gaussians `among` says (one entry per Gaussian);
// nothing when none of them has a finite F0 and a positive opacity. Throws goris::Error when the model has no
// material channels or the mask's size differs.
std::optional<float> fresnel_quantile(const GaussianModel& model, const SelectionMask& among, float quantile);

}  // namespace goris
