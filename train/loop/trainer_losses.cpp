// The trainer's loss terms: the photo loss, depth-normal consistency and the alpha loss, stage 1's material
// and normal losses on the rendered maps (intrinsic mode) and stage 2's inpainting targets. Split from
// trainer.cpp, which runs the step around them.
#include <cmath>
#include <utility>

#include "core/compute/host_device_image.h"
#include "core/util/error.h"
#include "train/loop/trainer.h"
#include "train/losses/depth_normal_loss.h"
#include "train/losses/image_losses.h"
#include "train/losses/intrinsic_losses.h"

namespace goris {

Trainer::LossGradients Trainer::losses(const TrainView& view, const RenderedImages& fwd, int it, StepStats& out) const {
  const Camera& cam = view.camera;
  const int w = cam.width, h = cam.height;
  const size_t hw = size_t(w) * size_t(h);
  LossGradients g;
  const HostView color(fwd.color, 3 * hw, device_);
  g.color.assign(3 * hw, 0.0f);
  const float lambda_ssim = config_.loss.lambda_ssim;
  const ColorLossParts cl = view.loss_weight.empty()
                                ? color_loss<float>(color.data(), view.image.data(), 3, w, h, g.color.data(), lambda_ssim)
                                : weighted_color_loss(color.data(), view.image.data(), view.loss_weight.data(), w, h,
                                                      g.color.data(), lambda_ssim, 1.0f);
  out.l1 = cl.l1;
  out.ssim = cl.ssim;
  out.loss = cl.total;
  out.psnr = psnr_from_mse(mse<float>(color.data(), view.image.data(), 3 * hw));

  if (config_.loss.depth_normal_weight > 0 && it > config_.loss.depth_normal_from) {
    const HostView depth(fwd.depth, hw, device_), alpha(fwd.alpha, hw, device_),
        median(fwd.median_depth, hw, device_), normal(fwd.normal, 3 * hw, device_);
    g.depth.assign(hw, 0.0f);
    g.alpha.assign(hw, 0.0f);
    g.median.assign(hw, 0.0f);
    g.normal.assign(3 * hw, 0.0f);
    out.depth_normal = rendered_depth_normal_loss<float>(
        depth.data(), alpha.data(), median.data(), normal.data(), w, h, cam.fx, cam.fy, cam.cx, cam.cy,
        config_.loss.depth_normal_median_ratio, g.depth.data(), g.alpha.data(), g.median.data(), g.normal.data(),
        config_.loss.depth_normal_weight);
    out.loss += config_.loss.depth_normal_weight * out.depth_normal;
  }
  if (config_.loss.alpha_weight > 0 && view.alpha.size() == hw) {
    const HostView alpha(fwd.alpha, hw, device_);
    if (g.alpha.empty()) g.alpha.assign(hw, 0.0f);
    // Stage 2 leaves the pixels under the target and its reflections to the inpainting (loss_weight 0).
    out.alpha = l1_loss(alpha.data(), view.alpha.data(), hw, g.alpha.data(), config_.loss.alpha_weight,
                        view.loss_weight.empty() ? nullptr : view.loss_weight.data());
    out.loss += config_.loss.alpha_weight * out.alpha;
  }
  if (intrinsic()) out.loss += intrinsic_losses(view, fwd, it, g.normal, g.extras, g.detached, out);
  if (view.inpaint) out.loss += inpaint_losses(view, fwd, g.color, g.base, g.normal, g.detached, out);
  if (!g.base.empty() && fwd.base_color == fwd.color) {  // D is the colour: one gradient
    for (size_t i = 0; i < g.base.size(); ++i) g.color[i] += g.base[i];
    g.base.clear();
  }
  return g;
}

double Trainer::normal_prior_weight(int it) const {
  const IntrinsicSettings& in = config_.intrinsic;
  const int from = config_.shading_from(), until = config_.shading_phase_iteration(in.normal_prior_until);
  if (in.normal_prior <= 0) return 0.0;
  if (it <= from || until <= from) return it <= from ? in.normal_prior : in.normal_prior_final;
  if (it >= until) return in.normal_prior_final;
  const double t = double(it - from) / double(until - from);
  return std::exp((1 - t) * std::log(double(in.normal_prior)) + t * std::log(std::max(double(in.normal_prior_final), 1e-12)));
}

double Trainer::intrinsic_losses(const TrainView& view, const RenderedImages& fwd, int it, std::vector<float>& g_normal,
                                 std::vector<float>& g_extras, std::vector<float>& g_detached, StepStats& out) const {
  if (!fwd.extras || fwd.n_extras != extra::kCount)
    throw Error("training: intrinsic mode needs a renderer that returns the material channels");
  const IntrinsicSettings& in = config_.intrinsic;
  const int w = fwd.width, h = fwd.height;
  const size_t hw = size_t(w) * size_t(h);
  const HostView extras(fwd.extras, size_t(extra::kCount) * hw, device_), normal(fwd.normal, 3 * hw, device_);
  if (g_normal.empty()) g_normal.assign(3 * hw, 0.0f);
  auto plane = [&](int c) { return extras.data() + size_t(c) * hw; };
  double total = 0;
  const bool glossy = !view.glossy_mask.empty();
  // Mask-driven losses only count where the photo losses do (stage 2: not under the target or its
  // reflections): glossy' = glossy w.
  std::vector<float> gl_w;
  const float* gmask = glossy ? view.glossy_mask.data() : nullptr;
  if (glossy && !view.loss_weight.empty()) {
    gl_w.resize(hw);
    for (size_t p = 0; p < hw; ++p) gl_w[p] = view.glossy_mask[p] * view.loss_weight[p];
    gmask = gl_w.data();
  }
  // Losses on material maps train the materials alone (detached from the geometry that blends them: a
  // material loss must not be lowered by making the surface transparent); normal losses train geometry.
  if (g_detached.empty()) g_detached.assign(size_t(extra::kCount) * hw, 0.0f);
  auto dplane = [&](int c) { return g_detached.data() + size_t(c) * hw; };
  const bool materials = in.material_losses_in_warmup || it > config_.shading_from();
  if (glossy && materials && in.region > 0) {
    out.region = region_loss<float>(plane(extra::kRegion), gmask, w, h, dplane(extra::kRegion), in.region);
    total += in.region * out.region;
  }
  if (glossy && materials && in.smoothness > 0) {
    const float s = in.smoothness;
    out.smoothness =
        edge_aware_smoothness<float>(plane(extra::kFresnel), 3, view.image.data(), gmask, w, h,
                                     dplane(extra::kFresnel), s) +
        edge_aware_smoothness<float>(plane(extra::kRoughness), 1, view.image.data(), gmask, w, h,
                                     dplane(extra::kRoughness), s) +
        edge_aware_smoothness<float>(normal.data(), 3, view.image.data(), gmask, w, h,
                                     g_normal.data(), s, /*normalize_x=*/true);
    total += s * out.smoothness;
  }
  const double wn = normal_prior_weight(it);
  if (glossy && !view.normal_prior.empty() && wn > 0) {
    out.normal_prior = normal_prior_loss<float>(normal.data(), view.normal_prior.data(), gmask, w, h,
                                                g_normal.data(), float(wn));
    total += wn * out.normal_prior;
  }
  if (!view.object_mask.empty() && in.label > 0) {
    // The label learns from the masks without moving geometry (see ImageGradients::extras_detached).
    out.label = label_bce_loss<float>(plane(extra::kLabel), view.object_mask.data(), w, h, dplane(extra::kLabel), in.label);
    total += in.label * out.label;
  }
  return total;
}

double Trainer::inpaint_losses(const TrainView& view, const RenderedImages& fwd, std::vector<float>& g_color,
                               std::vector<float>& g_base, std::vector<float>& g_normal, std::vector<float>& g_extras,
                               StepStats& out) const {
  // F0 and roughness targets train the materials alone, like the stage-1 material losses (g_extras here is
  // the detached gradient set).
  const InpaintTargets& t = *view.inpaint;
  const int w = fwd.width, h = fwd.height;
  const size_t hw = size_t(w) * size_t(h);
  auto sized = [&](const std::vector<float>& v, size_t n, const char* what) {
    if (!v.empty() && v.size() != n)
      throw Error(view.name, std::string("inpainting target '") + what + "' has the wrong size");
    return !v.empty();
  };
  double total = 0;
  const float wa = config_.inpaint.appearance_weight, wm = config_.inpaint.material_weight;
  if (wa > 0 && sized(t.appearance_weight, hw, "appearance weight") && sized(t.color, 3 * hw, "colour")) {
    const HostView color(fwd.color, 3 * hw, device_);
    out.appearance = weighted_color_loss(color.data(), t.color.data(), t.appearance_weight.data(), w, h, g_color.data(),
                                         config_.loss.lambda_ssim, wa).total;
    total += wa * out.appearance;
  }
  if (wm > 0 && sized(t.material_weight, hw, "material weight")) {
    const float* mw = t.material_weight.data();
    const float norm = 1.0f / float(hw);
    auto l1 = [&](const float* x, const float* target, int channels, float* grad) {
      double l = 0;
      for (int c = 0; c < channels; ++c)
        for (size_t p = 0; p < hw; ++p) {
          if (mw[p] == 0) continue;
          const float d = x[c * hw + p] - target[c * hw + p];
          l += mw[p] * std::abs(d);
          grad[c * hw + p] += wm * norm * mw[p] * (d > 0 ? 1.0f : (d < 0 ? -1.0f : 0.0f));
        }
      return l * norm;
    };
    double m = 0;
    if (sized(t.base_color, 3 * hw, "base colour")) {
      const HostView base(fwd.base_color, 3 * hw, device_);
      if (g_base.empty()) g_base.assign(3 * hw, 0.0f);
      m += l1(base.data(), t.base_color.data(), 3, g_base.data());
    }
    if (fwd.extras && fwd.n_extras == extra::kCount) {
      const HostView extras(fwd.extras, size_t(extra::kCount) * hw, device_);
      if (g_extras.empty()) g_extras.assign(size_t(extra::kCount) * hw, 0.0f);
      if (sized(t.f0, 3 * hw, "F0"))
        m += l1(extras.data() + size_t(extra::kFresnel) * hw, t.f0.data(), 3, g_extras.data() + size_t(extra::kFresnel) * hw);
      if (sized(t.roughness, hw, "roughness"))
        m += l1(extras.data() + size_t(extra::kRoughness) * hw, t.roughness.data(), 1,
                g_extras.data() + size_t(extra::kRoughness) * hw);
    }
    if (sized(t.normal, 3 * hw, "normal")) {
      const HostView normal(fwd.normal, 3 * hw, device_);
      if (g_normal.empty()) g_normal.assign(3 * hw, 0.0f);
      m += normal_prior_loss<float>(normal.data(), t.normal.data(), mw, w, h, g_normal.data(), wm);
    }
    out.material = m;
    total += wm * m;
  }
  return total;
}

}  // namespace goris
