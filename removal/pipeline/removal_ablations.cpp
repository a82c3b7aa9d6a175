#include "removal/pipeline/removal_ablations.h"

#include <algorithm>
#include <iterator>

namespace goris {

namespace {

// In the order the unknown-ablation error lists them.
constexpr const char* kAblations[] = {"material", "lamask",     "twins",     "shadows",
                                       "glossfill", "reflection", "underside", "texture"};

}  // namespace

std::string ablation_problem(const std::set<std::string>& ablate) {
  for (const std::string& a : ablate) {
    if (a == "elt" || a == "ssf")
      return "--ablate " + a + " is a stage-1 choice: train the run with " +
             (a == "elt" ? std::string("--mode radiance") : std::string("--set intrinsic_screen_space_filter=false")) +
             " and remove from that run";
    if (std::find(std::begin(kAblations), std::end(kAblations), a) == std::end(kAblations)) {
      std::string known;
      for (std::size_t k = 0; k < std::size(kAblations); ++k)
        known += std::string(k == 0 ? "" : k + 1 == std::size(kAblations) ? " or " : ", ") + kAblations[k];
      return "unknown ablation '" + a + "' (expected " + known + ")";
    }
  }
  return "";
}

}  // namespace goris
