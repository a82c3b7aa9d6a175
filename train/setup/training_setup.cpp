#include "train/setup/training_setup.h"

#include <algorithm>

#include "core/compute/device.h"
#include "core/io/image.h"
#include "core/io/ply.h"
#include "train/run/run_data.h"
#include "train/run/run_folder.h"
#include "train/run/normal_prior.h"
#include "train/run/train_setup.h"
#include "core/util/error.h"
#include "train/intrinsic/intrinsic_renderer.h"
#include "train/setup/auto_mode.h"
#include "train/setup/run_renderer.h"

namespace goris {

namespace fs = std::filesystem;

std::optional<ResumePoint> read_latest_checkpoint(const fs::path& run_dir) {
  const auto ck = latest_checkpoint(run_dir);
  if (!ck) return std::nullopt;
  return ResumePoint{*ck, read_checkpoint(*ck, Device::CPU)};
}

void select_training_data(const TrainConfig& config, Dataset& dataset) {
  std::vector<View>& train = dataset.train;
  if (config.input.max_train_views > 0 && std::size_t(config.input.max_train_views) < train.size()) {
    std::vector<View> kept;  // evenly spread: view round(i * n / k)
    const std::size_t n = train.size(), k = std::size_t(config.input.max_train_views);
    for (std::size_t i = 0; i < k; ++i) kept.push_back(train[(i * n) / k]);
    train = std::move(kept);
  }
  for (View& v : train) {
    // glossy_mask_dir replaces the data set's masks (prepare_training loads them).
    if (!config.input.use_glossy_masks || !config.input.glossy_mask_dir.empty()) v.glossy_mask.reset();
    if (!config.input.use_object_masks) v.object_mask.reset();
  }
}

PreparedTraining prepare_training(const fs::path& run_dir, TrainConfig config, std::optional<ResumePoint> resumed,
                                  const std::function<void(std::size_t, std::size_t)>& on_view) {
  config.validate("training options");
  const Device device = resolve_device(config.device);
  PreparedTraining p;
  const DatasetOptions dopt = dataset_options(config);
  p.dataset = load_dataset(config.input.data, dopt);
  if (p.dataset.train.empty()) throw Error(config.input.data, "the data set has no training views");
  // The record that lets a moved data set be checked (train/run/run_data.h); a resumed run's must match.
  const std::string fingerprint = training_views_fingerprint(p.dataset);
  if (!config.input.data_views.empty() && fingerprint != config.input.data_views)
    throw Error(config.input.data, "holds other training views than the run was trained on: " + fingerprint +
                                 " (names and image sizes), the run " + config.input.data_views);
  config.input.data_views = fingerprint;
  select_training_data(config, p.dataset);
  p.extent = scene_extent(p.dataset);
  resolve_environment_sphere(p.dataset, config);
  std::vector<TrainView> views = load_train_views(p.dataset.train, dopt, on_view);
  if (!config.input.glossy_mask_dir.empty()) load_glossy_mask_folder(config.input.glossy_mask_dir, views);
  // "auto": from the glossy masks, or radiance until the detection after the warm-up (auto_mode.h).
  p.auto_mode_reason = resolve_auto_mode(config, views);
  config.validate("training options");
  for (const TrainView& v : views) {
    p.glossy_views += !v.glossy_mask.empty();
    p.mask_views += !v.object_mask.empty();
  }
  if (config.mode == TrainMode::Intrinsic && !config.intrinsic.normals.empty())
    load_normal_priors(config.intrinsic.normals, views);

  TrainerState state;
  if (resumed) {
    state = std::move(resumed->checkpoint.state);
    if (device != Device::CPU) state.model = state.model.copy_to(device);
    for (Buffer<float>* b : {&state.stats.grad_accum, &state.stats.denom, &state.stats.max_radii})
      *b = b->copy_to(device);
  } else {
    state = Trainer::initial_state(config, initial_model(p.dataset, config, device, &p.initial_model));
  }
  fs::create_directories(run_dir / "checkpoints");
  p.renderer = make_renderer(config, p.extent, device);
  if (resumed) Trainer::load_renderer_state(resumed->file, *p.renderer);
  p.trainer = std::make_unique<Trainer>(config, std::move(views), p.extent, p.renderer, std::move(state));
  p.config = std::move(config);
  return p;
}

void write_trained_run(const fs::path& run_dir, const Trainer& trainer, DifferentiableRenderer& renderer) {
  write_ply(run_ply_path(run_dir), trainer.state().model.to_ply(/*bake_3d_filter=*/true));
  if (IntrinsicRenderer* ir = as_intrinsic(&renderer)) {
    // The checkpoints keep the map with the net for resuming; this is for people.
    const int ew = 4 * ir->environment().resolution();
    const std::vector<float> eq = ir->environment().equirect_image(ew);
    Image img(ew, ew / 2, 3);
    img.pixels.upload(eq.data(), eq.size());
    save_png(run_dir / "environment.png", img);
  }
}

}  // namespace goris
