#include "removal/shadow/target_shadow_scene.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "core/io/image.h"
#include "core/scene/gaussian_kernels.h"
#include "core/scene/selection_points.h"
#include "core/util/error.h"
#include "removal/masks/inpaint_mask_scene.h"
#include "removal/masks/lighting_aware_mask.h"
#include "render/raster/rasterizer.h"

namespace goris {

TargetOccluder::TargetOccluder(const GaussianModel& model, const SelectionMask& target)
    : target_(subset_model(model, target).copy_to(Device::CPU)), tracer_(Device::CPU) {
  tracer_.build(target_.view(false));
}

TargetOcclusion TargetOccluder::function() const {
  return [this](const std::vector<glm::vec3>& o, const std::vector<glm::vec3>& d, std::vector<float>& alpha) {
    if (o.empty()) return;
    TraceOutputs out;
    out.alpha = alpha.data();
    tracer_.trace({&o[0].x, &d[0].x, o.size()}, out);
  };
}

PlanePixels support_plane_pixels(const Camera& camera, const std::vector<float>& median_depth,
                                 const std::vector<float>& alpha, const ShadowGeometry& geo) {
  const std::size_t w = std::size_t(camera.width), h = std::size_t(camera.height);
  if (median_depth.size() != w * h || alpha.size() != w * h)
    throw Error("shadow", "depth/alpha maps of " + std::to_string(median_depth.size()) + " pixels for a " +
                              std::to_string(w) + "x" + std::to_string(h) + " camera");
  PlanePixels px;
  if (!geo.found) return px;
  const glm::dvec3 c(camera.center());
  const double nc = glm::dot(geo.plane.normal, c);
  for (std::size_t y = 0; y < h; ++y)
    for (std::size_t x = 0; x < w; ++x) {
      const std::size_t p = y * w + x;
      if (alpha[p] < 0.5f || median_depth[p] <= 0.0f) continue;
      const glm::dvec3 d(camera.ray_direction(float(x) + 0.5f, float(y) + 0.5f));
      const double nd = glm::dot(geo.plane.normal, d);
      if (std::abs(nd) < 1e-6) continue;
      const double t = (geo.plane.offset - nc) / nd;
      if (t <= 0) continue;
      const glm::dvec3 hit = c + t * d;
      if (!geo.in_reach(hit)) continue;
      const double z = camera.to_camera(glm::vec3(hit)).z;
      if (std::abs(double(median_depth[p]) - z) > 0.03 * z + 2.0 * geo.plane.tolerance) continue;
      px.pixel.push_back(std::uint32_t(p));
      px.point.push_back(glm::vec3(hit));
    }
  return px;
}

namespace {

// Multiplies channel c of pixel p, at data[p * pixel_stride + c * channel_stride], by its gain.
void relight(float* data, std::size_t pixel_stride, std::size_t channel_stride, bool sizes_ok, const std::string& image,
             const PlanePixels& px, const std::vector<float>& s, const TargetShadow& shadow) {
  if (s.size() != px.size() || !sizes_ok)
    throw Error("shadow", "relighting " + std::to_string(px.size()) + " pixels with " + std::to_string(s.size()) +
                              " shadow values in an image of " + image);
  for (std::size_t k = 0; k < px.size(); ++k) {
    const glm::vec3 g = shadow_gain(shadow, s[k]);
    for (std::size_t c = 0; c < 3; ++c) data[px.pixel[k] * pixel_stride + c * channel_stride] *= g[c];
  }
}

// The opacity-weighted median F0 of the support surface's Gaussians near the target (0 without materials).
double support_fresnel(const GaussianModel& model, const SelectionMask& candidates, const std::vector<float>& opacity,
                       const std::vector<glm::vec3>& position, const ShadowGeometry& geo) {
  if (model.tensor(Param::ExtraLogit).width != extra::kCount) return 0.0;
  SelectionMask support(candidates.size(), 0);
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const glm::dvec3 p(position[i]);
    support[i] = candidates[i] && opacity[i] >= 0.05f && geo.near_plane(p) && geo.in_reach(p);
  }
  return fresnel_quantile(model, support, 0.5f).value_or(0.0f);
}

// The other objects standing on the support surface: non-target Gaussians above its plane's tolerance, opaque
// enough not to be a short run's fog.
SelectionMask other_objects_on(const SelectionMask& candidates, const std::vector<float>& opacity,
                               const std::vector<glm::vec3>& position, const ShadowGeometry& geo,
                               const ShadowSettings& settings) {
  SelectionMask other_objects(candidates.size(), 0);
  for (std::size_t i = 0; i < candidates.size(); ++i)
    other_objects[i] = candidates[i] && opacity[i] >= settings.others_opacity &&
                       geo.height(glm::dvec3(position[i])) > geo.plane.tolerance;
  return other_objects;
}

}  // namespace

void relight_planar(std::vector<float>& image, std::size_t hw, const PlanePixels& px, const std::vector<float>& s,
                    const TargetShadow& shadow) {
  relight(image.data(), 1, hw, image.size() >= 3 * hw, std::to_string(image.size()) + " floats", px, s, shadow);
}

void relight_image(Image& image, const PlanePixels& px, const std::vector<float>& s, const TargetShadow& shadow) {
  relight(image.pixels.data(), std::size_t(image.channels), 1, image.channels >= 3,
          std::to_string(image.channels) + " channels", px, s, shadow);
}

ShadowRelight relight_target_shadow(GaussianModel& model, const SelectionMask& target, const SelectionMask& selected,
                                    const MirrorPlane* fallback, std::vector<TrainView>& views,
                                    const RasterSettings& raster, const std::filesystem::path& out_dir,
                                    ShadowSampleColour sample_colour, const EnvironmentImage* environment) {
  ShadowRelight out;
  const SelectionPoints pts = selection_points(model);
  const std::vector<float> logit = model.tensor(Param::OpacityLogit).value.to_host();
  std::vector<float> opacity(logit.size());
  for (std::size_t i = 0; i < logit.size(); ++i) opacity[i] = kernels::sigmoid(logit[i]);
  SelectionMask candidates(selected.size());
  for (std::size_t i = 0; i < selected.size(); ++i) candidates[i] = !selected[i];
  const ShadowGeometry geo = shadow_geometry(pts.position, opacity, target, candidates, {}, fallback);
  if (!geo.found) {
    out.fit.reason = geo.reason;
    return out;
  }

  constexpr std::size_t kMaxSamples = 20000;
  out.pixels.resize(views.size());
  std::size_t total = 0;
  std::vector<std::vector<glm::vec3>> colour(views.size());  // per view, per plane pixel
  for (std::size_t i = 0; i < views.size(); ++i) {
    const RasterOutput r = rasterize(model.view(false), views[i].camera, raster, model.device());
    out.pixels[i] = support_plane_pixels(views[i].camera, r.gbuffer.median_depth.to_host(), r.gbuffer.alpha.to_host(), geo);
    const std::vector<float> rendered =
        sample_colour == ShadowSampleColour::Model ? r.gbuffer.color.to_host() : std::vector<float>{};
    const std::vector<float>& c = sample_colour == ShadowSampleColour::Model ? rendered : views[i].image;
    const std::size_t hw = c.size() / 3;
    for (const std::uint32_t p : out.pixels[i].pixel) colour[i].push_back({c[p], c[hw + p], c[2 * hw + p]});
    total += out.pixels[i].size();
  }
  const std::size_t stride = std::max<std::size_t>(1, (total + kMaxSamples - 1) / kMaxSamples);
  ShadowSamples samples;
  std::size_t seen = 0;
  for (std::size_t i = 0; i < views.size(); ++i)
    for (std::size_t k = 0; k < out.pixels[i].size(); ++k, ++seen)
      if (seen % stride == 0) samples.add(out.pixels[i].point[k], colour[i][k]);
  const TargetOccluder occluder(model, target);
  const EnvironmentLight light = environment ? environment_light(*environment, geo.up) : EnvironmentLight{};
  const glm::dvec3 known = light.direction_from(geo.centroid);
  const bool above = light.found && glm::dot(known, geo.up) > 0.0;  // one under the surface casts no shadow on it
  const ShadowSettings settings;
  const double f0 = environment ? support_fresnel(model, candidates, opacity, pts.position, geo) : 0.0;
  const bool dielectric = f0 <= settings.known_light_max_fresnel;
  out.fit = fit_target_shadow(geo, samples, occluder.function(), settings, above && dielectric ? &known : nullptr);
  if (environment) {
    char b[160];
    std::snprintf(b, sizeof b, "; support F0 %.3f%s", f0,
                  out.fit.found ? ""
                  : !light.found ? ", no light in the environment"
                  : !above     ? ", the environment's light is not above the support surface"
                  : !dielectric ? ", a metal's colour is its reflections: no search near the environment's light"
                                : "");
    out.fit.reason += b;
  }
  if (!out.fit.found) return out;
  // Step 6 of target_shadow.h: the fitted light against the other objects' shadows; step 7 below.
  const SelectionMask other_objects = other_objects_on(candidates, opacity, pts.position, geo, settings);
  std::optional<TargetOccluder> others;
  if (count_selected(other_objects) > 0) others.emplace(model, other_objects);
  const OthersShadow check =
      others ? others_shadow(out.fit, samples, occluder.function(), others->function(), settings) : OthersShadow{};
  if (check.contradicts) {
    char b[200];
    std::snprintf(b, sizeof b, "the light puts the other objects' shadows on %.0f %% of the lit samples, "
                  "where the photos show a shadow of %.2f: not the light (",
                  100.0 * check.shaded_share, check.strength);
    out.fit.found = false;
    out.fit.reason = b + out.fit.reason + ")";
    return out;
  }

  if (!out_dir.empty()) std::filesystem::create_directories(out_dir);
  out.s.resize(views.size());
  for (std::size_t i = 0; i < views.size(); ++i) {
    const PlanePixels& px = out.pixels[i];
    out.s[i] = shadow_fraction(out.fit, px.point, occluder.function());
    if (others) {
      const std::vector<float> so = shadow_fraction(out.fit, px.point, others->function());
      for (std::size_t k = 0; k < so.size(); ++k)
        out.s[i][k] = shadow_fraction_beside_others(out.s[i][k], so[k], out.fit.strength_luminance);
    }
    const std::size_t hw = views[i].image.size() / 3;
    relight_planar(views[i].image, hw, px, out.s[i], out.fit);
    std::vector<float> share(px.size());  // the share of the light the target took, per plane pixel
    for (std::size_t k = 0; k < px.size(); ++k) {
      share[k] = float(out.fit.strength_luminance) * out.s[i][k];
      out.relit_pixels += share[k] > 0.05f ? 1 : 0;
    }
    if (out_dir.empty()) continue;
    Image im(views[i].camera.width, views[i].camera.height, 1, Device::CPU);
    for (std::size_t p = 0; p < hw; ++p) im.pixels[p] = 0.0f;
    for (std::size_t k = 0; k < px.size(); ++k) im.pixels[px.pixel[k]] = share[k];
    save_png(out_dir / (views[i].name + ".png"), im);
  }
  return out;
}

}  // namespace goris
