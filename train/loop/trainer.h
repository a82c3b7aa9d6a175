#pragma once
// The training loop (stage 1, radiance mode: docs/design/maths.md, Stage 1), usable from the CLI and from a
// GUI thread: step() runs one iteration (render, losses, backward, optimiser step, density control, and the
// optional behaviours as training hooks: train/loop/hooks/train_hook.h); run() loops with periodic
// checkpoints, a CSV log and a progress callback, and stops cleanly (checkpoint written) when a stop flag is
// raised. A NaN/Inf loss, gradient or parameter throws goris::Error naming the iteration and the parameter
// group; the checkpoints on disk stay intact.
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "core/compute/host_device_image.h"
#include "core/io/camera.h"
#include "core/scene/gaussians.h"
#include "train/config/train_config.h"
#include "train/loop/differentiable_renderer.h"
#include "train/loop/hooks/train_hook.h"
#include "train/optimizer/adam.h"
#include "train/optimizer/densify.h"
#include "train/optimizer/param_groups.h"

namespace goris {

// Stage-2 targets of one view inside the inpainting hole (paper Sec. 3.4, S1.4-S1.5): an appearance
// target on the rough part, material targets on the glossy part. Planar host images at the camera's size;
// weights in [0, 1] select the pixels (0 = no target there).
struct InpaintTargets {
  std::vector<float> color;              // [3][H][W] inpainted colour
  std::vector<float> appearance_weight;  // [H][W]
  std::vector<float> base_color;         // [3][H][W] D (the SH colour) target
  std::vector<float> f0;                 // [3][H][W]
  std::vector<float> roughness;          // [H][W]
  std::vector<float> normal;             // [3][H][W] unit, camera space (zero = no target)
  std::vector<float> material_weight;    // [H][W]
};

// One training image with its camera, the image as planar RGB [3][H][W] on the host, at camera's size,
// and what intrinsic mode uses when the data set has it (empty vectors = not available).
struct TrainView {
  std::string name;
  Camera camera;
  std::vector<float> image;
  std::vector<float> glossy_mask;   // [H][W] in [0, 1]: the paper's M_gt
  std::vector<float> object_mask;   // [H][W] in [0, 1]: the target
  std::vector<float> normal_prior;  // [3][H][W] unit normals in camera space (OpenCV axes, facing the camera)
  std::vector<float> alpha;         // [H][W] the image's alpha channel (coverage), when it has one
  // Stage 2: weight of the photo losses per pixel ([H][W], empty = 1 everywhere; 0 under the target and
  // its reflections), and the inpainting targets (null = none for this view).
  std::vector<float> loss_weight;
  std::shared_ptr<const InpaintTargets> inpaint;
};

// Each view's glossy mask, null where it has none: the form plane_from_glossy_masks takes
// (core/scene/plane_from_masks.h). The pointers are into `views`.
std::vector<const std::vector<float>*> glossy_masks_of(const std::vector<TrainView>& views);
// Each view's camera, in order.
std::vector<Camera> cameras_of(const std::vector<TrainView>& views);

// Everything that changes while training; a checkpoint stores exactly this (and the config).
struct TrainerState {
  int iteration = 0;  // iterations completed
  GaussianModel model;
  GaussianAdam adam;
  DensifyStats stats;
  std::mt19937_64 rng;                   // view order
  std::vector<std::uint32_t> view_stack; // views left in this epoch (taken from the back)
  double ema_loss = 0, ema_psnr = 0;     // training loss / PSNR smoothed over ~20 iterations, for display
  double elapsed_s = 0;                  // training time so far, over all sessions
  double lr_scale = 1.0;                 // lowered by each step skipped for non-finite values
  int skipped_steps = 0;                 // in all; consecutive ones are counted in the trainer
  // The training hooks' own state by hook name (TrainHook::serialize; train/loop/hooks/train_hook.h), as a
  // checkpoint or Trainer::save_checkpoint left it. A Trainer built on this state gives each hook its part.
  std::map<std::string, std::string> hooks;
};

struct TrainProgress {
  int iteration = 0, total = 0;
  double loss = 0, psnr = 0;  // smoothed over recent iterations
  size_t gaussians = 0;
  double it_per_s = 0, eta_s = 0, elapsed_s = 0;
};

struct StepStats {
  double loss = 0, l1 = 0, ssim = 0, depth_normal = 0, distortion = 0, psnr = 0;
  double alpha = 0;  // alpha_weight's L1 against the image's alpha (0 when off)
  // Intrinsic-mode terms (unweighted; 0 when off).
  double normal_prior = 0, smoothness = 0, region = 0, label = 0;
  double appearance = 0, material = 0;  // stage 2 (0 when off)
  DensifyCounts densify;  // after == 0 when this step did not densify
  int view = -1;          // the training view of this step
  // How many Gaussians the mirror-world pruning removed in this step (empty: none).
  std::string densify_note;
  // A step skipped for non-finite values (nan_policy recover): what was found, where; nothing was updated.
  bool skipped = false;
  std::string problem;
};

class Trainer {
 public:
  // `extent`: the scene's size (3DGS camera extent radius): scales the position learning rate, the
  // clone/split limit and world-space pruning. The model in `state` must live on the renderer's device.
  Trainer(TrainConfig config, std::vector<TrainView> views, float extent,
          std::shared_ptr<DifferentiableRenderer> renderer, TrainerState state);

  // A fresh state: the model from initial points (SfM or random; see core/scene/gaussian_init.h), RNG
  // seeded from config.seed.
  static TrainerState initial_state(const TrainConfig& config, GaussianModel model);

  // One iteration. Returns the losses of this step.
  StepStats step();
  bool finished() const { return state_.iteration >= config_.iterations; }

  enum class RunResult { Finished, Stopped };
  struct RunOptions {
    std::filesystem::path run_dir;                 // checkpoints/ and log.csv; empty = neither
    const std::atomic<bool>* stop = nullptr;       // raised (e.g. by SIGINT): finish the step, checkpoint, return
    std::function<void(const TrainProgress&)> on_progress;  // called every progress_every iterations and at the end
    int progress_every = 10;
    std::function<void(const std::string&)> on_skip;  // a step skipped for non-finite values (default: stderr)
    std::function<void(const std::string&)> on_note;  // StepStats::densify_note (default: stdout)
    // Called before every step (--mode auto's switch after the warm-up: train/setup/auto_mode.h); its time
    // counts as training time but not as iteration time.
    std::function<void(Trainer&)> before_step;
  };
  // Steps until config.iterations or until *stop. Writes a checkpoint every
  // config.bookkeeping.checkpoint_interval iterations, at the end and when stopped; appends to run_dir/log.csv
  // every config.bookkeeping.log_interval.
  RunResult run(const RunOptions& options);

  // Checkpoint file for the current state, written to a temporary file then renamed; the renderer's own
  // parameters (if any) go beside it (renderer_state_path). The hooks' state is recorded in state().hooks
  // first.
  void save_checkpoint(const std::filesystem::path& path);
  // Restores the renderer's own parameters saved beside a checkpoint (no-op when there is no such file and
  // the renderer owns nothing; an error when the renderer needs one and it is missing).
  static void load_renderer_state(const std::filesystem::path& checkpoint, DifferentiableRenderer& renderer);

  // The normal-prior weight at an iteration (the 0.5 -> 0.001 decay of S1.5, scaled to the run's length).
  double normal_prior_weight(int iteration) const;
  bool intrinsic() const { return config_.mode == TrainMode::Intrinsic; }

  // Continues the run under another configuration and renderer (--mode auto switching a radiance run to
  // intrinsic after the warm-up); `update_views` may set the views' glossy masks and normal priors. The
  // renderer must live on the model's device. Parameter groups the previous renderer did not train (the
  // material extras of a radiance run) restart with zero Adam moments and step counts.
  void switch_mode(TrainConfig config, std::shared_ptr<DifferentiableRenderer> renderer,
                   const std::function<void(std::vector<TrainView>&)>& update_views = {});
  const std::shared_ptr<DifferentiableRenderer>& renderer() const { return renderer_; }

  const TrainConfig& config() const { return config_; }
  TrainerState& state() { return state_; }
  const TrainerState& state() const { return state_; }
  GaussianModel& model() { return state_.model; }
  Device device() const { return device_; }
  float extent() const { return extent_; }
  const std::vector<TrainView>& views() const { return views_; }
  TrainProgress progress(double it_per_s) const;
  // TrainConfig::densify_until() of the run's configuration.
  int densify_until() const;

 private:
  // A step's image gradients dL/d(rendered image) on the host (empty = zero), and their copies on the
  // device once uploaded (alive until the step ends).
  struct LossGradients {
    std::vector<float> color, depth, alpha, median, normal, extras, detached, base;
    std::vector<DeviceGrad> on_device;
    ImageGradients upload(Device device);
  };
  // The next view of a random permutation of all views (a new one each epoch).
  const TrainView& next_view(StepStats& out);
  // Every loss of the step on `view` (photo, depth-normal, alpha, intrinsic, inpainting) with its image
  // gradients; the terms go to `out`.
  LossGradients losses(const TrainView& view, const RenderedImages& fwd, int it, StepStats& out) const;
  // Zeroes the gradients, runs the renderer's backward pass of `g` and returns where it accumulated
  // (the per-view densification statistic in view_grad_norm_).
  GaussianGradView backward(const GaussianView& gv, LossGradients& g, bool with_extras);
  // Adam on the active groups (learning rates scaled down after skipped steps), then the renderer's own
  // parameters; a parameter turned non-finite stops the run.
  void optimizer_step(int it);
  // Density control and the 3D filter of iteration `it`; what densification did (after == 0: none).
  DensifyCounts densify(int it);
  // After Gaussians were removed or added: resets what is sized by their count (the densification
  // statistics, the 3D filter).
  void model_changed();
  // The hooks `config_` switches on (make_train_hooks), each given its state from state_.hooks; and back.
  void make_hooks();
  void store_hook_states();
  // The first parameter group whose gradient / value holds a NaN or Inf, as "group 'x' (Gaussian i)"; empty
  // when all are finite.
  std::string non_finite_gradient() const;
  std::string non_finite_parameter() const;
  // Handles a non-finite loss or gradient at iteration `it` (see NanSettings): throws, or marks
  // `out` skipped, lowers the learning rates and completes the iteration without an update.
  void skip_step(int it, const std::string& problem, StepStats& out);
  int consecutive_skips_ = 0;
  std::vector<ParamGroup> active_groups() const;
  // Intrinsic-mode losses on the host images; adds their gradients. Returns the weighted sum.
  double intrinsic_losses(const TrainView& view, const RenderedImages& fwd, int it, std::vector<float>& g_normal,
                          std::vector<float>& g_extras, std::vector<float>& g_detached, StepStats& out) const;
  // Stage-2 inpainting losses of views with targets; adds their gradients. Returns the weighted sum.
  double inpaint_losses(const TrainView& view, const RenderedImages& fwd, std::vector<float>& g_color,
                        std::vector<float>& g_base, std::vector<float>& g_normal, std::vector<float>& g_extras,
                        StepStats& out) const;
  std::vector<Camera> cameras() const;

  TrainConfig config_;
  std::vector<TrainView> views_;
  float extent_;
  std::shared_ptr<DifferentiableRenderer> renderer_;
  Device device_;
  TrainerState state_;
  TrainHooks hooks_;  // make_train_hooks(config_, *renderer_), called in this order
  Buffer<float> view_grad_norm_;  // per-view |dL/dmean2d| scratch for the densification statistic
};

}  // namespace goris
