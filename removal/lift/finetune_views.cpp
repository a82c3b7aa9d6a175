#include "removal/lift/finetune_views.h"

#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "core/util/error.h"

namespace goris {

namespace {

// Value of channel c at pixel p of an optional host map (nullptr when absent).
struct HostMap {
  std::vector<float> px;
  int channels = 0;
  explicit HostMap(const Image& im) {
    if (im.pixels.size() == 0) return;
    px = im.pixels.to_host();
    channels = im.channels;
  }
  bool present() const { return channels > 0; }
  float at(std::size_t p, int c) const { return px[p * std::size_t(channels) + std::size_t(c)]; }
};

void check_size(const TrainView& v, int w, int h, const char* what) {
  if (w != v.camera.width || h != v.camera.height)
    throw Error(v.name, std::string(what) + " is " + std::to_string(w) + "x" + std::to_string(h) + ", the view " +
                            std::to_string(v.camera.width) + "x" + std::to_string(v.camera.height));
}

std::shared_ptr<InpaintTargets> empty_targets(std::size_t hw) {
  auto t = std::make_shared<InpaintTargets>();
  t->color.assign(3 * hw, 0.0f);
  t->appearance_weight.assign(hw, 0.0f);
  t->base_color.assign(3 * hw, 0.0f);
  t->f0.assign(3 * hw, 0.0f);
  t->roughness.assign(hw, 0.0f);
  t->normal.assign(3 * hw, 0.0f);
  t->material_weight.assign(hw, 0.0f);
  return t;
}

// Writes the targets of an inpainted map set into `t` on the hole pixels that `skip` leaves (skip[p] true:
// taken already), with the set's weight; returns how many pixels it set.
std::size_t targets_from_maps(const TrainView& v, const ReferenceTargets& r, const std::vector<bool>* skip,
                              const FinetuneViewSettings& st, InpaintTargets& t, FinetuneViewStats& stats) {
  const std::size_t hw = std::size_t(v.camera.width) * v.camera.height;
  check_size(v, r.hole->width, r.hole->height, "the inpainting mask");
  const HostMap rgb(r.maps->rgb), region(r.maps->region), f0(r.maps->fresnel), rough(r.maps->roughness),
      normal(r.maps->normal);
  if (!rgb.present()) throw Error(v.name, "the inpainted colour map is missing");
  std::size_t n = 0;
  for (std::size_t p = 0; p < hw; ++p) {
    if (!r.hole->data[p] || (skip && (*skip)[p])) continue;
    ++n;
    const bool rough_px = !region.present() || region.at(p, 0) > st.rough_threshold;
    for (int c = 0; c < 3; ++c) t.color[c * hw + p] = t.base_color[c * hw + p] = rgb.at(p, c);
    if (rough_px) {
      t.appearance_weight[p] = r.weight;
      ++stats.appearance_pixels;
      continue;
    }
    t.material_weight[p] = r.weight;
    ++stats.material_pixels;
    for (int c = 0; c < 3; ++c) {
      t.f0[c * hw + p] = f0.present() ? f0.at(p, c) : 0.5f;
      t.normal[c * hw + p] = normal.present() ? normal.at(p, c) : 0.0f;
    }
    t.roughness[p] = rough.present() ? rough.at(p, 0) : 0.5f;
  }
  return n;
}

// Per pixel, the index of the nearest reference point projected there (-1 = none), only where the photo
// loss is off and the removed scene's own surface is not in front of the point.
std::vector<int> nearest_points(const TrainView& v, const FinetuneViewInputs& in, const ReferencePoints& points,
                                const FinetuneViewSettings& st) {
  const int W = v.camera.width, H = v.camera.height;
  const std::size_t hw = std::size_t(W) * H;
  std::vector<int> who(hw, -1);
  if (points.size() == 0) return who;
  std::vector<float> zbuf(hw, std::numeric_limits<float>::infinity());
  std::vector<float> removed_depth;
  if (in.removed_depth) {
    check_size(v, in.removed_depth->width, in.removed_depth->height, "the removed depth");
    removed_depth = in.removed_depth->pixels.to_host();
  }
  for (std::size_t k = 0; k < points.size(); ++k) {
    const glm::vec3 c = v.camera.to_camera(points.position[k]);
    if (!(c.z > 1e-4f)) continue;
    const int x = int(std::floor(v.camera.fx * c.x / c.z + v.camera.cx));
    const int y = int(std::floor(v.camera.fy * c.y / c.z + v.camera.cy));
    if (x < 0 || y < 0 || x >= W || y >= H) continue;
    const std::size_t p = std::size_t(y) * W + x;
    if (v.loss_weight[p] > 0) continue;
    if (!removed_depth.empty() && removed_depth[p] > 0 && removed_depth[p] * (1 + st.depth_tolerance) < c.z) continue;
    if (c.z < zbuf[p]) {
      zbuf[p] = c.z;
      who[p] = int(k);
    }
  }
  return who;
}

}  // namespace

FinetuneViewStats prepare_finetune_views(std::vector<TrainView>& views, const std::vector<FinetuneViewInputs>& inputs,
                                         const std::vector<ReferenceTargets>& references,
                                         const ReferencePoints& points, const FinetuneViewSettings& st) {
  if (inputs.size() != views.size())
    throw Error("fine-tune views", std::to_string(inputs.size()) + " inputs for " + std::to_string(views.size()) + " views");
  FinetuneViewStats stats;
  for (std::size_t i = 0; i < views.size(); ++i) {
    TrainView& v = views[i];
    const FinetuneViewInputs& in = inputs[i];
    const int W = v.camera.width, H = v.camera.height;
    const std::size_t hw = std::size_t(W) * H;
    v.loss_weight.assign(hw, 1.0f);
    v.inpaint.reset();
    if (in.exclude) {
      check_size(v, in.exclude->width, in.exclude->height, "the exclusion mask");
      for (std::size_t p = 0; p < hw; ++p)
        if (in.exclude->data[p]) {
          v.loss_weight[p] = 0.0f;
          ++stats.excluded_pixels;
        }
    }
    if (!v.object_mask.empty()) v.object_mask.clear();  // the label loss is off in stage 2

    std::shared_ptr<InpaintTargets> t = empty_targets(hw);
    bool any = false;
    if (in.reference >= 0) {
      any = targets_from_maps(v, references.at(std::size_t(in.reference)), nullptr, st, *t, stats) > 0;
    } else {
      const std::vector<int> who = nearest_points(v, in, points, st);
      std::vector<bool> taken(hw, false);  // by a point, or photo loss on: the view's own fill stays out
      for (std::size_t p = 0; p < hw; ++p) {
        taken[p] = who[p] >= 0 || v.loss_weight[p] != 0.0f;
        if (who[p] < 0) continue;
        const std::size_t k = std::size_t(who[p]);
        any = true;
        ++stats.projected_points;
        for (int c = 0; c < 3; ++c) t->color[c * hw + p] = t->base_color[c * hw + p] = points.color[k][c];
        if (points.region[k] > st.rough_threshold) {
          t->appearance_weight[p] = 1.0f;
          continue;
        }
        t->material_weight[p] = 1.0f;
        const glm::vec3 n = v.camera.R * points.normal[k];
        for (int c = 0; c < 3; ++c) {
          t->f0[c * hw + p] = points.fresnel[k][c];
          t->normal[c * hw + p] = glm::length(n) > 0.5f ? glm::normalize(n)[c] : 0.0f;
        }
        t->roughness[p] = points.roughness[k];
      }
      if (in.fill >= 0) {
        const std::size_t filled = targets_from_maps(v, references.at(std::size_t(in.fill)), &taken, st, *t, stats);
        stats.filled_pixels += filled;
        any = any || filled > 0;
      }
    }
    if (any) v.inpaint = std::move(t);
  }
  return stats;
}

std::size_t use_true_fills(std::vector<TrainView>& views, const std::vector<std::vector<float>>& truth) {
  if (truth.size() != views.size())
    throw Error("true fills", std::to_string(truth.size()) + " images for " + std::to_string(views.size()) + " views");
  std::size_t replaced = 0;
  for (std::size_t i = 0; i < views.size(); ++i) {
    TrainView& v = views[i];
    const std::size_t hw = std::size_t(v.camera.width) * v.camera.height;
    if (truth[i].size() != 3 * hw || v.image.size() != 3 * hw)
      throw Error(v.name, "the true image is not the view's size (" + std::to_string(v.camera.width) + "x" +
                              std::to_string(v.camera.height) + ")");
    if (v.loss_weight.empty()) v.loss_weight.assign(hw, 1.0f);
    const InpaintTargets* t = v.inpaint.get();
    for (std::size_t p = 0; p < hw; ++p) {
      const bool target = t && ((!t->appearance_weight.empty() && t->appearance_weight[p] > 0) ||
                                (!t->material_weight.empty() && t->material_weight[p] > 0));
      if (v.loss_weight[p] > 0 && !target) continue;
      for (std::size_t c = 0; c < 3; ++c) v.image[c * hw + p] = truth[i][c * hw + p];
      v.loss_weight[p] = 1.0f;
      ++replaced;
    }
    v.inpaint.reset();
  }
  return replaced;
}

PhotoTargetsTruthError photo_targets_against_truth(const std::vector<TrainView>& views,
                                                   const std::vector<std::vector<float>>& photos,
                                                   const std::vector<std::vector<float>>& truth) {
  if (photos.size() != views.size() || truth.size() != views.size())
    throw Error("photo targets against the truth", std::to_string(photos.size()) + " photos and " +
                                                       std::to_string(truth.size()) + " true images for " +
                                                       std::to_string(views.size()) + " views");
  PhotoTargetsTruthError e;
  for (std::size_t i = 0; i < views.size(); ++i) {
    const TrainView& v = views[i];
    const std::size_t hw = std::size_t(v.camera.width) * v.camera.height;
    if (photos[i].size() != 3 * hw || truth[i].size() != 3 * hw || v.image.size() != 3 * hw ||
        (!v.loss_weight.empty() && v.loss_weight.size() != hw))
      throw Error(v.name, "the photo, the true image and the view are not all " + std::to_string(v.camera.width) + "x" +
                              std::to_string(v.camera.height));
    for (std::size_t p = 0; p < hw; ++p) {
      double photo = 0, target = 0;
      bool changed = false;
      for (std::size_t c = 0; c < 3; ++c) {
        const std::size_t k = c * hw + p;
        photo += std::abs(double(photos[i][k]) - truth[i][k]) / 3.0;
        target += std::abs(double(v.image[k]) - truth[i][k]) / 3.0;
        changed = changed || v.image[k] != photos[i][k];
      }
      e.imprint += photo;
      if (!v.loss_weight.empty() && !(v.loss_weight[p] > 0)) continue;
      ++e.trained_pixels;
      e.photos += photo;
      e.targets += target;
      if (!changed) continue;
      ++e.changed_pixels;
      e.changed_photos += photo;
      e.changed_targets += target;
    }
  }
  return e;
}

}  // namespace goris
