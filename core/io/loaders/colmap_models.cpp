// COLMAP camera-model table shared by the binary and text parsers.
#include "core/io/loaders/colmap_model.h"

#include "core/io/loaders/colmap_parse_util.h"

namespace goris {
namespace {
struct ModelInfo {
  const char* name;
  int params;
};
// Index = COLMAP model id (colmap/src/base/camera_models.h).
constexpr ModelInfo kModels[] = {
    {"SIMPLE_PINHOLE", 3}, {"PINHOLE", 4},         {"SIMPLE_RADIAL", 4},         {"RADIAL", 5},
    {"OPENCV", 8},         {"OPENCV_FISHEYE", 8},  {"FULL_OPENCV", 12},          {"FOV", 5},
    {"SIMPLE_RADIAL_FISHEYE", 4}, {"RADIAL_FISHEYE", 5}, {"THIN_PRISM_FISHEYE", 12},
};
constexpr int kModelCount = int(sizeof(kModels) / sizeof(kModels[0]));
constexpr int kSupported = 5;  // ids 0..4
}  // namespace

const char* colmap_model_name(int id) { return id >= 0 && id < kModelCount ? kModels[id].name : ""; }
int colmap_param_count(int id) { return id >= 0 && id < kModelCount ? kModels[id].params : -1; }

namespace colmap_detail {

ColmapModel supported_model(int id, uint32_t camera_id, const std::string& name, const std::string& where) {
  if (id < 0 || id >= kModelCount)
    throw Error(name, where + ": camera " + std::to_string(camera_id) + " has unknown camera model id " +
                          std::to_string(id));
  if (id >= kSupported)
    throw Error(name, where + ": camera " + std::to_string(camera_id) + " uses camera model " + kModels[id].name +
                          " (id " + std::to_string(id) +
                          "), which is not supported (supported: SIMPLE_PINHOLE, PINHOLE, SIMPLE_RADIAL, RADIAL, OPENCV)");
  return ColmapModel(id);
}

int model_id_from_name(std::string_view model, uint32_t camera_id, const std::string& name, const std::string& where) {
  for (int i = 0; i < kModelCount; ++i)
    if (model == kModels[i].name) return i;
  throw Error(name, where + ": camera " + std::to_string(camera_id) + " has unknown camera model '" +
                        std::string(model) + "'");
}

void check_camera(const ColmapCamera& c, const std::string& name, const std::string& where) {
  const std::string cam = where + ": camera " + std::to_string(c.id);
  if (c.width == 0 || c.height == 0 || c.width > (1u << 20) || c.height > (1u << 20))
    throw Error(name, cam + " has an invalid image size " + std::to_string(c.width) + "x" + std::to_string(c.height));
  for (double p : c.params)
    if (!std::isfinite(p)) throw Error(name, cam + " has a non-finite parameter");
  const int focal_count = (c.model == ColmapModel::Pinhole || c.model == ColmapModel::OpenCV) ? 2 : 1;
  for (int i = 0; i < focal_count; ++i)
    if (!(c.params[i] > 0)) throw Error(name, cam + " has a non-positive focal length");
}

void check_image(const ColmapImage& im, const std::string& name, const std::string& where) {
  const std::string img = where + ": image " + std::to_string(im.id) + " ('" + im.name + "')";
  if (im.name.empty()) throw Error(name, where + ": image " + std::to_string(im.id) + " has an empty name");
  double n2 = 0;
  for (double q : im.qvec) {
    if (!std::isfinite(q)) throw Error(name, img + " has a non-finite rotation");
    n2 += q * q;
  }
  for (double t : im.tvec)
    if (!std::isfinite(t)) throw Error(name, img + " has a non-finite translation");
  if (n2 < 1e-12) throw Error(name, img + " has a zero rotation quaternion");
}

}  // namespace colmap_detail
}  // namespace goris
