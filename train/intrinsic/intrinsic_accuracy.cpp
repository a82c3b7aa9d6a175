#include "train/intrinsic/intrinsic_accuracy.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "core/io/file_bytes.h"
#include "core/util/error.h"
#include "render/raster/rasterizer.h"

namespace goris {

namespace fs = std::filesystem;

std::optional<GlossyMaterialReference> glossy_reference_from_scene(const fs::path& scene_json) {
  if (!fs::exists(scene_json)) return std::nullopt;
  const nlohmann::json j = nlohmann::json::parse(read_text_file(scene_json), nullptr, false);
  if (j.is_discarded()) throw Error(scene_json.string(), "is not valid JSON");
  if (!j.contains("objects") || !j["objects"].is_array()) return std::nullopt;
  std::optional<GlossyMaterialReference> ref;
  for (const auto& o : j["objects"]) {
    if (!o.value("glossy", false) || !o.contains("material")) continue;
    const auto& m = o["material"];
    GlossyMaterialReference r;
    r.roughness = m.value("roughness", 0.5f);
    const float metallic = std::clamp(m.value("metallic", 0.0f), 0.0f, 1.0f);
    const float dielectric = 0.08f * m.value("specular", 0.5f);
    glm::vec3 color(0.8f);
    if (m.contains("color") && m["color"].is_array() && m["color"].size() == 3)
      color = {m["color"][0].get<float>(), m["color"][1].get<float>(), m["color"][2].get<float>()};
    r.f0 = glm::mix(glm::vec3(dielectric), color, metallic);
    if (ref && (std::abs(ref->roughness - r.roughness) > 1e-3f || glm::length(ref->f0 - r.f0) > 1e-3f))
      return std::nullopt;  // several glossy materials: no single reference
    ref = r;
  }
  return ref;
}

std::optional<fs::path> ground_truth_normal_dir(const fs::path& data) {
  const fs::path dir = data / "train" / "gt";
  if (!fs::is_directory(dir)) return std::nullopt;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().rfind("normal_", 0) == 0) return dir;
  return std::nullopt;
}

IntrinsicAccuracy measure_intrinsic_accuracy(const GaussianView& gaussians, const std::vector<TrainView>& views,
                                             const RasterSettings& raster, Device device,
                                             const std::optional<GlossyMaterialReference>& reference) {
  if (gaussians.n_extras != extra::kCount)
    throw Error("intrinsic accuracy", "the model has no material channels (a radiance run?)");
  IntrinsicAccuracy a;
  a.reference = reference;
  std::vector<double> angles;
  double rough_sum = 0, rough_err = 0, f0_err = 0;
  glm::dvec3 f0_sum(0.0);
  for (const TrainView& v : views) {
    const std::size_t hw = std::size_t(v.camera.width) * std::size_t(v.camera.height);
    if (v.glossy_mask.size() != hw || v.normal_prior.size() != 3 * hw) continue;
    const RasterOutput r = rasterize(gaussians, v.camera, raster, device);
    const std::vector<float> alpha = r.gbuffer.alpha.to_host(), normal = r.gbuffer.normal.to_host(),
                             extras = r.gbuffer.extras.to_host();
    ++a.views;
    for (std::size_t p = 0; p < hw; ++p) {
      const glm::vec3 truth(v.normal_prior[p], v.normal_prior[hw + p], v.normal_prior[2 * hw + p]);
      const glm::vec3 n(normal[p], normal[hw + p], normal[2 * hw + p]);
      if (v.glossy_mask[p] < 0.5f || alpha[p] < 0.5f || glm::length(truth) < 0.5f || glm::length(n) < 1e-6f) continue;
      const double c = std::clamp(double(glm::dot(glm::normalize(n), glm::normalize(truth))), -1.0, 1.0);
      angles.push_back(std::acos(c) * 180.0 / M_PI);
      const double inv = 1.0 / double(alpha[p]);
      const double rough = double(extras[std::size_t(extra::kRoughness) * hw + p]) * inv;
      glm::dvec3 f0;
      for (int ch = 0; ch < 3; ++ch) f0[ch] = double(extras[std::size_t(extra::kFresnel + ch) * hw + p]) * inv;
      rough_sum += rough;
      f0_sum += f0;
      if (reference) {
        rough_err += std::abs(rough - double(reference->roughness));
        f0_err += (std::abs(f0.x - reference->f0.x) + std::abs(f0.y - reference->f0.y) + std::abs(f0.z - reference->f0.z)) / 3.0;
      }
    }
  }
  if (angles.empty())
    throw Error("intrinsic accuracy", "no opaque glossy pixel with a true normal in " + std::to_string(views.size()) +
                                          " views (glossy masks and train/gt/normal_*.exr present?)");
  a.pixels = angles.size();
  const double n = double(a.pixels);
  double sum = 0;
  for (double x : angles) sum += x;
  a.normal_mean_deg = sum / n;
  std::nth_element(angles.begin(), angles.begin() + std::ptrdiff_t(angles.size() / 2), angles.end());
  a.normal_median_deg = angles[angles.size() / 2];
  a.roughness_mean = rough_sum / n;
  a.f0_mean = f0_sum / n;
  a.roughness_mae = rough_err / n;
  a.f0_mae = f0_err / n;
  return a;
}

}  // namespace goris
