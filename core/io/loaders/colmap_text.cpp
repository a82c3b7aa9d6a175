// COLMAP's text sparse model: '#' comment lines, one camera / point per line, two lines per image
// (the pose line, then its 2D points, which may be an empty line).
#include <charconv>
#include <unordered_set>

#include "core/io/loaders/colmap_model.h"
#include "core/io/loaders/colmap_parse_util.h"

namespace goris {
namespace {
using namespace colmap_detail;

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

std::string_view trim(std::string_view s) {
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

class LineReader {
 public:
  LineReader(std::string_view text, const std::string& name) : text_(text), name_(name) {}
  // The next line (without '\n'); false at the end of the text.
  bool next(std::string_view& line) {
    if (pos_ >= text_.size()) return false;
    size_t end = text_.find('\n', pos_);
    if (end == std::string_view::npos) end = text_.size();
    line = text_.substr(pos_, end - pos_);
    pos_ = end + 1;
    ++line_no_;
    return true;
  }
  // The next line that is neither empty nor a comment.
  bool next_record(std::string_view& line) {
    while (next(line)) {
      line = trim(line);
      if (!line.empty() && line.front() != '#') return true;
    }
    return false;
  }
  std::string where() const { return "line " + std::to_string(line_no_); }
  const std::string& name() const { return name_; }

 private:
  std::string_view text_;
  const std::string& name_;
  size_t pos_ = 0;
  size_t line_no_ = 0;
};

// Whitespace-separated fields of one line.
class Fields {
 public:
  Fields(std::string_view line, const LineReader& lr) : rest_(line), lr_(lr) {}

  std::string_view word(const char* what) {
    rest_ = trim(rest_);
    if (rest_.empty()) fail(std::string("missing ") + what);
    size_t end = 0;
    while (end < rest_.size() && !is_space(rest_[end])) ++end;
    std::string_view w = rest_.substr(0, end);
    rest_.remove_prefix(end);
    return w;
  }
  template <class T>
  T number(const char* what) {
    const std::string_view w = word(what);
    T v{};
    auto [p, ec] = std::from_chars(w.data(), w.data() + w.size(), v);
    if (ec != std::errc() || p != w.data() + w.size())
      fail(std::string("expected a number for ") + what + ", got '" + std::string(w) + "'");
    return v;
  }
  std::string_view rest() const { return trim(rest_); }
  [[noreturn]] void fail(const std::string& what) const { throw Error(lr_.name(), lr_.where() + ": " + what); }

 private:
  std::string_view rest_;
  const LineReader& lr_;
};

}  // namespace

std::vector<ColmapCamera> parse_colmap_cameras_txt(std::string_view text, const std::string& name) {
  LineReader lr(text, name);
  std::vector<ColmapCamera> cams;
  std::unordered_set<uint32_t> ids;
  std::string_view line;
  while (lr.next_record(line)) {
    Fields f(line, lr);
    ColmapCamera c;
    c.id = f.number<uint32_t>("CAMERA_ID");
    const int model_id = model_id_from_name(f.word("MODEL"), c.id, name, lr.where());
    c.model = supported_model(model_id, c.id, name, lr.where());
    c.width = f.number<uint64_t>("WIDTH");
    c.height = f.number<uint64_t>("HEIGHT");
    c.params.resize(size_t(colmap_param_count(model_id)));
    for (double& p : c.params) p = f.number<double>("a camera parameter");
    if (!f.rest().empty()) f.fail(std::string("too many parameters for model ") + colmap_model_name(model_id));
    check_camera(c, name, lr.where());
    if (!ids.insert(c.id).second) f.fail("duplicate camera id " + std::to_string(c.id));
    cams.push_back(std::move(c));
  }
  return cams;
}

std::vector<ColmapImage> parse_colmap_images_txt(std::string_view text, const std::string& name) {
  LineReader lr(text, name);
  std::vector<ColmapImage> images;
  std::unordered_set<uint32_t> ids;
  std::string_view line;
  while (lr.next_record(line)) {
    Fields f(line, lr);
    ColmapImage im;
    im.id = f.number<uint32_t>("IMAGE_ID");
    for (double& q : im.qvec) q = f.number<double>("a rotation component (QW QX QY QZ)");
    for (double& t : im.tvec) t = f.number<double>("a translation component (TX TY TZ)");
    im.camera_id = f.number<uint32_t>("CAMERA_ID");
    im.name = std::string(f.rest());  // the rest of the line, so names may contain spaces
    if (im.name.empty()) f.fail("missing NAME");
    check_image(im, name, lr.where());
    if (!ids.insert(im.id).second) f.fail("duplicate image id " + std::to_string(im.id));
    images.push_back(std::move(im));
    // The 2D points line follows every image line (possibly empty); a model without them ends here.
    std::string_view points_line;
    if (!lr.next(points_line)) break;
    Fields pf(points_line, lr);
    size_t n = 0;
    while (!pf.rest().empty()) {
      pf.number<double>(n % 3 == 2 ? "POINT3D_ID" : "a 2D point coordinate");
      ++n;
    }
    if (n % 3 != 0)
      pf.fail("2D points must come as X Y POINT3D_ID triples (every image line is followed by its points line, "
              "which may be empty)");
  }
  return images;
}

std::vector<ColmapPoint> parse_colmap_points3d_txt(std::string_view text, const std::string& name) {
  LineReader lr(text, name);
  std::vector<ColmapPoint> points;
  std::string_view line;
  while (lr.next_record(line)) {
    Fields f(line, lr);
    ColmapPoint p;
    p.id = f.number<uint64_t>("POINT3D_ID");
    for (double& v : p.xyz) v = f.number<double>("a coordinate (X Y Z)");
    for (uint8_t& c : p.rgb) {
      const int v = f.number<int>("a colour component (R G B)");
      if (v < 0 || v > 255) f.fail("colour component " + std::to_string(v) + " is outside 0..255");
      c = uint8_t(v);
    }
    f.number<double>("ERROR");
    // TRACK[] (IMAGE_ID, POINT2D_IDX) pairs are not needed; they are not parsed.
    check_point(p, name, [&] { return lr.where(); });
    points.push_back(p);
  }
  return points;
}

}  // namespace goris
