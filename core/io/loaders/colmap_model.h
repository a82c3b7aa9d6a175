#pragma once
// COLMAP sparse models (cameras, images, points3D) in COLMAP's binary and text formats, parsed from
// memory without file-system access so that the parsers can be fuzzed. Poses are COLMAP's: world-to-
// camera, OpenCV axes, quaternion (w, x, y, z) — the engine's convention already.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace goris {

// COLMAP's model ids. Only the first five are supported; the parsers reject the others by name.
enum class ColmapModel : int {
  SimplePinhole = 0,  // f, cx, cy
  Pinhole = 1,        // fx, fy, cx, cy
  SimpleRadial = 2,   // f, cx, cy, k
  Radial = 3,         // f, cx, cy, k1, k2
  OpenCV = 4,         // fx, fy, cx, cy, k1, k2, p1, p2
};

struct ColmapCamera {
  uint32_t id = 0;
  ColmapModel model = ColmapModel::Pinhole;
  uint64_t width = 0, height = 0;
  std::vector<double> params;
};

struct ColmapImage {
  uint32_t id = 0;
  double qvec[4] = {1, 0, 0, 0};  // w, x, y, z
  double tvec[3] = {0, 0, 0};
  uint32_t camera_id = 0;
  std::string name;  // path relative to the images folder
};

struct ColmapPoint {
  uint64_t id = 0;
  double xyz[3] = {0, 0, 0};
  uint8_t rgb[3] = {0, 0, 0};
};

struct ColmapSparseModel {
  std::vector<ColmapCamera> cameras;
  std::vector<ColmapImage> images;
  std::vector<ColmapPoint> points;
};

// "PINHOLE"... for a model id of COLMAP (also the unsupported ones); "" for ids COLMAP does not define.
const char* colmap_model_name(int model_id);
// Number of parameters of a COLMAP model id, -1 for ids COLMAP does not define.
int colmap_param_count(int model_id);

// Each throws goris::Error(name_for_errors, ...) naming the byte offset (binary) or line (text) of the
// problem: truncation, counts that do not match the data, unknown or unsupported camera models,
// duplicate ids, non-finite values.
std::vector<ColmapCamera> parse_colmap_cameras_bin(const uint8_t* data, size_t size, const std::string& name_for_errors);
std::vector<ColmapImage> parse_colmap_images_bin(const uint8_t* data, size_t size, const std::string& name_for_errors);
std::vector<ColmapPoint> parse_colmap_points3d_bin(const uint8_t* data, size_t size, const std::string& name_for_errors);
std::vector<ColmapCamera> parse_colmap_cameras_txt(std::string_view text, const std::string& name_for_errors);
std::vector<ColmapImage> parse_colmap_images_txt(std::string_view text, const std::string& name_for_errors);
std::vector<ColmapPoint> parse_colmap_points3d_txt(std::string_view text, const std::string& name_for_errors);

// Reads {cameras,images,points3D}.bin from `sparse_dir`, or the .txt files when there are no .bin files,
// and checks that every image's camera exists. points3D is optional (empty when absent). `binary` tells
// which was read.
ColmapSparseModel read_colmap_model(const std::filesystem::path& sparse_dir, bool* binary = nullptr);

}  // namespace goris
