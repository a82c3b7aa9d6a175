#pragma once
// Writes tiny COLMAP sparse models in both of COLMAP's formats (for the loader tests).
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "core/io/loaders/colmap_model.h"
#include "tests/unit/io_test_util.h"

namespace goris::test {

class BinWriter {
 public:
  template <class T>
  BinWriter& put(T v) {
    const size_t at = bytes.size();
    bytes.resize(at + sizeof(T));
    std::memcpy(bytes.data() + at, &v, sizeof(T));
    return *this;
  }
  BinWriter& str(const std::string& s) {
    bytes.insert(bytes.end(), s.begin(), s.end());
    bytes.push_back(0);
    return *this;
  }
  std::vector<uint8_t> bytes;
};

inline std::vector<uint8_t> colmap_cameras_bin(const std::vector<ColmapCamera>& cams) {
  BinWriter w;
  w.put<uint64_t>(cams.size());
  for (const auto& c : cams) {
    w.put<uint32_t>(c.id).put<int32_t>(int32_t(c.model)).put<uint64_t>(c.width).put<uint64_t>(c.height);
    for (double p : c.params) w.put(p);
  }
  return w.bytes;
}

// Each image gets `points2d` 2D points (x, y, point3D id -1).
inline std::vector<uint8_t> colmap_images_bin(const std::vector<ColmapImage>& images, int points2d = 2) {
  BinWriter w;
  w.put<uint64_t>(images.size());
  for (const auto& im : images) {
    w.put<uint32_t>(im.id);
    for (double q : im.qvec) w.put(q);
    for (double t : im.tvec) w.put(t);
    w.put<uint32_t>(im.camera_id).str(im.name).put<uint64_t>(uint64_t(points2d));
    for (int i = 0; i < points2d; ++i) w.put(1.5 * i).put(2.5 * i).put<int64_t>(-1);
  }
  return w.bytes;
}

inline std::vector<uint8_t> colmap_points_bin(const std::vector<ColmapPoint>& points) {
  BinWriter w;
  w.put<uint64_t>(points.size());
  for (const auto& p : points) {
    w.put<uint64_t>(p.id);
    for (double v : p.xyz) w.put(v);
    for (uint8_t c : p.rgb) w.put(c);
    w.put(0.5).put<uint64_t>(2).put<int32_t>(1).put<int32_t>(0).put<int32_t>(2).put<int32_t>(1);  // error, track
  }
  return w.bytes;
}

inline std::string num(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

inline std::string colmap_cameras_txt(const std::vector<ColmapCamera>& cams) {
  std::string s = "# Camera list with one line of data per camera:\n#   CAMERA_ID, MODEL, WIDTH, HEIGHT, PARAMS[]\n";
  for (const auto& c : cams) {
    s += std::to_string(c.id) + " " + colmap_model_name(int(c.model)) + " " + std::to_string(c.width) + " " +
         std::to_string(c.height);
    for (double p : c.params) s += " " + num(p);
    s += "\n";
  }
  return s;
}

inline std::string colmap_images_txt(const std::vector<ColmapImage>& images) {
  std::string s = "# Image list with two lines of data per image:\n";
  for (size_t i = 0; i < images.size(); ++i) {
    const auto& im = images[i];
    s += std::to_string(im.id);
    for (double q : im.qvec) s += " " + num(q);
    for (double t : im.tvec) s += " " + num(t);
    s += " " + std::to_string(im.camera_id) + " " + im.name + "\n";
    s += i % 2 ? "\n" : "0 0 -1 1.5 2.5 -1\n";  // an empty points line and a non-empty one
  }
  return s;
}

inline std::string colmap_points_txt(const std::vector<ColmapPoint>& points) {
  std::string s = "# 3D point list\n";
  for (const auto& p : points) {
    s += std::to_string(p.id);
    for (double v : p.xyz) s += " " + num(v);
    for (uint8_t c : p.rgb) s += " " + std::to_string(int(c));
    s += " 0.5 1 0 2 1\n";
  }
  return s;
}

// A sparse model in `sparse_dir` in one format.
inline void write_colmap_model(const std::filesystem::path& sparse_dir, const ColmapSparseModel& m, bool binary) {
  if (binary) {
    write_bytes(sparse_dir / "cameras.bin", colmap_cameras_bin(m.cameras));
    write_bytes(sparse_dir / "images.bin", colmap_images_bin(m.images));
    write_bytes(sparse_dir / "points3D.bin", colmap_points_bin(m.points));
  } else {
    write_text(sparse_dir / "cameras.txt", colmap_cameras_txt(m.cameras));
    write_text(sparse_dir / "images.txt", colmap_images_txt(m.images));
    write_text(sparse_dir / "points3D.txt", colmap_points_txt(m.points));
  }
}

inline ColmapCamera colmap_camera(uint32_t id, ColmapModel model, uint64_t w, uint64_t h, std::vector<double> params) {
  ColmapCamera c;
  c.id = id;
  c.model = model;
  c.width = w;
  c.height = h;
  c.params = std::move(params);
  return c;
}

inline ColmapImage colmap_image(uint32_t id, uint32_t camera_id, const std::string& name, std::vector<double> q,
                                std::vector<double> t) {
  ColmapImage im;
  im.id = id;
  im.camera_id = camera_id;
  im.name = name;
  for (int i = 0; i < 4; ++i) im.qvec[i] = q[i];
  for (int i = 0; i < 3; ++i) im.tvec[i] = t[i];
  return im;
}

}  // namespace goris::test
