#pragma once
// What photo_targets_against_truth (finetune_views.h) measures: sums over every training view of the
// mean-RGB |x - truth| per pixel, against the views rendered without the target (`goris synth --train-after`).
#include <cstddef>

namespace goris {

struct PhotoTargetsTruthError {
  double imprint = 0;               // over every pixel: the target's whole imprint on the photos
  std::size_t trained_pixels = 0;   // pixels whose photo loss is on
  double photos = 0, targets = 0;   // over those: the photos as taken, the photos as trained
  std::size_t changed_pixels = 0;   // of those, the ones the removal changed (dereflected or relit)
  double changed_photos = 0, changed_targets = 0;  // over the changed ones alone
};

}  // namespace goris
