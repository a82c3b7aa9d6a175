#pragma once
// Normal-prior maps for intrinsic training (paper S1.5: a normal estimator's output; here any folder of
// per-view normal maps). World-space normals in the data set's world frame (the frame the camera poses
// are given in), one file per training view, found as DIR/<view>.exr|.png, DIR/normal_<view>.exr|.png or
// DIR/normal_<digits of the view name>.exr|.png (the scene generator's train/gt/normal_XXX.exr). EXR
// holds raw components, PNG n * 0.5 + 0.5. Resized to the camera, turned into camera space, normalised and
// flipped to face the camera; pixels of (near) zero length become 0 (no prior there).
#include <filesystem>
#include <vector>

#include "train/loop/trainer.h"

namespace goris {

// Fills view.normal_prior of every view; throws goris::Error naming the folder and the view when a file is
// missing or unreadable (a partial prior would silently train some views differently).
void load_normal_priors(const std::filesystem::path& dir, std::vector<TrainView>& views);

}  // namespace goris
