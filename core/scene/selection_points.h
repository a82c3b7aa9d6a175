#pragma once
// What target selection (docs/design/maths.md, Stage 2; paper Sec. 3.3) reads of a Gaussian scene: a host
// copy of the per-Gaussian quantities the selection rules compare, activated, from a GaussianModel on any
// device. A selection itself is a per-Gaussian 0/1 mask in the model's order (SelectionMask).
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace goris {

class GaussianModel;

// One byte per Gaussian, 1 = selected (the target), 0 = kept. Index i is Gaussian i of the model.
using SelectionMask = std::vector<std::uint8_t>;

std::size_t count_selected(const SelectionMask& mask);

struct SelectionPoints {
  std::vector<glm::vec3> position;  // centre mu
  std::vector<float> scale;         // largest axis scale exp(max log_scale), world units
  std::vector<glm::vec3> color;     // SH DC colour: 0.5 + C0 * dc, clamped at 0 (view-independent part)
  std::vector<float> label;         // sigmoid(label logit), the learned object label
  std::size_t size() const { return position.size(); }
};

// Copies and activates what selection needs (explicit device-to-host copies when the model is on CUDA).
// Throws goris::Error when a centre or scale is not finite (a broken checkpoint would otherwise poison
// every neighbour query).
SelectionPoints selection_points(const GaussianModel& model);

// Per Gaussian, the unit axis of its smallest scale where it is flat (smallest < kFlatRatio x middle scale),
// else zero: a surface element's normal (sign arbitrary). The mirror twins' plane is fitted to these
// (mirror_twins.h); kept apart from selection_points so that selection does not download the rotations.
constexpr float kFlatRatio = 0.3f;
std::vector<glm::vec3> flat_normals(const GaussianModel& model);

}  // namespace goris
