#pragma once
// Optional behaviours of the training loop (train/loop/trainer.h) as small objects, in the manner of
// gsplat's densification strategies: the loop itself renders, computes the losses, runs the backward pass,
// steps the optimiser and controls the density; everything a configuration may switch on besides (emit
// weights from the glossy masks, the depth distortion pass, the mirror-world prune, the glossy plane) is a
// TrainHook that the loop calls at fixed points of each step. make_train_hooks() creates only the hooks a
// configuration needs, in a fixed order; a hook keeps the state that belongs to its behaviour and, where a
// resumed run must continue bit for bit, stores it in checkpoints (serialize / deserialize).
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/scene/gaussian_view.h"

namespace goris {

class DifferentiableRenderer;
class GaussianModel;
struct StepStats;
struct TrainConfig;
struct TrainView;

// What a hook sees of the step being run.
struct HookStep {
  int iteration;  // 1-based: the iteration this step completes
  const TrainConfig& config;
  GaussianModel& model;
  const std::vector<TrainView>& views;  // all training views
  const TrainView& view;                // this step's view
  DifferentiableRenderer& renderer;
  float extent;     // the scene's size (Trainer::extent)
  StepStats& out;   // this step's losses and notes
  // after_backward: the Gaussians as the forward pass rendered them and the gradients to add to.
  const GaussianView* gaussians = nullptr;
  const GaussianGradView* grads = nullptr;
  // To be called by a hook that removed Gaussians: resets what is sized by their count (densification
  // statistics, 3D filter).
  std::function<void()> model_pruned = {};

  // Appends a note for the user to out.densify_note ("; " between notes).
  void note(const std::string& text);
};

class TrainHook {
 public:
  virtual ~TrainHook() = default;
  // Names the hook's state in checkpoints (TrainerState::hooks); unique per hook type.
  virtual const char* name() const = 0;

  // After the renderer was told the iteration, before the forward pass.
  virtual void before_forward(HookStep& /*step*/) {}
  // After the renderer's backward pass, before the gradients are checked: a hook may add gradients (and
  // loss to out.loss; a non-finite loss then skips the step).
  virtual void after_backward(HookStep& /*step*/) {}
  // After the optimiser step and the density control of the iteration.
  virtual void after_densify(HookStep& /*step*/) {}

  // The hook's state as bytes for a checkpoint (empty = nothing worth keeping), and back. `source` names
  // the file in errors.
  virtual std::string serialize() const { return {}; }
  virtual void deserialize(const std::string& /*bytes*/, const std::string& /*source*/) {}
};

using TrainHooks = std::vector<std::unique_ptr<TrainHook>>;

// The hooks `config` switches on, for a run on `renderer`, in the order the loop calls them: emit weights,
// depth distortion, mirror-world prune, glossy plane.
TrainHooks make_train_hooks(const TrainConfig& config, const DifferentiableRenderer& renderer);

}  // namespace goris
