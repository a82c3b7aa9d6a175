#pragma once
// A read-only copy of a Gaussian model's values for display: what renderers read, nothing a trainer needs
// (no gradients or Adam moments), with the extra channels already activated. The trainer thread makes one
// under its own schedule and hands it to the GUI through a shared_ptr, so the viewports never touch the
// model while it trains.
//
// An intrinsic run's snapshot also carries how it is shaded: the run's configuration and scene extent
// (shared by all snapshots of a run) and the renderer's own parameters (environment map, roughness net) at
// the snapshot's iteration, so the display shades with the environment being trained.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/compute/buffer.h"
#include "core/scene/gaussians.h"
#include "render/raster/raster_types.h"
#include "train/config/train_config.h"

namespace goris::ui {

// What the intrinsic renderer of a run is built from (IntrinsicRenderer(config, extent, device)).
struct ShadingSource {
  TrainConfig config;
  float extent = 1.0f;
};

class ModelSnapshot {
 public:
  // Copies `model`'s values on its own device (the extras are activated on the host and sent back).
  // `iteration` tells which training step the copy shows (0 for a model loaded from disk); `settings` are
  // those the model is rendered with (its run's background and anti-aliasing filters). `shading` and
  // `renderer_state` (DifferentiableRenderer::save_own_state bytes) are given for intrinsic runs only.
  ModelSnapshot(const GaussianModel& model, int iteration, const RasterSettings& settings,
                std::shared_ptr<const ShadingSource> shading = nullptr,
                std::shared_ptr<const std::string> renderer_state = nullptr);

  // What the rasterizer reads, extras included (kCount channels); pointers live on device().
  GaussianView view() const;
  Device device() const { return device_; }
  size_t count() const { return count_; }
  int iteration() const { return iteration_; }
  const RasterSettings& settings() const { return settings_; }

  // Intrinsic runs: shaded by the intrinsic renderer built from shading() with renderer_state() loaded.
  bool intrinsic() const { return shading_ && renderer_state_; }
  const std::shared_ptr<const ShadingSource>& shading() const { return shading_; }
  const std::shared_ptr<const std::string>& renderer_state() const { return renderer_state_; }

  // The opacity logits with those of the `hidden` Gaussians (1 = hidden) set so low that nothing of them
  // is drawn, on device(): for view() with hidden Gaussians left out.
  Buffer<float> opacity_logits_hiding(const std::vector<std::uint8_t>& hidden) const;

  // A GaussianModel with these values (extras as logits; gradients and moments zero) on device(), for the
  // library functions that take a model (selection, picking, fingerprints).
  GaussianModel to_model() const;

 private:
  Device device_;
  size_t count_ = 0;
  int iteration_ = 0;
  int sh_degree_ = 0, max_sh_degree_ = 3;
  RasterSettings settings_;
  Buffer<float> positions_, log_scales_, rotations_, opacity_logits_, sh_, extras_, extra_logits_, filter3d_var_;
  std::shared_ptr<const ShadingSource> shading_;
  std::shared_ptr<const std::string> renderer_state_;
};

}  // namespace goris::ui
