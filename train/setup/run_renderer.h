#pragma once
// The differentiable renderer a run's configuration asks for: the rasterizer (radiance mode) or the
// intrinsic renderer (train/intrinsic/intrinsic_renderer.h). Shared by `goris train | render | eval`, the
// removal stage and the editor, so every consumer shades a run the same way.
#include <filesystem>
#include <memory>

#include "train/config/train_config.h"
#include "train/loop/differentiable_renderer.h"

namespace goris {

class IntrinsicRenderer;

// A fresh renderer for training (intrinsic: environment map and net at their initial values).
std::shared_ptr<DifferentiableRenderer> make_renderer(const TrainConfig& config, float extent, Device device);

// The renderer of a trained run, ready to render: in intrinsic mode with the environment map and roughness
// net of the run's latest checkpoint (an error naming the file when they are missing) and shading on.
std::shared_ptr<DifferentiableRenderer> load_run_renderer(const std::filesystem::path& run_dir,
                                                          const TrainConfig& config, float extent, Device device);

// The intrinsic renderer behind a renderer made above, or null for a radiance run.
IntrinsicRenderer* as_intrinsic(DifferentiableRenderer* renderer);

}  // namespace goris
