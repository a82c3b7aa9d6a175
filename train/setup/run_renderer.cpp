#include "train/setup/run_renderer.h"

#include "core/io/dataset.h"
#include "train/loop/checkpoint.h"
#include "train/loop/emit_weights.h"
#include "train/run/train_setup.h"
#include "train/loop/trainer.h"
#include "core/util/error.h"
#include "train/intrinsic/intrinsic_renderer.h"
#include "train/setup/auto_mode.h"
#include "train/radiance/raster_renderer.h"
#include "train/setup/training_setup.h"

namespace goris {

namespace {

// The training views' glossy masks as the run trained with them (the data set's, a subset, or
// config.input.glossy_mask_dir's detected ones); the photos are not read.
std::vector<GlossyMaskView> training_glossy_masks(const TrainConfig& config) {
  Dataset dataset = load_dataset(config.input.data, dataset_options(config));
  select_training_data(config, dataset);
  std::vector<std::vector<float>> masks = run_glossy_masks(config, dataset.train);
  std::vector<GlossyMaskView> out;
  for (std::size_t k = 0; k < masks.size(); ++k)
    if (!masks[k].empty()) out.push_back({dataset.train[k].camera, std::move(masks[k])});
  return out;
}

}  // namespace

std::shared_ptr<DifferentiableRenderer> make_renderer(const TrainConfig& config, float extent, Device device) {
  if (config.mode == TrainMode::Intrinsic) return std::make_shared<IntrinsicRenderer>(config, extent, device);
  return std::make_shared<RasterRenderer>(RasterRenderer::settings_for(config), device);
}

std::shared_ptr<DifferentiableRenderer> load_run_renderer(const std::filesystem::path& run_dir,
                                                          const TrainConfig& config, float extent, Device device) {
  auto r = make_renderer(config, extent, device);
  if (IntrinsicRenderer* ir = as_intrinsic(r.get())) {
    const auto ck = latest_checkpoint(run_dir);
    if (!ck)
      throw Error(run_dir.string(), "an intrinsic run needs a checkpoint (its environment map and roughness net "
                                    "live beside it) and has none in checkpoints/");
    Trainer::load_renderer_state(*ck, *ir);
    ir->set_shading(true);
    // Emission from the glossy masks (not learned): the trainer's weights are not saved, so recompute them.
    if (config.intrinsic.emit != EmitSource::Region)
      ir->set_emit_masks(training_glossy_masks(config), config.intrinsic.emit == EmitSource::Max);
  }
  return r;
}

IntrinsicRenderer* as_intrinsic(DifferentiableRenderer* renderer) { return dynamic_cast<IntrinsicRenderer*>(renderer); }

}  // namespace goris
