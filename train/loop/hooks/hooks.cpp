#include "train/loop/hooks/hooks.h"

#include <cstdint>
#include <cstring>

#include "core/util/error.h"
#include "train/config/train_config.h"
#include "train/loop/emit_weights.h"
#include "train/loop/mirror_world.h"
#include "train/loop/trainer.h"
#include "train/losses/depth_distortion.h"

namespace goris {

void HookStep::note(const std::string& text) { out.densify_note += (out.densify_note.empty() ? "" : "; ") + text; }

TrainHooks make_train_hooks(const TrainConfig& config, const DifferentiableRenderer& renderer) {
  TrainHooks hooks;
  const bool intrinsic = config.mode == TrainMode::Intrinsic;
  if (renderer.wants_extras() && config.intrinsic.emit != EmitSource::Region) hooks.push_back(std::make_unique<EmitWeightsHook>());
  if (config.loss.depth_distortion_weight > 0) hooks.push_back(std::make_unique<DepthDistortionHook>());
  if (intrinsic && config.intrinsic.prune_mirror_world > 0) hooks.push_back(std::make_unique<MirrorWorldHook>());
  if (intrinsic && config.intrinsic.glossy_plane) hooks.push_back(std::make_unique<GlossyPlaneHook>());
  return hooks;
}

void EmitWeightsHook::before_forward(HookStep& s) {
  const bool refresh = weights_.size() != s.model.count() || s.iteration % kRefreshInterval == 0;
  if (refresh) weights_ = glossy_mask_emit_weights(s.model, s.views);
  if (refresh || !given_) s.renderer.set_emit_weights(weights_, s.config.intrinsic.emit == EmitSource::Max);
  given_ = true;
}

std::string EmitWeightsHook::serialize() const {
  if (weights_.empty()) return {};
  const std::uint64_t n = weights_.size();
  std::string bytes(reinterpret_cast<const char*>(&n), sizeof n);
  bytes.append(reinterpret_cast<const char*>(weights_.data()), weights_.size() * sizeof(float));
  return bytes;
}

void EmitWeightsHook::deserialize(const std::string& bytes, const std::string& source) {
  weights_.clear();
  given_ = false;
  if (bytes.empty()) return;
  std::uint64_t n = 0;
  if (bytes.size() >= sizeof n) std::memcpy(&n, bytes.data(), sizeof n);
  if (bytes.size() < sizeof n || (bytes.size() - sizeof n) / sizeof(float) != n || (bytes.size() - sizeof n) % sizeof(float))
    throw Error(source, "checkpoint emit weights are invalid");
  weights_.resize(n);
  if (n) std::memcpy(weights_.data(), bytes.data() + sizeof n, n * sizeof(float));
}

const float* DepthDistortionHook::pixel_weights(const HookStep& s) {
  const float glossy = s.config.loss.depth_distortion_glossy;
  if (glossy == 1.0f || s.view.glossy_mask.empty()) return nullptr;
  pixel_weights_.resize(s.view.glossy_mask.size());
  for (std::size_t p = 0; p < pixel_weights_.size(); ++p)
    pixel_weights_[p] = 1.0f - (1.0f - glossy) * s.view.glossy_mask[p];
  return pixel_weights_.data();
}

void DepthDistortionHook::after_backward(HookStep& s) {
  if (!s.config.depth_distortion_at(s.iteration)) return;
  const float weight = s.config.loss.depth_distortion_weight;
  s.out.distortion = s.renderer.depth_distortion(*s.gaussians, s.view.camera, DistortionDepthRange::for_extent(s.extent),
                                                 weight, pixel_weights(s), *s.grads);
  s.out.loss += weight * s.out.distortion;
}

void MirrorWorldHook::after_densify(HookStep& s) {
  const int it = s.iteration;
  if (!s.config.prunes_mirror_world_after(it, s.out.densify.after > 0)) return;
  const size_t before = s.model.count();
  const size_t removed = prune_mirror_world(s.model, s.views, s.renderer, s.config.intrinsic.prune_mirror_world);
  s.model_pruned();
  s.note("mirror world: pruned " + std::to_string(removed) + " of " + std::to_string(before) +
         (it == s.config.shading_from() ? " Gaussians before shading starts" : " Gaussians after densifying"));
}

void GlossyPlaneHook::after_densify(HookStep& s) {
  if (s.iteration < s.config.shading_from()) return;
  if (!constraint_.started()) {
    const std::string note = constraint_.start(s.model, s.views);
    if (constraint_.pruned() > 0) s.model_pruned();
    s.note(note);
    return;
  }
  if (constraint_.apply(s.model, s.views, s.iteration, s.config.intrinsic.glossy_plane_prune_sinkers).pruned > 0)
    s.model_pruned();
  if (s.config.intrinsic.glossy_plane_align) constraint_.align_normals(s.model);
}

}  // namespace goris
