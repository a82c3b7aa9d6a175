#include "ui/display/display_renderer.h"

#include "core/util/error.h"
#include "train/intrinsic/intrinsic_renderer.h"
#include "render/raster/rasterizer.h"

namespace goris::ui {

DisplayRenderer::DisplayRenderer() = default;
DisplayRenderer::~DisplayRenderer() = default;

IntrinsicRenderer& DisplayRenderer::intrinsic_for(const ModelSnapshot& m) {
  if (!renderer_ || m.shading() != source_ || m.device() != device_) {
    loaded_state_.reset();
    renderer_ = std::make_unique<IntrinsicRenderer>(m.shading()->config, m.shading()->extent, m.device());
    renderer_->set_shading(true);
    source_ = m.shading();
    device_ = m.device();
  }
  if (m.renderer_state() != loaded_state_) {
    renderer_->load_own_state(*m.renderer_state(), "the trained environment map and roughness net");
    loaded_state_ = m.renderer_state();
  }
  return *renderer_;
}

DisplayFrame DisplayRenderer::render(const ModelSnapshot& m, const Camera& camera,
                                     const std::shared_ptr<const SelectionMask>& selection,
                                     const std::shared_ptr<const SelectionMask>& hidden) {
  GaussianView shown = m.view();
  if (hidden) {
    if (hidden->size() != m.count())
      throw Error("display", "the hidden mask has " + std::to_string(hidden->size()) + " entries for " +
                                 std::to_string(m.count()) + " Gaussians");
    if (hidden != hidden_ || &m != hidden_model_ || hidden_logits_.device() != m.device()) {
      hidden_logits_ = m.opacity_logits_hiding(*hidden);
      hidden_ = hidden;
      hidden_model_ = &m;
    }
    shown.opacity_logits = hidden_logits_.data();
  }
  DisplayFrame frame;
  if (m.intrinsic()) {
    IntrinsicRenderer& ir = intrinsic_for(m);
    const IntrinsicMaps maps = ir.render_maps(shown, camera);
    frame = make_display_frame(ir.last().gbuffer, camera);
    add_intrinsic_maps(frame, maps);
  } else {
    const RasterOutput out = rasterize(shown, camera, m.settings(), m.device());
    frame = make_display_frame(out.gbuffer, camera);
  }
  if (selection) {
    if (selection->size() != m.count())
      throw Error("display", "the selection has " + std::to_string(selection->size()) + " entries for " +
                                 std::to_string(m.count()) + " Gaussians");
    if (selection != selection_ || selection_values_.device() != m.device()) {
      std::vector<float> v(selection->size());
      for (size_t i = 0; i < v.size(); ++i) v[i] = (*selection)[i] ? 1.0f : 0.0f;
      selection_values_ = Buffer<float>(v, m.device());
      selection_ = selection;
    }
    // The selection as the only extra channel: the rasterizer blends it into its per-pixel coverage.
    GaussianView v = shown;
    v.extras = selection_values_.data();
    v.n_extras = 1;
    const RasterOutput sel = rasterize(v, camera, m.settings(), m.device());
    add_selection_coverage(frame, sel.gbuffer.extras);  // stays on the GPU for CUDA frames
  }
  return frame;
}

}  // namespace goris::ui
