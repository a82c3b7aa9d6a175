#pragma once
// Byte-level reader of NeRF-style transforms*.json files (NeRF-synthetic and instant-ngp), without any
// file-system access, so that it can be fuzzed. Intrinsics may be given once for the file and overridden
// per frame (instant-ngp allows both).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace goris {

struct TransformsIntrinsics {
  std::optional<double> camera_angle_x, camera_angle_y;  // radians, full field of view
  std::optional<double> fl_x, fl_y, cx, cy;              // pixels
  std::optional<double> k1, k2, k3, p1, p2;
  std::optional<int> w, h;

  // Every field that `over` sets replaces this one's.
  TransformsIntrinsics overridden_by(const TransformsIntrinsics& over) const;
};

struct TransformsFrame {
  std::string file_path;  // as written, relative to the json's folder, maybe without extension
  glm::dmat4 c2w{1.0};    // camera-to-world in OpenGL/Blender camera axes (x right, y up, z back)
  TransformsIntrinsics intrinsics;  // per-frame overrides (usually empty)
};

struct TransformsFile {
  TransformsIntrinsics intrinsics;
  std::vector<TransformsFrame> frames;
};

// Throws goris::Error(name_for_errors, ...) for malformed JSON (with nlohmann's byte position), missing
// or mistyped keys, non-finite numbers, matrices that are not 4x4 (or 3x4) rigid transforms, fisheye
// models.
TransformsFile parse_transforms_json(const uint8_t* bytes, size_t n, const std::string& name_for_errors);
TransformsFile load_transforms_json(const std::filesystem::path& path);

}  // namespace goris
