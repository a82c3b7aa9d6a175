#pragma once
// Renders a model snapshot for the viewports on the calling thread (the render worker's): the rasterized
// G-buffer; for intrinsic snapshots the intrinsic renderer's maps (shaded colour, G, L_ind, V, L_dir, R_s),
// with one renderer kept per run and its environment map and net reloaded when a snapshot brings new
// ones; and, when something is selected, the selection's coverage as one more rasterized channel. Hidden Gaussians are drawn fully transparent. On CUDA
// the frame's images stay on the GPU (display_frame.h).
#include <memory>
#include <string>

#include "core/compute/buffer.h"
#include "core/scene/selection_points.h"
#include "ui/display/display_frame.h"
#include "ui/display/model_snapshot.h"

namespace goris {
class IntrinsicRenderer;
}

namespace goris::ui {

class DisplayRenderer {
 public:
  DisplayRenderer();
  ~DisplayRenderer();
  DisplayRenderer(const DisplayRenderer&) = delete;
  DisplayRenderer& operator=(const DisplayRenderer&) = delete;

  // `selection`, `hidden` (Gaussians not drawn): null, or a mask with one entry per Gaussian of `model`
  // (else goris::Error).
  DisplayFrame render(const ModelSnapshot& model, const Camera& camera,
                      const std::shared_ptr<const SelectionMask>& selection,
                      const std::shared_ptr<const SelectionMask>& hidden = nullptr);

 private:
  IntrinsicRenderer& intrinsic_for(const ModelSnapshot& model);

  std::shared_ptr<const ShadingSource> source_;
  Device device_ = Device::CPU;
  std::shared_ptr<const std::string> loaded_state_;
  std::unique_ptr<IntrinsicRenderer> renderer_;
  std::shared_ptr<const SelectionMask> selection_;  // what selection_values_ holds
  Buffer<float> selection_values_;
  std::shared_ptr<const SelectionMask> hidden_;  // what hidden_logits_ leaves out
  const ModelSnapshot* hidden_model_ = nullptr;
  Buffer<float> hidden_logits_;
};

}  // namespace goris::ui
