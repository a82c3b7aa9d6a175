#include "render/train/run_renderer.h"

#include "core/train/checkpoint.h"
#include "core/train/trainer.h"
#include "core/util/error.h"
#include "render/intrinsic/intrinsic_renderer.h"
#include "render/train/raster_renderer.h"

namespace goris {

std::shared_ptr<DifferentiableRenderer> make_renderer(const TrainConfig& config, float extent, Device device) {
  if (config.mode == "intrinsic") return std::make_shared<IntrinsicRenderer>(config, extent, device);
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
  }
  return r;
}

IntrinsicRenderer* as_intrinsic(DifferentiableRenderer* renderer) { return dynamic_cast<IntrinsicRenderer*>(renderer); }

}  // namespace goris
