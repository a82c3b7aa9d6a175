// COLMAP's binary sparse model (little-endian; colmap/src/base/reconstruction.cc WriteCamerasBinary etc.).
#include <cstring>
#include <unordered_set>

#include "core/io/loaders/colmap_model.h"
#include "core/io/loaders/colmap_parse_util.h"

namespace goris {
namespace {
using namespace colmap_detail;

// Bounds-checked little-endian reader whose errors name the file and the byte offset.
class ByteReader {
 public:
  ByteReader(const uint8_t* data, size_t size, const std::string& name) : data_(data), size_(size), name_(name) {}

  template <class T>
  T read(const char* what) {
    if (size_ - off_ < sizeof(T)) truncated(what, sizeof(T));
    T v;
    std::memcpy(&v, data_ + off_, sizeof(T));
    off_ += sizeof(T);
    return v;
  }
  std::string read_cstring(const char* what) {
    const void* end = std::memchr(data_ + off_, 0, size_ - off_);
    if (!end) truncated(what, size_ - off_ + 1);
    const size_t len = static_cast<const uint8_t*>(end) - (data_ + off_);
    std::string s(reinterpret_cast<const char*>(data_ + off_), len);
    off_ += len + 1;
    return s;
  }
  // Skips `count` records of `record_size` bytes, checking first that they are all there.
  void skip(uint64_t count, size_t record_size, const std::string& what) {
    if (count > (size_ - off_) / record_size)
      throw Error(name_, "truncated at byte offset " + std::to_string(off_) + ": " + what + " declares " +
                             std::to_string(count) + " entries of " + std::to_string(record_size) +
                             " bytes, but only " + std::to_string(size_ - off_) + " bytes remain");
    off_ += size_t(count) * record_size;
  }
  size_t offset() const { return off_; }
  std::string where() const { return "byte offset " + std::to_string(off_); }
  void expect_end(const char* what) const {
    if (off_ != size_)
      throw Error(name_, "inconsistent: " + std::to_string(size_ - off_) + " bytes after the last " + what +
                             " at byte offset " + std::to_string(off_) + " (the count in the file header is wrong?)");
  }

 private:
  [[noreturn]] void truncated(const char* what, size_t need) const {
    throw Error(name_, "truncated at byte offset " + std::to_string(off_) + " while reading " + what + " (needs " +
                           std::to_string(need) + " bytes, " + std::to_string(size_ - off_) + " remain)");
  }
  const uint8_t* data_;
  size_t size_;
  const std::string& name_;
  size_t off_ = 0;
};

}  // namespace

std::vector<ColmapCamera> parse_colmap_cameras_bin(const uint8_t* data, size_t size, const std::string& name) {
  ByteReader rd(data, size, name);
  const uint64_t count = rd.read<uint64_t>("the number of cameras");
  std::vector<ColmapCamera> cams;
  std::unordered_set<uint32_t> ids;
  for (uint64_t i = 0; i < count; ++i) {
    const std::string where = rd.where();
    ColmapCamera c;
    c.id = rd.read<uint32_t>("a camera id");
    const int model_id = rd.read<int32_t>("a camera model id");
    c.model = supported_model(model_id, c.id, name, where);
    c.width = rd.read<uint64_t>("a camera width");
    c.height = rd.read<uint64_t>("a camera height");
    c.params.resize(size_t(colmap_param_count(model_id)));
    for (double& p : c.params) p = rd.read<double>("a camera parameter");
    check_camera(c, name, where);
    if (!ids.insert(c.id).second) throw Error(name, where + ": duplicate camera id " + std::to_string(c.id));
    cams.push_back(std::move(c));
  }
  rd.expect_end("camera");
  return cams;
}

std::vector<ColmapImage> parse_colmap_images_bin(const uint8_t* data, size_t size, const std::string& name) {
  ByteReader rd(data, size, name);
  const uint64_t count = rd.read<uint64_t>("the number of images");
  std::vector<ColmapImage> images;
  std::unordered_set<uint32_t> ids;
  for (uint64_t i = 0; i < count; ++i) {
    const std::string where = rd.where();
    ColmapImage im;
    im.id = rd.read<uint32_t>("an image id");
    for (double& q : im.qvec) q = rd.read<double>("an image rotation");
    for (double& t : im.tvec) t = rd.read<double>("an image translation");
    im.camera_id = rd.read<uint32_t>("an image's camera id");
    im.name = rd.read_cstring("an image name");
    const uint64_t n2d = rd.read<uint64_t>("the number of 2D points");
    rd.skip(n2d, 24, "image " + std::to_string(im.id) + " ('" + im.name + "')");  // x, y (double), point3D id (int64)
    check_image(im, name, where);
    if (!ids.insert(im.id).second) throw Error(name, where + ": duplicate image id " + std::to_string(im.id));
    images.push_back(std::move(im));
  }
  rd.expect_end("image");
  return images;
}

std::vector<ColmapPoint> parse_colmap_points3d_bin(const uint8_t* data, size_t size, const std::string& name) {
  ByteReader rd(data, size, name);
  const uint64_t count = rd.read<uint64_t>("the number of points");
  // Each point takes at least 43 bytes; do not trust `count` for the reservation.
  std::vector<ColmapPoint> points;
  points.reserve(size_t(std::min<uint64_t>(count, (size - rd.offset()) / 43)));
  for (uint64_t i = 0; i < count; ++i) {
    const size_t start = rd.offset();  // no per-point string: files hold millions of points
    ColmapPoint p;
    p.id = rd.read<uint64_t>("a point id");
    for (double& v : p.xyz) v = rd.read<double>("a point position");
    for (uint8_t& c : p.rgb) c = rd.read<uint8_t>("a point colour");
    rd.read<double>("a point error");
    const uint64_t track = rd.read<uint64_t>("a point's track length");
    rd.skip(track, 8, "point " + std::to_string(p.id) + "'s track");  // image id, point2D index (int32 each)
    check_point(p, name, [&] { return "byte offset " + std::to_string(start); });
    points.push_back(p);
  }
  rd.expect_end("point");
  return points;
}

}  // namespace goris
