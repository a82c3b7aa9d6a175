#pragma once
// The training hooks (train/loop/hooks/train_hook.h). Each reads its settings from the run's TrainConfig
// (HookStep::config), so that a configuration stays the one description of a run, and keeps only the state
// of its behaviour.
#include <cstddef>
#include <string>
#include <vector>

#include "train/loop/glossy_plane.h"
#include "train/loop/hooks/train_hook.h"

namespace goris {

// intrinsic.emit = mask or max (train/loop/emit_weights.h): gives the renderer emit weights computed from
// the glossy masks, refreshed every kRefreshInterval iterations and whenever the Gaussian count changed.
// Only for renderers that take the extra channels (the weights choose what traced rays see).
class EmitWeightsHook final : public TrainHook {
 public:
  static constexpr const char* kName = "emit_weights";
  static constexpr int kRefreshInterval = 25;
  const char* name() const override { return kName; }
  void before_forward(HookStep& step) override;
  // The weights last given to the renderer (of the model of that iteration), as the checkpoint's float
  // block: a uint64 count, then the floats. A resumed run gives the renderer these again instead of weights
  // computed from its later model.
  std::string serialize() const override;
  void deserialize(const std::string& bytes, const std::string& source) override;
  const std::vector<float>& weights() const { return weights_; }

 private:
  std::vector<float> weights_;  // empty = none yet
  bool given_ = false;          // weights_ are the renderer's
};

// depth_distortion_weight > 0 (train/losses/depth_distortion.h): the distortion pass of its own after the
// backward pass, on its schedule (TrainConfig::depth_distortion_at), with depth_distortion_glossy weighting
// the glossy-mask pixels.
class DepthDistortionHook final : public TrainHook {
 public:
  const char* name() const override { return "depth_distortion"; }
  void after_backward(HookStep& step) override;

 private:
  // The per-pixel weights of `step`'s view, or null for 1 everywhere. Points into pixel_weights_.
  const float* pixel_weights(const HookStep& step);
  std::vector<float> pixel_weights_;  // scratch, one view's
};

// intrinsic.prune_mirror_world > 0 in intrinsic mode (train/loop/mirror_world.h): removes the warm-up's
// mirror world at the last warm-up iteration and, with the repeat, after every densification of the
// shading phase (TrainConfig::prunes_mirror_world_after).
class MirrorWorldHook final : public TrainHook {
 public:
  const char* name() const override { return "mirror_world"; }
  void after_densify(HookStep& step) override;
};

// intrinsic.glossy_plane in intrinsic mode (train/loop/glossy_plane.h): fits the glossy plane at the last
// warm-up iteration, then keeps the Gaussians over glossy pixels on the cameras' side after every update
// (with prune_sinkers and align as configured). Its state is fitted again after a resume, not stored.
class GlossyPlaneHook final : public TrainHook {
 public:
  const char* name() const override { return "glossy_plane"; }
  void after_densify(HookStep& step) override;
  const GlossyPlaneConstraint& constraint() const { return constraint_; }

 private:
  GlossyPlaneConstraint constraint_;
};

}  // namespace goris
