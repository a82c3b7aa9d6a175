#include "removal/selection/selection_labels.h"

#include <algorithm>
#include <cstdio>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/scene/gaussians.h"
#include "core/util/error.h"

namespace goris {

std::string SelectionSummary::describe(const std::string& seed_rule) const {
  char b[512];
  std::snprintf(b, sizeof b, "%zu of %zu Gaussians (%.2f%%): %zu %s", selected, total, 100.0 * fraction(), seeds,
                seed_rule.c_str());
  std::string s = b;
  if (volume != SelectionVolume::Kind::None) {
    std::snprintf(b, sizeof b, ", %zu outliers left out of the %s%s, %zu added inside it", outliers,
                  volume_kind_name(volume),
                  volume == SelectionVolume::Kind::Hull ? (" (" + std::to_string(hull_facets) + " facets)").c_str() : "",
                  by_volume);
    s += b;
  }
  if (dropped) s += ", " + std::to_string(dropped) + " outliers dropped";
  return s;
}

SelectionResult close_selection(const SelectionPoints& pts, const SelectionMask& seeds, const CloseSettings& cs) {
  const std::size_t n = pts.size();
  if (seeds.size() != n)
    throw Error("selection", "seed mask has " + std::to_string(seeds.size()) + " entries for " + std::to_string(n) +
                                 " Gaussians");
  SelectionResult r;
  r.mask.assign(n, 0);
  r.outliers.assign(n, 0);
  r.summary.total = n;
  std::vector<std::uint32_t> seed_ids;
  for (std::size_t i = 0; i < n; ++i)
    if (seeds[i]) {
      seed_ids.push_back(std::uint32_t(i));
      r.mask[i] = 1;
    }
  r.summary.seeds = seed_ids.size();
  if (!cs.enabled || seed_ids.empty()) {
    r.summary.selected = seed_ids.size();
    return r;
  }

  std::vector<glm::vec3> seed_pos(seed_ids.size());
  for (std::size_t k = 0; k < seed_ids.size(); ++k) seed_pos[k] = pts.position[seed_ids[k]];
  const OutlierResult out = find_outliers(seed_pos, cs.outliers);
  std::vector<glm::vec3> inliers;
  std::vector<float> inlier_scale;
  for (std::size_t k = 0; k < seed_ids.size(); ++k) {
    if (out.outlier[k]) {
      r.outliers[seed_ids[k]] = 1;
      ++r.summary.outliers;
      if (!cs.keep_outliers) {
        r.mask[seed_ids[k]] = 0;
        ++r.summary.dropped;
      }
    } else {
      inliers.push_back(seed_pos[k]);
      inlier_scale.push_back(pts.scale[seed_ids[k]]);
    }
  }
  // Thickness of the fallback box: the typical (median) 1-sigma size of the Gaussians that span it.
  double pad = 0.0;
  if (!inlier_scale.empty()) {
    auto mid = inlier_scale.begin() + std::ptrdiff_t(inlier_scale.size() / 2);
    std::nth_element(inlier_scale.begin(), mid, inlier_scale.end());
    pad = *mid;
  }
  // Fewer than 4 centres span no volume; a box padded around one or two would only add whatever happens
  // to lie within one Gaussian's size of them.
  if (inliers.size() >= kMinVolumeSeeds) r.volume = enclosing_volume(inliers, pad, cs.hull);
  r.summary.volume = r.volume.kind;
  r.summary.hull_facets = r.volume.kind == SelectionVolume::Kind::Hull ? r.volume.hull.planes.size() : 0;

  std::vector<std::uint8_t> inside(n, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i)
      if (!seeds[i]) inside[i] = r.volume.contains(pts.position[i]) ? 1 : 0;
  });
  for (std::size_t i = 0; i < n; ++i)
    if (inside[i]) {
      r.mask[i] = 1;
      ++r.summary.by_volume;
    }
  r.summary.selected = count_selected(r.mask);
  return r;
}

SelectionMask label_seeds(const SelectionPoints& pts, float threshold) {
  SelectionMask m(pts.size(), 0);
  for (std::size_t i = 0; i < pts.size(); ++i) m[i] = pts.label[i] > threshold ? 1 : 0;
  return m;
}

SelectionResult select_by_label(const SelectionPoints& pts, const LabelSelectSettings& s) {
  if (!(s.threshold >= 0.0f && s.threshold < 1.0f))
    throw Error("selection", "label threshold " + std::to_string(s.threshold) + " is outside [0, 1)");
  return close_selection(pts, label_seeds(pts, s.threshold), s.close);
}

void apply_selection_to_labels(GaussianModel& model, const SelectionMask& mask) {
  if (mask.size() != model.count())
    throw Error("selection", "mask has " + std::to_string(mask.size()) + " entries for " +
                                 std::to_string(model.count()) + " Gaussians");
  ParamTensor& t = model.tensor(Param::ExtraLogit);
  std::vector<float> logits = t.value.to_host();
  for (std::size_t i = 0; i < mask.size(); ++i)
    logits[std::size_t(t.width) * i + extra::kLabel] = mask[i] ? kSelectionLabelLogit : -kSelectionLabelLogit;
  t.value.upload(logits.data(), logits.size());
}

}  // namespace goris
