#pragma once
// The lighting-aware mask (paper Sec. 3.3, DESIGN.md §5): where the target shows up in reflections. The
// intrinsic renderer traces each glossy pixel's reflection ray carrying the object label, filters it like
// the glossy term and weights it by (1 - M) F (IntrinsicRenderer::reflected_label: E_obj); pixels with
// E_obj > tau (0.1) are the target's reflections, dilated a little so the soft edge of a blurred
// reflection is covered too.
#include <vector>

#include "core/inpaint/mask.h"

namespace goris {

struct LightingMaskSettings {
  float tau = 0.1f;
  // Dilation radius in pixels; < 0 = automatic: 1 pixel per 128 pixels of image width (at least 1).
  int dilate = -1;
};

// The mask from an E_obj image [H][W]. Throws goris::Error for a size mismatch or non-finite values.
Mask lighting_aware_mask(const std::vector<float>& reflected_label, int width, int height,
                         const LightingMaskSettings& settings = {});

}  // namespace goris
