#include "core/scene/selection_points.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/gtc/quaternion.hpp>

#include "core/scene/gaussian_kernels.h"
#include "core/scene/gaussians.h"
#include "core/util/error.h"

namespace goris {

std::size_t count_selected(const SelectionMask& mask) {
  return std::size_t(std::count_if(mask.begin(), mask.end(), [](std::uint8_t m) { return m != 0; }));
}

SelectionPoints selection_points(const GaussianModel& model) {
  const std::size_t n = model.count();
  const std::vector<float> pos = model.tensor(Param::Position).value.to_host();
  const std::vector<float> ls = model.tensor(Param::LogScale).value.to_host();
  const std::vector<float> sh = model.tensor(Param::Sh).value.to_host();
  const std::vector<float> ex = model.tensor(Param::ExtraLogit).value.to_host();
  const int sh_width = param_width(Param::Sh);
  const int ex_width = model.tensor(Param::ExtraLogit).width;
  if (n > 0 && (pos.size() != 3 * n || ls.size() != 3 * n || sh.size() != std::size_t(sh_width) * n ||
                ex_width != extra::kCount || ex.size() != std::size_t(ex_width) * n))
    throw Error("selection", "the Gaussian model's arrays do not match its count of " + std::to_string(n));

  SelectionPoints p;
  p.position.resize(n);
  p.scale.resize(n);
  p.color.resize(n);
  p.label.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    p.position[i] = glm::vec3(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]);
    p.scale[i] = std::exp(std::max({ls[3 * i], ls[3 * i + 1], ls[3 * i + 2]}));
    if (!std::isfinite(p.position[i].x) || !std::isfinite(p.position[i].y) || !std::isfinite(p.position[i].z) ||
        !std::isfinite(p.scale[i]))
      throw Error("selection", "Gaussian " + std::to_string(i) + " has a non-finite centre or scale");
    const float* dc = &sh[std::size_t(sh_width) * i];
    p.color[i] = glm::max(kernels::colour_from_sh_dc(glm::vec3(dc[0], dc[1], dc[2])), glm::vec3(0.0f));
    p.label[i] = 1.0f / (1.0f + std::exp(-ex[std::size_t(ex_width) * i + extra::kLabel]));
  }
  return p;
}

std::vector<glm::vec3> flat_normals(const GaussianModel& model) {
  const std::size_t n = model.count();
  const std::vector<float> ls = model.tensor(Param::LogScale).value.to_host();
  const std::vector<float> rot = model.tensor(Param::Rotation).value.to_host();
  if (ls.size() != 3 * n || rot.size() != 4 * n)
    throw Error("selection", "the Gaussian model's scales or rotations do not match its count of " + std::to_string(n));
  std::vector<glm::vec3> out(n, glm::vec3(0.0f));
  for (std::size_t i = 0; i < n; ++i) {
    const float* s = &ls[3 * i];
    const int k = int(std::min_element(s, s + 3) - s);  // smallest axis
    const float middle = std::min(s[(k + 1) % 3], s[(k + 2) % 3]);
    const glm::quat q(rot[4 * i], rot[4 * i + 1], rot[4 * i + 2], rot[4 * i + 3]);  // w, x, y, z
    const float len = glm::length(q);
    if (std::exp(s[k] - middle) < kFlatRatio && len > 0 && std::isfinite(len))
      out[i] = glm::normalize(glm::mat3_cast(q / len)[k]);
  }
  return out;
}

}  // namespace goris
