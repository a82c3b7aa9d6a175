#pragma once
// A run folder and a training configuration turned into a Trainer ready to run: shared by `goris train`
// (app/goris/cmd_train.cpp) and the editor's training session (ui/document/trainer_session.h), so both train the
// same way. It loads the data set, resolves mode "auto" (train/setup/auto_mode.h: the callers pass
// apply_auto_mode as Trainer::RunOptions::before_step for the decision after the warm-up), loads the training images (and normal priors in
// intrinsic mode), builds the initial model or takes a checkpoint's state, and makes the differentiable
// renderer the configuration asks for (train/setup/run_renderer.h) with its own parameters restored when
// resuming. What differs between the callers (new or resumed run, how the iteration target is given, what
// is printed) stays with them.
#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "core/io/dataset.h"
#include "train/config/train_config.h"
#include "train/loop/checkpoint.h"
#include "train/loop/differentiable_renderer.h"
#include "train/loop/trainer.h"

namespace goris {

// A checkpoint to continue from, with the file it came from (its renderer state lies beside it).
struct ResumePoint {
  std::filesystem::path file;
  Checkpoint checkpoint;
};
// The latest checkpoint of a run folder, read onto the CPU; nullopt when the folder has none.
std::optional<ResumePoint> read_latest_checkpoint(const std::filesystem::path& run_dir);

struct PreparedTraining {
  TrainConfig config;  // as trained: mode "auto" resolved
  Dataset dataset;
  float extent = 1.0f;
  std::shared_ptr<DifferentiableRenderer> renderer;  // as prepared (--mode auto may switch: trainer->renderer())
  std::unique_ptr<Trainer> trainer;
  // For the user: how "auto" decided (empty when the mode was given), the intrinsic inputs found, and how
  // the initial model was made (empty when resumed).
  std::string auto_mode_reason;
  std::size_t glossy_views = 0, mask_views = 0;
  std::string initial_model;
};

// Applies config.input.use_glossy_masks / use_object_masks / max_train_views to the loaded data set's training
// views (prepare_training calls it; the views' mask paths are dropped, the subset is spread evenly). With
// config.input.glossy_mask_dir the data set's glossy masks are dropped too (prepare_training reads that folder).
void select_training_data(const TrainConfig& config, Dataset& dataset);

// `config` names the data set and the iteration target (it is validated here); `resumed` continues from a
// checkpoint (its state moves into the trainer, placed on the configured device) instead of initialising.
// Creates RUN/checkpoints. `on_view` is told (index, count) as each training image loads. Throws
// goris::Error naming the file and the problem (no training views, unreadable images or priors, ...).
PreparedTraining prepare_training(const std::filesystem::path& run_dir, TrainConfig config,
                                  std::optional<ResumePoint> resumed,
                                  const std::function<void(std::size_t, std::size_t)>& on_view = {});

// What a finished stage-1 run leaves beside its checkpoints: RUN/point_cloud.ply (3D filter baked in, for
// standard viewers) and, for intrinsic runs, RUN/environment.png (the environment map as a picture).
void write_trained_run(const std::filesystem::path& run_dir, const Trainer& trainer, DifferentiableRenderer& renderer);

}  // namespace goris
