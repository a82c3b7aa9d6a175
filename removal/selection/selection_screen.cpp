#include "removal/selection/selection_screen.h"

#include <cmath>
#include <sstream>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/util/error.h"

namespace goris {

const char* through_name(Through t) { return t == Through::Visible ? "visible" : "all"; }

Through through_from_name(const std::string& name) {
  if (name == "visible") return Through::Visible;
  if (name == "all") return Through::All;
  throw Error("--through", "'" + name + "' is neither visible nor all");
}

ScreenPolygon rect_polygon(const glm::vec2& a, const glm::vec2& b) {
  const glm::vec2 lo = glm::min(a, b), hi = glm::max(a, b);
  return {lo, {hi.x, lo.y}, hi, {lo.x, hi.y}};
}

ScreenPolygon disc_polygon(const glm::vec2& c, float r) {
  ScreenPolygon p;
  constexpr int kSides = 32;
  for (int k = 0; k < kSides; ++k) {
    const float a = 6.28318530718f * float(k) / float(kSides);
    p.push_back(c + r * glm::vec2(std::cos(a), std::sin(a)));
  }
  return p;
}

std::vector<float> parse_number_list(const std::string& text, const std::string& what) {
  std::vector<float> v;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    std::size_t used = 0;
    float f = 0.0f;
    try {
      f = std::stof(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != item.size() || item.empty() || !std::isfinite(f))
      throw Error(what, "'" + item + "' in '" + text + "' is not a number");
    v.push_back(f);
  }
  if (v.empty() || text.back() == ',') throw Error(what, "'" + text + "' is not a list of numbers a,b,c,...");
  return v;
}

ScreenPolygon parse_polygon(const std::string& text, const std::string& what) {
  const std::vector<float> v = parse_number_list(text, what);
  if (v.size() % 2 != 0) throw Error(what, "'" + text + "' has an odd count of numbers (x,y pairs expected)");
  ScreenPolygon p;
  for (std::size_t i = 0; i + 1 < v.size(); i += 2) p.push_back({v[i], v[i + 1]});
  if (p.size() < 3) throw Error(what, "'" + text + "' has fewer than three points");
  return p;
}

bool inside_polygon(const ScreenPolygon& poly, const glm::vec2& p) {
  bool in = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const glm::vec2 a = poly[i], b = poly[j];
    if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x) in = !in;
  }
  return in;
}

std::vector<std::int32_t> centre_pixels(const std::vector<glm::vec3>& positions, const Camera& cam, float near_plane) {
  std::vector<std::int32_t> px(positions.size(), -1);
  const int w = cam.width, h = cam.height;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, positions.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i != r.end(); ++i) {
                        const glm::vec3 pc = cam.to_camera(positions[i]);
                        if (!(pc.z > near_plane)) continue;
                        const glm::vec2 uv = cam.project_camera(pc);
                        if (!(uv.x >= 0.0f && uv.y >= 0.0f && uv.x < float(w) && uv.y < float(h))) continue;
                        px[i] = std::int32_t(int(uv.y) * w + int(uv.x));
                      }
                    });
  return px;
}

SelectionMask select_in_polygon(const std::vector<glm::vec3>& positions, const Camera& cam,
                                const ScreenPolygon& polygon, float near_plane,
                                const std::vector<std::uint8_t>* visible) {
  if (polygon.size() < 3) throw Error("selection", "a screen region needs at least three vertices");
  if (visible && visible->size() != positions.size())
    throw Error("selection", "visibility of " + std::to_string(visible->size()) + " Gaussians for " +
                                 std::to_string(positions.size()));
  SelectionMask out(positions.size(), 0);
  for (std::size_t i = 0; i < positions.size(); ++i) {
    if (visible && !(*visible)[i]) continue;
    const glm::vec3 pc = cam.to_camera(positions[i]);
    if (!(pc.z > near_plane)) continue;
    out[i] = inside_polygon(polygon, cam.project_camera(pc));
  }
  return out;
}

}  // namespace goris
