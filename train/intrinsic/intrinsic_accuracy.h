#pragma once
// How close a trained run's materials are to a scene's intrinsic ground truth (issue: "report the error of
// the recovered normals and roughness"), for data sets made by `goris synth`: train/gt/normal_XXX.exr holds
// the true world-space normals, scene.json the materials Blender rendered. Measured on the glossy surface
// (the views' glossy masks) where the model is opaque (alpha > 0.5):
//   normals    angle between the rasterized normal and the true one, mean and median in degrees;
//   roughness  the rasterized roughness (alpha-normalised) against the glossy objects' roughness;
//   F0         against Blender's principled F0: the base colour for metals, 0.08 x specular otherwise,
//              mixed by `metallic`.
// The material references exist only when every glossy object of scene.json has the same value (the
// glossy-table presets have one glossy table); otherwise only the rendered statistics are reported.
#include <filesystem>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene/gaussians.h"
#include "render/raster/raster_types.h"
#include "train/loop/trainer.h"

namespace goris {

struct GlossyMaterialReference {
  float roughness = 0.0f;
  glm::vec3 f0{0.0f};
};

// The shared material of scene.json's glossy objects; nullopt when the file is missing, has no glossy
// object, or they differ. Throws goris::Error naming the file when it is not valid JSON.
std::optional<GlossyMaterialReference> glossy_reference_from_scene(const std::filesystem::path& scene_json);

// Where a data set keeps its true normals (DATA/train/gt with normal_*.exr); nullopt when it has none.
std::optional<std::filesystem::path> ground_truth_normal_dir(const std::filesystem::path& data);

struct IntrinsicAccuracy {
  std::size_t views = 0, pixels = 0;  // views compared, glossy opaque pixels with a true normal
  double normal_mean_deg = 0, normal_median_deg = 0;
  double roughness_mean = 0;
  glm::dvec3 f0_mean{0.0};
  std::optional<GlossyMaterialReference> reference;
  double roughness_mae = 0, f0_mae = 0;  // against the reference (mean over pixels; F0 over RGB), when present
};

// Rasterizes `gaussians` (with their material channels) from each view and compares. `views` carry their glossy
// masks and true normals (TrainView::glossy_mask, ::normal_prior from load_normal_priors); views missing
// either are skipped. Throws goris::Error when the model has no material channels or no pixel qualifies.
IntrinsicAccuracy measure_intrinsic_accuracy(const GaussianView& gaussians, const std::vector<TrainView>& views,
                                             const RasterSettings& raster, Device device,
                                             const std::optional<GlossyMaterialReference>& reference);

}  // namespace goris
