#include "removal/pipeline/removal_ablations.h"

#include <algorithm>
#include <iterator>

namespace goris {

namespace {

struct Ablation {
  const char* name;
  const char* what;  // what switching it off does (the --ablate help)
};

// In the order the help and the unknown-ablation error list them.
constexpr Ablation kAblations[] = {
    {"material", "RGB-only inpainting"},
    {"lamask", "no lighting-aware mask: neither reflections nor shadow"},
    {"twins", "keep the target's mirror twin below a planar glossy surface"},
    {"shadows", "keep the target's cast shadow"},
    {"glossfill", "fine-tune with the photos' glossy masks under the target instead of masks filled from around it"},
    {"reflection", "no mask of the target mirrored through the glossy plane, and the glossy surface's part of the "
                   "hole filled like the rest instead of from the surface alone"},
    {"underside", "keep the Gaussians that stand on the glossy surface under the target"},
    {"texture", "the target's planar reflection filled everywhere, also where the dereflected photo differs from "
                "the fill only by the surface's texture"},
};

}  // namespace

std::string ablation_problem(const std::set<std::string>& ablate) {
  for (const std::string& a : ablate) {
    if (a == "elt" || a == "ssf")
      return "--ablate " + a + " is a stage-1 choice: train the run with " +
             (a == "elt" ? std::string("--mode radiance") : std::string("--set intrinsic_screen_space_filter=false")) +
             " and remove from that run";
    if (std::none_of(std::begin(kAblations), std::end(kAblations), [&](const Ablation& k) { return a == k.name; })) {
      std::string known;
      for (std::size_t k = 0; k < std::size(kAblations); ++k)
        known += std::string(k == 0 ? "" : k + 1 == std::size(kAblations) ? " or " : ", ") + kAblations[k].name;
      return "unknown ablation '" + a + "' (expected " + known + ")";
    }
  }
  return "";
}

std::string ablation_help() {
  std::string help;
  for (const Ablation& k : kAblations) help += std::string(help.empty() ? "" : ", ") + k.name + " (" + k.what + ")";
  return help;
}

}  // namespace goris
