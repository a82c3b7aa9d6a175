#pragma once
// The parts of the removal `goris remove --ablate` switches off (RemovalOptions::ablate, removal_pipeline.h):
// their names and what each switches off, in one table (removal_ablations.cpp).
#include <set>
#include <string>

namespace goris {

// "" when every name is a known ablation; otherwise why not (a stage-1 choice, or the names it takes).
std::string ablation_problem(const std::set<std::string>& ablate);

// "material (RGB-only inpainting), lamask (...), ...": every ablation with what it switches off, for help texts.
std::string ablation_help();

}  // namespace goris
