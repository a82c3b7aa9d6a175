#include "core/io/loaders/transforms_json.h"

#include <cmath>

#include <nlohmann/json.hpp>

#include "core/io/file_bytes.h"
#include "core/util/error.h"

namespace goris {
namespace {

constexpr double kMinFieldOfView = 0.1 * M_PI / 180, kMaxFieldOfView = 175 * M_PI / 180;  // radians

using nlohmann::json;

class Reader {
 public:
  explicit Reader(const std::string& name) : name_(name) {}

  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw Error(name_, where.empty() ? what : where + ": " + what);
  }

  std::optional<double> number(const json& obj, const char* key, const std::string& where) const {
    auto it = obj.find(key);
    if (it == obj.end() || it->is_null()) return std::nullopt;
    if (!it->is_number()) fail(where, std::string("'") + key + "' must be a number");
    const double v = it->get<double>();
    if (!std::isfinite(v)) fail(where, std::string("'") + key + "' is not finite");
    return v;
  }

  std::optional<int> size(const json& obj, const char* key, const std::string& where) const {
    auto v = number(obj, key, where);
    if (!v) return std::nullopt;
    if (*v < 1 || *v > (1 << 20) || *v != std::floor(*v))
      fail(where, std::string("'") + key + "' must be a positive whole number of pixels");
    return int(*v);
  }

  TransformsIntrinsics intrinsics(const json& obj, const std::string& where) const {
    if (auto it = obj.find("camera_model"); it != obj.end()) {
      if (!it->is_string()) fail(where, "'camera_model' must be a string");
      const auto m = it->get<std::string>();
      if (m != "OPENCV" && m != "PINHOLE" && m != "SIMPLE_PINHOLE")
        fail(where, "camera_model '" + m + "' is not supported (pinhole with OpenCV distortion only)");
    }
    if (auto it = obj.find("is_fisheye"); it != obj.end() && it->is_boolean() && it->get<bool>())
      fail(where, "fisheye cameras are not supported");
    TransformsIntrinsics in;
    in.camera_angle_x = number(obj, "camera_angle_x", where);
    in.camera_angle_y = number(obj, "camera_angle_y", where);
    in.fl_x = number(obj, "fl_x", where);
    in.fl_y = number(obj, "fl_y", where);
    in.cx = number(obj, "cx", where);
    in.cy = number(obj, "cy", where);
    in.k1 = number(obj, "k1", where);
    in.k2 = number(obj, "k2", where);
    in.k3 = number(obj, "k3", where);
    in.p1 = number(obj, "p1", where);
    in.p2 = number(obj, "p2", where);
    in.w = size(obj, "w", where);
    in.h = size(obj, "h", where);
    for (const char* k : {"camera_angle_x", "camera_angle_y"}) {
      auto v = number(obj, k, where);
      // Between 0.1 and 175 degrees: outside, the focal length is absurd (1e-30 rad gives fx = 1e32, pi
      // gives fx = 0) and the renders meaningless.
      if (v && !(*v >= kMinFieldOfView && *v <= kMaxFieldOfView))
        fail(where, std::string("'") + k + "' is " + std::to_string(*v) + " radians (" +
                        std::to_string(*v * 180 / M_PI) + " degrees): a field of view must lie between 0.1 and 175 degrees");
    }
    for (const char* k : {"fl_x", "fl_y"}) {
      auto v = number(obj, k, where);
      if (v && *v <= 0) fail(where, std::string("'") + k + "' must be positive");
    }
    return in;
  }

  glm::dmat4 matrix(const json& frame, const std::string& where) const {
    auto it = frame.find("transform_matrix");
    if (it == frame.end()) fail(where, "no 'transform_matrix'");
    const json& m = *it;
    if (!m.is_array() || (m.size() != 4 && m.size() != 3))
      fail(where, "'transform_matrix' must be a 4x4 (or 3x4) array of numbers");
    glm::dmat4 c2w(1.0);
    for (size_t r = 0; r < m.size(); ++r) {
      if (!m[r].is_array() || m[r].size() != 4) fail(where, "'transform_matrix' must be a 4x4 (or 3x4) array of numbers");
      for (size_t c = 0; c < 4; ++c) {
        if (!m[r][c].is_number()) fail(where, "'transform_matrix' must contain numbers only");
        const double v = m[r][c].get<double>();
        if (!std::isfinite(v)) fail(where, "'transform_matrix' has a non-finite value");
        c2w[c][r] = v;  // glm is column-major: [column][row]
      }
    }
    if (m.size() == 4) {
      const glm::dvec4 last(c2w[0][3], c2w[1][3], c2w[2][3], c2w[3][3]);
      if (glm::length(last - glm::dvec4(0, 0, 0, 1)) > 1e-6)
        fail(where, "'transform_matrix' last row must be 0 0 0 1");
    }
    return c2w;
  }

 private:
  const std::string& name_;
};

}  // namespace

TransformsIntrinsics TransformsIntrinsics::overridden_by(const TransformsIntrinsics& o) const {
  TransformsIntrinsics r = *this;
  auto take = [](auto& dst, const auto& src) {
    if (src) dst = src;
  };
  take(r.camera_angle_x, o.camera_angle_x);
  take(r.camera_angle_y, o.camera_angle_y);
  take(r.fl_x, o.fl_x);
  take(r.fl_y, o.fl_y);
  take(r.cx, o.cx);
  take(r.cy, o.cy);
  take(r.k1, o.k1);
  take(r.k2, o.k2);
  take(r.k3, o.k3);
  take(r.p1, o.p1);
  take(r.p2, o.p2);
  take(r.w, o.w);
  take(r.h, o.h);
  return r;
}

TransformsFile parse_transforms_json(const uint8_t* bytes, size_t n, const std::string& name) {
  json doc;
  try {
    doc = json::parse(bytes, bytes + n);
  } catch (const json::parse_error& e) {
    throw Error(name, "malformed JSON at byte " + std::to_string(e.byte) + ": " + e.what());
  } catch (const json::exception& e) {  // e.g. a number too large for a double
    throw Error(name, std::string("malformed JSON: ") + e.what());
  }
  Reader rd(name);
  if (!doc.is_object()) rd.fail("", "expected a JSON object at the top level");
  TransformsFile tf;
  tf.intrinsics = rd.intrinsics(doc, "");
  auto fit = doc.find("frames");
  if (fit == doc.end()) rd.fail("", "no 'frames' array");
  if (!fit->is_array()) rd.fail("", "'frames' must be an array");
  size_t index = 0;
  for (const json& f : *fit) {
    const std::string where = "frame " + std::to_string(index++);
    if (!f.is_object()) rd.fail(where, "must be an object");
    TransformsFrame fr;
    auto p = f.find("file_path");
    if (p == f.end()) rd.fail(where, "no 'file_path'");
    if (!p->is_string() || p->get<std::string>().empty()) rd.fail(where, "'file_path' must be a non-empty string");
    fr.file_path = p->get<std::string>();
    fr.c2w = rd.matrix(f, where + " ('" + fr.file_path + "')");
    fr.intrinsics = rd.intrinsics(f, where + " ('" + fr.file_path + "')");
    tf.frames.push_back(std::move(fr));
  }
  return tf;
}

TransformsFile load_transforms_json(const std::filesystem::path& path) {
  const auto bytes = read_file_bytes(path);
  return parse_transforms_json(bytes.data(), bytes.size(), path.string());
}

}  // namespace goris
