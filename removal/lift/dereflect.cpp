#include "removal/lift/dereflect.h"

#include <algorithm>
#include <cmath>

#include "core/io/image.h"
#include "core/util/error.h"
#include "train/intrinsic/intrinsic_renderer.h"
#include "train/run/train_setup.h"

namespace goris {

double subtract_reflection(std::vector<float>& photo, const std::vector<float>& with_target,
                           const std::vector<float>& removed, const Mask& where) {
  const std::size_t hw = where.pixel_count();
  if (photo.size() != 3 * hw || with_target.size() != 3 * hw || removed.size() != 3 * hw)
    throw Error("lighting-aware targets", "photo (" + std::to_string(photo.size()) + "), renders (" +
                                              std::to_string(with_target.size()) + ", " +
                                              std::to_string(removed.size()) + ") and mask (3 x " +
                                              std::to_string(hw) + ") differ in size");
  double change = 0;
  for (std::size_t p = 0; p < hw; ++p) {
    if (!where.data[p]) continue;
    double d = 0;
    for (int c = 0; c < 3; ++c) {
      float& v = photo[c * hw + p];
      const float next = std::clamp(v - (with_target[c * hw + p] - removed[c * hw + p]), 0.0f, 1.0f);
      d += std::abs(double(next) - double(v));
      v = next;
    }
    change += d / 3;
  }
  return change;
}

DereflectResult dereflect_views(IntrinsicRenderer& renderer, GaussianModel& with_target,
                                GaussianModel& removed, const std::vector<Mask>& lighting,
                                std::vector<TrainView>& views, const std::filesystem::path& out_dir,
                                const std::function<void(std::size_t, std::size_t)>& tell,
                                const std::function<bool()>& cancelled) {
  if (lighting.size() != views.size())
    throw Error("lighting-aware targets", std::to_string(lighting.size()) + " masks for " +
                                              std::to_string(views.size()) + " views");
  if (!out_dir.empty()) std::filesystem::create_directories(out_dir);
  DereflectResult r;
  double change = 0;
  for (std::size_t i = 0; i < views.size(); ++i) {
    if (cancelled && cancelled()) break;
    if (tell) tell(i, views.size());
    const Mask& m = lighting[i];
    if (count_set(m) == 0) continue;
    TrainView& v = views[i];
    if (m.width != v.camera.width || m.height != v.camera.height)
      throw Error("lighting-aware targets", "the mask of " + v.name + " is " + std::to_string(m.width) + "x" +
                                                std::to_string(m.height) + ", its camera " +
                                                std::to_string(v.camera.width) + "x" + std::to_string(v.camera.height));
    const std::vector<float> with = renderer.render_maps(with_target.view(true), v.camera).color;
    const std::vector<float> without = renderer.render_maps(removed.view(true), v.camera).color;
    change += subtract_reflection(v.image, with, without, m);
    r.views += 1;
    r.pixels += count_set(m);
    if (!out_dir.empty())
      save_png(out_dir / (v.name + ".png"), from_planar(v.image.data(), 3, v.camera.width, v.camera.height));
  }
  r.mean_change = r.pixels ? change / double(r.pixels) : 0.0;
  return r;
}

}  // namespace goris
