#include "removal/masks/planar_dereflect_scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <nlohmann/json.hpp>

#include "core/inpaint/inpainter.h"
#include "core/io/json_file.h"
#include "core/util/error.h"
#include "removal/masks/inpaint_mask_scene.h"
#include "removal/masks/planar_reflection.h"
#include "render/raster/rasterizer.h"
#include "train/run/train_setup.h"

namespace goris {
namespace {

std::vector<float> mirror_image(GaussianModel& mirrored, const Camera& camera, RasterSettings raster) {
  raster.background = glm::vec3(0.0f);
  if (mirrored.count() == 0) return std::vector<float>(3 * std::size_t(camera.width) * camera.height, 0.0f);
  return rasterize(mirrored.view(false), camera, raster, mirrored.device()).gbuffer.color.to_host();
}

std::vector<float> planar_of(const Image& hwc) {
  const std::size_t hw = hwc.pixel_count();
  const std::vector<float> v = hwc.pixels.to_host();
  std::vector<float> out(3 * hw);
  for (std::size_t p = 0; p < hw; ++p)
    for (int c = 0; c < 3; ++c) out[c * hw + p] = v[p * std::size_t(hwc.channels) + c];
  return out;
}

// What the fit of one view needs, whatever the plane's offset.
struct ViewFit {
  std::size_t view = 0;
  Mask region;
  std::vector<float> smooth;  // the photo's smooth fill from the surface alone
  float busyness = -1.0f;     // the smooth fill's own mean squared error in a band around the region
};

ViewFit prepare_view(std::size_t v, const TrainView& view, const Mask& reflection, GaussianModel& target_front,
                     const RasterSettings& raster, const Inpainter& harmonic, const PlanarDereflectSettings& settings) {
  const int w = view.camera.width, h = view.camera.height;
  ViewFit f;
  f.view = v;
  if (reflection.width != w || reflection.height != h || view.glossy_mask.size() != reflection.pixel_count())
    throw Error("planar dereflection", "the reflection or glossy mask of " + view.name + " is not its camera's size");
  // The target's own pixels: its Gaussians in front of the plane (the removal's coverage also holds the
  // model's mirror world under the target, i.e. the reflection itself).
  Mask own(w, h);
  if (target_front.count() > 0) {
    const std::vector<float> alpha =
        rasterize(target_front.view(false), view.camera, raster, target_front.device()).gbuffer.alpha.to_host();
    for (std::size_t p = 0; p < own.data.size(); ++p) own.data[p] = alpha[p] > 0.2f ? 255 : 0;
  }
  const Mask covered = dilate_mask(own, 2);
  f.region = Mask(w, h);
  Mask hole = mask_or(reflection, covered);  // the smooth fill's: everything but the surface around
  for (std::size_t p = 0; p < hole.data.size(); ++p) {
    const bool surface = view.glossy_mask[p] > 0.5f;
    f.region.data[p] = reflection.data[p] && !covered.data[p] && surface ? 255 : 0;
    if (!surface) hole.data[p] = 255;
  }
  if (count_set(f.region) == 0) return f;
  const Image photo = from_planar(view.image.data(), 3, w, h);
  f.smooth = planar_of(inpaint_map(harmonic, photo, hole, {view.name, "rgb", MapKind::Color}));
  // The same fill's error where the photo is known: a band around the reflection filled as if unseen.
  const Mask out = dilate_mask(reflection, std::max(1, int(std::lround(settings.band_fraction * float(w)))));
  Mask band(w, h), band_hole = hole;
  for (std::size_t p = 0; p < band.data.size(); ++p)
    if (out.data[p] && !hole.data[p]) band.data[p] = band_hole.data[p] = 255;
  const std::size_t n = count_set(band);
  if (n == 0) return f;
  const std::vector<float> fill = planar_of(inpaint_map(harmonic, photo, band_hole, {view.name, "rgb", MapKind::Color}));
  const std::size_t hw = band.pixel_count();
  double e = 0;
  for (std::size_t p = 0; p < hw; ++p)
    if (band.data[p])
      for (int c = 0; c < 3; ++c) e += std::pow(double(view.image[c * hw + p]) - fill[c * hw + p], 2.0);
  f.busyness = float(e / double(3 * n));
  return f;
}

}  // namespace

PlanarDereflectScene dereflect_planar_views(const GaussianModel& model, const SelectionMask& target,
                                            const SelectionMask& removed, const MirrorPlane& plane,
                                            const std::vector<TrainView>& views, const std::vector<Mask>& reflection,
                                            const RasterSettings& raster, const PlanarDereflectSettings& settings) {
  const std::size_t n = model.count();
  if (target.size() != n || removed.size() != n)
    throw Error("planar dereflection", "the selections have " + std::to_string(target.size()) + " and " +
                                           std::to_string(removed.size()) + " entries for " + std::to_string(n) +
                                           " Gaussians");
  if (reflection.size() != views.size())
    throw Error("planar dereflection", std::to_string(reflection.size()) + " reflection masks for " +
                                           std::to_string(views.size()) + " views");
  PlanarDereflectScene out;
  out.fits.resize(views.size());
  out.region.resize(views.size());
  out.rgb.resize(views.size());
  // What stands in front of the surface (beyond the plane's tolerance: not the surface itself, not the
  // mirror world behind it), with and without the target.
  const std::vector<float> pos = model.tensor(Param::Position).value.to_host();
  SelectionMask with(n, 0), without(n, 0), target_front(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const glm::dvec3 c(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]);
    const bool in_front = plane.signed_distance(c) > plane.tolerance;
    without[i] = in_front && !removed[i] ? 1 : 0;
    target_front[i] = in_front && target[i] ? 1 : 0;
    with[i] = without[i] || target_front[i] ? 1 : 0;
  }
  GaussianModel target_model = subset_model(model, target_front);
  const auto harmonic = make_inpainter("harmonic");
  std::vector<ViewFit> fits;
  std::vector<float> busyness;
  for (std::size_t v = 0; v < views.size(); ++v) {
    if (reflection[v].data.empty() || count_set(reflection[v]) == 0) continue;
    ViewFit f = prepare_view(v, views[v], reflection[v], target_model, raster, *harmonic, settings);
    if (f.smooth.empty()) continue;
    if (f.busyness >= 0.0f) busyness.push_back(f.busyness);
    fits.push_back(std::move(f));
  }
  if (fits.empty()) return out;
  if (!busyness.empty()) {
    std::nth_element(busyness.begin(), busyness.begin() + std::ptrdiff_t(busyness.size() / 2), busyness.end());
    out.busyness = busyness[busyness.size() / 2];
  }
  out.busy = out.busyness > settings.busy_surface;
  PlanarDereflectSettings apply = settings;
  if (out.busy) apply.min_explained = -std::numeric_limits<float>::infinity();

  // The mirror images' share of the target for every view, at one offset of the plane.
  auto deltas_at = [&](const MirrorPlane& p) {
    GaussianModel a = mirrored_through(model, with, p), b = mirrored_through(model, without, p);
    std::vector<std::vector<float>> d(fits.size());
    for (std::size_t k = 0; k < fits.size(); ++k) {
      const Camera& cam = views[fits[k].view].camera;
      const std::vector<float> ia = mirror_image(a, cam, raster), ib = mirror_image(b, cam, raster);
      d[k].resize(ia.size());
      for (std::size_t q = 0; q < ia.size(); ++q) d[k][q] = ia[q] - ib[q];
    }
    return d;
  };
  // The offset whose mirror images explain the most of the photos (region pixels weighted).
  MirrorPlane best = plane;
  double best_score = -1;
  std::vector<std::vector<float>> best_deltas;
  for (int k = -settings.offset_steps; k <= settings.offset_steps; ++k) {
    MirrorPlane p = plane;
    p.offset += double(k) * double(settings.offset_step_ratio) * plane.tolerance;
    std::vector<std::vector<float>> d = deltas_at(p);
    double score = 0;
    for (std::size_t f = 0; f < fits.size(); ++f) {
      std::vector<float> photo = views[fits[f].view].image;
      const PlanarDereflectFit r = dereflect_planar_reflection(photo, fits[f].smooth, d[f], fits[f].region, settings);
      score += double(r.explained) * double(r.pixels);
    }
    if (score > best_score) best_score = score, best = p, best_deltas = std::move(d);
  }
  out.offset = best.offset - plane.offset;
  for (std::size_t f = 0; f < fits.size(); ++f) {
    const std::size_t v = fits[f].view;
    std::vector<float> photo = views[v].image;
    out.fits[v] = dereflect_planar_reflection(photo, fits[f].smooth, best_deltas[f], fits[f].region, apply);
    if (!out.fits[v].applied) continue;
    out.views += 1;
    out.pixels += out.fits[v].pixels;
    out.region[v] = std::move(fits[f].region);
    out.rgb[v] = std::move(photo);
  }
  return out;
}

void write_planar_dereflect(const std::filesystem::path& out_dir, const PlanarDereflectScene& scene,
                            const std::vector<TrainView>& views) {
  std::filesystem::create_directories(out_dir);
  nlohmann::json per_view = nlohmann::json::array();
  for (std::size_t v = 0; v < scene.fits.size() && v < views.size(); ++v) {
    const PlanarDereflectFit& f = scene.fits[v];
    if (f.pixels == 0) continue;
    per_view.push_back({{"view", views[v].name}, {"pixels", f.pixels}, {"scale", f.reflectance}, {"blur_px", f.blur},
                        {"explained", f.explained}, {"applied", f.applied}});
    if (!scene.rgb[v].empty())
      save_png(out_dir / (views[v].name + ".png"),
               from_planar(scene.rgb[v].data(), 3, views[v].camera.width, views[v].camera.height));
  }
  write_json_file(out_dir / "fits.json", {{"plane_offset", scene.offset},
                                          {"busyness", scene.busyness},
                                          {"busy", scene.busy},
                                          {"views", per_view}});
}

void paste_planar_dereflect(Image& rgb, const PlanarDereflectScene& scene, std::size_t view) {
  if (view >= scene.rgb.size() || scene.rgb[view].empty()) return;
  const Mask& region = scene.region[view];
  const std::size_t hw = region.pixel_count();
  if (rgb.pixel_count() != hw || rgb.channels < 3)
    throw Error("planar dereflection", "the colour map (" + std::to_string(rgb.width) + "x" + std::to_string(rgb.height) +
                                           "x" + std::to_string(rgb.channels) + ") is not the region's size (" +
                                           std::to_string(region.width) + "x" + std::to_string(region.height) + "x3)");
  std::vector<float> px = rgb.pixels.to_host();
  const std::size_t ch = std::size_t(rgb.channels);
  for (std::size_t p = 0; p < hw; ++p)
    if (region.data[p])
      for (std::size_t c = 0; c < 3; ++c) px[p * ch + c] = scene.rgb[view][c * hw + p];
  rgb.pixels.upload(px.data(), px.size());
}

}  // namespace goris
