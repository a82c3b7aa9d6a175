#pragma once
// The target's underside: Gaussians of the kept model that stand on the glossy surface inside the target's
// footprint, below its top. Stage 1 places a few there (the underside of a ball, the foot of a monkey), where no
// photo sees them but the surface's reflection of them: they are never part of the object's masks or votes, so a
// selection leaves them, and after the removal they stand where the target stood, as a remnant of its colour and
// in the traced glossy term's reflection of it (a tinted patch on the table). They go with the target.
//
// Footprint: in the glossy plane, within radius_ratio x the radius_quantile of the target's centres' distances
// from their centroid (a disc inside the target's outline for a round target); height: above the plane and
// below the target's highest centre.
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene/mirror_twins.h"
#include "core/scene/selection_points.h"

namespace goris {

struct UndersideSettings {
  // 0.7 of the 90 % radius: on the generalization suite 1.0 reached a neighbouring object's foot on one scene
  // (-0.35 dB), 0.7 lowered none (docs/design/deviations.md, "The target's underside").
  double radius_ratio = 0.7;
  double radius_quantile = 0.9;
};

// Gaussians (centres) that are in neither `target` nor `selected` and lie in the target's footprint under its
// top, as a mask over `centres`. Empty when the target has no Gaussian or the plane was not found.
SelectionMask target_underside(const std::vector<glm::vec3>& centres, const SelectionMask& target,
                               const SelectionMask& selected, const MirrorPlane& plane,
                               const UndersideSettings& settings = {});

}  // namespace goris
