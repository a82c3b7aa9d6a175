#pragma once
// Selecting the target from the learned object label (docs/design/maths.md, Stage 2; paper Sec. 3.3): every
// Gaussian with label > 0.3, closed by every Gaussian whose centre lies inside the convex hull of the
// selected centres (outliers left out of the hull first, so that stray labels cannot inflate it). The
// closing step is shared with the other selection rules (masks, click + grow): close_selection().
//
//   SelectionPoints pts = selection_points(model);
//   SelectionResult r = select_by_label(pts, {});          // r.mask: per-Gaussian 0/1, r.summary: counts
//   apply_selection_to_labels(model, r.mask);             // e.g. before tracing the lighting-aware mask
#include <cstddef>
#include <string>

#include "core/scene/select_hull.h"
#include "core/scene/selection_points.h"
#include "removal/selection/select_outliers.h"

namespace goris {

class GaussianModel;

// How a selection is closed: seeds -> outliers (select_outliers.h) -> hull of the other seeds (or, for a
// degenerate set, their oriented box padded by the median largest-axis scale of those Gaussians) -> every
// Gaussian inside it is added. Fewer than kMinVolumeSeeds inlier seeds are not closed at all.
constexpr std::size_t kMinVolumeSeeds = 4;
struct CloseSettings {
  bool enabled = true;  // false: the seeds are the selection
  OutlierSettings outliers;
  // Outlier seeds stay selected: they only do not shape the hull. The paper deletes every Gaussian with
  // label > 0.3, wherever it is; set false to drop them from the selection as well.
  bool keep_outliers = true;
  HullSettings hull;
};

// What a selection rule found. Every count is a number of Gaussians.
struct SelectionSummary {
  std::size_t total = 0;      // in the model
  std::size_t seeds = 0;      // chosen by the rule itself (label > threshold, mask votes, ...)
  std::size_t outliers = 0;   // seeds left out of the hull (isolated + in small groups)
  std::size_t by_volume = 0;  // added because their centre lies inside the closing volume
  std::size_t dropped = 0;    // outlier seeds removed from the selection (keep_outliers = false)
  std::size_t selected = 0;   // in the final mask
  SelectionVolume::Kind volume = SelectionVolume::Kind::None;
  std::size_t hull_facets = 0;

  double fraction() const { return total ? double(selected) / double(total) : 0.0; }
  // One line for logs and the CLI, e.g. "412 of 30000 Gaussians (1.37%): 380 by label, 3 outliers, ...".
  std::string describe(const std::string& seed_rule) const;
};

struct SelectionResult {
  SelectionMask mask;      // final selection
  SelectionMask outliers;  // 1 = a seed judged an outlier (for display)
  SelectionVolume volume;  // the closing volume (kind None when not closed)
  SelectionSummary summary;
};

// Closes `seeds` (size = pts.size(), else goris::Error) as described above.
SelectionResult close_selection(const SelectionPoints& pts, const SelectionMask& seeds, const CloseSettings& settings = {});

struct LabelSelectSettings {
  float threshold = 0.3f;  // activated label above which a Gaussian is the target (paper: 0.3)
  CloseSettings close;
};

SelectionMask label_seeds(const SelectionPoints& pts, float threshold);
SelectionResult select_by_label(const SelectionPoints& pts, const LabelSelectSettings& settings = {});

// Writes the selection into the model's label channel as confident logits (+-kSelectionLabelLogit, i.e.
// labels 0.9975 / 0.0025), so that label-driven steps (the lighting-aware mask traces the label) follow a
// selection made by clicking or masks. Throws goris::Error when the sizes differ.
constexpr float kSelectionLabelLogit = 6.0f;
void apply_selection_to_labels(GaussianModel& model, const SelectionMask& mask);

}  // namespace goris
