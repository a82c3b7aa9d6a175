#include "train/setup/glossy_detection.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <random>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "core/compute/parallel_for.h"
#include "core/io/image.h"
#include "core/util/error.h"
#include "core/util/median.h"
#include "render/raster/rasterizer.h"
#include "train/run/train_setup.h"

namespace goris {

GlossyDetectionSettings GlossyDetectionSettings::from_config(const TrainConfig& config) {
  const IntrinsicSettings& in = config.intrinsic;
  GlossyDetectionSettings s;
  s.neighbours = in.detect_neighbours;
  s.threshold = in.detect_threshold;
  s.depth_tolerance = in.detect_depth_tolerance;
  s.search_radius = in.detect_search_radius;
  s.depth_window = in.detect_depth_window;
  s.morph_radius = in.detect_morph_radius;
  s.min_fraction = in.detect_fraction;
  s.work_width = in.detect_width;
  s.grow_planes = in.detect_plane_tolerance > 0;
  s.plane_tolerance = in.detect_plane_tolerance;
  s.mirror_world = in.detect_mirror_world;
  return s;
}

std::vector<int> nearest_views(const std::vector<Camera>& cameras, int i, int k) {
  std::vector<int> order;
  for (int j = 0; j < int(cameras.size()); ++j)
    if (j != i) order.push_back(j);
  const glm::vec3 d = cameras[size_t(i)].forward();
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return glm::dot(cameras[size_t(a)].forward(), d) > glm::dot(cameras[size_t(b)].forward(), d);
  });
  order.resize(std::min(order.size(), size_t(std::max(k, 0))));
  return order;
}

namespace {

// Bilinear sample of a planar channel at continuous pixel coordinates (centres at +0.5), clamped at the
// border.
float bilinear(const float* plane, int w, int h, float u, float v) {
  const float x = std::clamp(u - 0.5f, 0.0f, float(w - 1)), y = std::clamp(v - 0.5f, 0.0f, float(h - 1));
  const int x0 = std::min(int(x), w - 1), y0 = std::min(int(y), h - 1);
  const int x1 = std::min(x0 + 1, w - 1), y1 = std::min(y0 + 1, h - 1);
  const float fx = x - float(x0), fy = y - float(y0);
  const float a = plane[size_t(y0) * w + x0] * (1 - fx) + plane[size_t(y0) * w + x1] * fx;
  const float b = plane[size_t(y1) * w + x0] * (1 - fx) + plane[size_t(y1) * w + x1] * fx;
  return a * (1 - fy) + b * fy;
}

// Per channel, the darkest and brightest colour of a photo within a (2r+1)^2 window around each pixel
// (planar [3][H][W]): the colours a misregistration of up to r pixels could show.
struct ColourRange {
  std::vector<float> lo, hi;
};

ColourRange colour_range(const ConsistencyView& v, int r) {
  const int w = v.camera.width, h = v.camera.height;
  const size_t hw = size_t(w) * size_t(h);
  ColourRange out{std::vector<float>(3 * hw), std::vector<float>(3 * hw)};
  const cv::Mat box = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * r + 1, 2 * r + 1));
  for (int c = 0; c < 3; ++c) {
    const cv::Mat src(h, w, CV_32F, const_cast<float*>(v.image + c * hw));
    cv::Mat lo(h, w, CV_32F, out.lo.data() + c * hw), hi(h, w, CV_32F, out.hi.data() + c * hw);
    cv::erode(src, lo, box, cv::Point(-1, -1), 1, cv::BORDER_REPLICATE);
    cv::dilate(src, hi, box, cv::Point(-1, -1), 1, cv::BORDER_REPLICATE);
  }
  return out;
}

// How far the colour x (RGB) lies outside what view j shows around (u, v): mean over RGB of the distance
// to the window's colour range, 0 = explained.
float outside_range(const float x[3], const ColourRange& rj, const Camera& cj, glm::vec2 uv) {
  const size_t hwj = size_t(cj.width) * size_t(cj.height);
  float d = 0;
  for (int c = 0; c < 3; ++c) {
    const float lo = bilinear(rj.lo.data() + c * hwj, cj.width, cj.height, uv.x, uv.y);
    const float hi = bilinear(rj.hi.data() + c * hwj, cj.width, cj.height, uv.x, uv.y);
    d += std::max({0.0f, x[c] - hi, lo - x[c]});
  }
  return d / 3.0f;
}

bool inside(const Camera& c, glm::vec2 uv) {
  return uv.x >= 0 && uv.y >= 0 && uv.x < float(c.width) && uv.y < float(c.height);
}

// The nearest and farthest covered depth of view i within `g` pixels of p (g = 0: p's own).
glm::vec2 depth_range(const ConsistencyView& v, size_t p, int g) {
  const int w = v.camera.width, h = v.camera.height;
  const int x = int(p % size_t(w)), y = int(p / size_t(w));
  glm::vec2 r(v.depth[p], v.depth[p]);
  for (int yy = std::max(0, y - g); yy <= std::min(h - 1, y + g); ++yy)
    for (int xx = std::max(0, x - g); xx <= std::min(w - 1, x + g); ++xx) {
      const size_t q = size_t(yy) * size_t(w) + size_t(xx);
      const float z = v.depth[q];
      if (!(v.alpha[q] > 0.5f) || !(z > 0) || !std::isfinite(z)) continue;
      r.x = std::min(r.x, z), r.y = std::max(r.y, z);
    }
  return r;
}

// Per-pixel scores of view i against its neighbours (-1 = fewer than min_visible of them see the point).
std::vector<float> score_view(const std::vector<ConsistencyView>& views, const std::vector<ColourRange>& ranges, int i,
                              const std::vector<int>& nbrs, const GlossyDetectionSettings& s) {
  const ConsistencyView& vi = views[size_t(i)];
  const Camera& ci = vi.camera;
  const int w = ci.width, h = ci.height;
  const size_t hw = size_t(w) * size_t(h);
  const glm::mat3 rt = glm::transpose(ci.R);
  std::vector<float> score(hw, -1.0f);
  parallel_for(Device::CPU, hw, [&](size_t p) {
    if (!(vi.alpha[p] > 0.5f)) return;
    const float z = vi.depth[p];
    if (!(z > 0) || !std::isfinite(z)) return;
    const float u = float(p % size_t(w)) + 0.5f, v = float(p / size_t(w)) + 0.5f;
    const glm::vec3 ray((u - ci.cx) / ci.fx, (v - ci.cy) / ci.fy, 1.0f);  // camera space, z = 1
    auto at_depth = [&](float zz) { return rt * (ray * zz - ci.t); };     // world point at camera z = zz
    const glm::vec3 x_world = at_depth(z);
    const float colour[3] = {vi.image[p], vi.image[hw + p], vi.image[2 * hw + p]};
    glm::vec2 zr(z, z);
    if (s.depth_window > 0) zr = depth_range(vi, p, s.depth_window) * glm::vec2(1 - s.depth_tolerance, 1 + s.depth_tolerance);
    std::array<float, 16> diffs{};
    int n = 0;
    for (const int j : nbrs) {
      const ConsistencyView& vj = views[size_t(j)];
      const Camera& cj = vj.camera;
      const glm::vec3 xc = cj.to_camera(x_world);
      if (!(xc.z > 0)) continue;
      const glm::vec2 uv = cj.project_camera(xc);
      if (!inside(cj, uv)) continue;
      // The nearest pixel of view j must see this surface point: covered, at the same depth.
      const size_t q = size_t(int(uv.y)) * size_t(cj.width) + size_t(int(uv.x));
      if (!(vj.alpha[q] > 0.5f) || !(std::abs(vj.depth[q] - xc.z) <= s.depth_tolerance * xc.z)) continue;
      float d = outside_range(colour, ranges[size_t(j)], cj, uv);
      if (d > 0 && s.depth_window > 0) {
        // Any depth the model is unsure between may be the true one: the best match along its epipolar
        // segment in view j, sampled every half pixel (at most 64 samples).
        const glm::vec3 a = cj.to_camera(at_depth(zr.x)), b = cj.to_camera(at_depth(zr.y));
        if (a.z > 0 && b.z > 0) {
          const float len = glm::length(cj.project_camera(b) - cj.project_camera(a));
          const int steps = std::clamp(int(std::ceil(2.0f * len)), 1, 64);
          for (int k = 0; k <= steps && d > 0; ++k) {
            const float zk = zr.x + (zr.y - zr.x) * float(k) / float(steps);
            const glm::vec3 xk = cj.to_camera(at_depth(zk));
            if (!(xk.z > 0)) continue;
            const glm::vec2 uk = cj.project_camera(xk);
            if (inside(cj, uk)) d = std::min(d, outside_range(colour, ranges[size_t(j)], cj, uk));
          }
        }
      }
      if (n < int(diffs.size())) diffs[size_t(n++)] = d;
    }
    if (n < std::max(s.min_visible, 1)) return;
    std::sort(diffs.begin(), diffs.begin() + n);
    score[p] = diffs[size_t((n - 1) / 2)];  // lower median: a pixel must differ in most views
  }, 64);
  return score;
}

// Opening then closing with a disc, restricted to the covered pixels.
void clean_mask(std::vector<std::uint8_t>& mask, const float* alpha, int w, int h, int radius) {
  if (radius > 0) {
    cv::Mat m(h, w, CV_8U, mask.data());
    const cv::Mat disc = cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * radius + 1, 2 * radius + 1));
    cv::morphologyEx(m, m, cv::MORPH_OPEN, disc);
    cv::morphologyEx(m, m, cv::MORPH_CLOSE, disc);
  }
  for (size_t p = 0; p < mask.size(); ++p) mask[p] = (mask[p] && alpha[p] > 0.5f) ? 1 : 0;
}

glm::vec3 surface_point(const ConsistencyView& v, size_t p) {
  const Camera& c = v.camera;
  const float z = v.depth[p];
  const float u = float(p % size_t(c.width)) + 0.5f, y = float(p / size_t(c.width)) + 0.5f;
  return glm::transpose(c.R) * (glm::vec3((u - c.cx) / c.fx * z, (y - c.cy) / c.fy * z, z) - c.t);
}

struct Plane {
  glm::vec3 n{0.0f};
  float d = 0;  // n . x + d = 0
  float distance(const glm::vec3& x) const { return std::abs(glm::dot(n, x) + d); }
};

// The planes that hold most of the detected points (RANSAC, one plane after another on the points left),
// with the distance tolerance used. Deterministic (fixed seed).
std::vector<Plane> fit_planes(std::vector<glm::vec3> pts, float tolerance, const GlossyDetectionSettings& s) {
  std::vector<Plane> planes;
  const size_t total = pts.size();
  std::mt19937 rng(12345);
  while (pts.size() >= size_t(s.plane_min_points) && planes.size() < 4) {
    std::uniform_int_distribution<size_t> pick(0, pts.size() - 1);
    Plane best;
    size_t best_count = 0;
    for (int it = 0; it < 300; ++it) {
      const glm::vec3 a = pts[pick(rng)], b = pts[pick(rng)], c = pts[pick(rng)];
      const glm::vec3 n = glm::cross(b - a, c - a);
      const float len = glm::length(n);
      if (!(len > 1e-12f)) continue;
      Plane pl{n / len, -glm::dot(n / len, a)};
      size_t count = 0;
      for (const glm::vec3& x : pts) count += pl.distance(x) <= tolerance;
      if (count > best_count) {
        best_count = count;
        best = pl;
      }
    }
    // A plane must hold most of the detections left (a curved glossy object has none), and a further
    // plane (the second mirror of a room) a real share of all of them, not a few specks on an object.
    if (double(best_count) < s.plane_min_share * double(pts.size()) ||
        (!planes.empty() && double(best_count) < 0.1 * double(total)))
      break;
    planes.push_back(best);
    std::vector<glm::vec3> rest;
    for (const glm::vec3& x : pts)
      if (best.distance(x) > tolerance) rest.push_back(x);
    pts = std::move(rest);
  }
  return planes;
}

// The share of the detections (all but those on the other planes found) that stand in front of a plane's
// surface: nearer to the camera that saw them than the surface's own thickness allows. The surface is the
// plane refitted (least squares) to `on`, every covered surface point within `tolerance` of it, its thickness the
// 90th percentile of their distances (at least a tenth of the tolerance). A planar reflector shows its reflections on its surface, or - in a
// radiance model - as virtual geometry behind it; when much of the view dependence sits on something
// standing in front of the plane (fur and a varnished plaque before a papered wall), the plane is a
// backdrop, not the reflector.
float evidence_in_front(const std::vector<ConsistencyView>& views, const std::vector<std::vector<std::uint8_t>>& detected,
                        const Plane& pl, const std::vector<glm::vec3>& on, const std::vector<Plane>& others,
                        float tolerance) {
  if (on.size() < 3) return 0.0f;
  glm::dvec3 centre(0.0);
  glm::dmat3 scatter(0.0);
  for (const glm::vec3& x : on) centre += glm::dvec3(x);
  centre /= double(on.size());
  for (const glm::vec3& x : on) scatter += glm::outerProduct(glm::dvec3(x) - centre, glm::dvec3(x) - centre);
  cv::Matx33d m;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m(r, c) = scatter[c][r];
  cv::Matx31d values;
  cv::Matx33d vectors;  // rows: eigenvectors, largest eigenvalue first
  cv::eigen(m, values, vectors);
  const glm::dvec3 n(vectors(2, 0), vectors(2, 1), vectors(2, 2));
  std::vector<double> spread;
  spread.reserve(on.size());
  for (const glm::vec3& x : on) spread.push_back(std::abs(glm::dot(n, glm::dvec3(x) - centre)));
  const size_t k90 = spread.size() * 9 / 10;
  std::nth_element(spread.begin(), spread.begin() + long(k90), spread.end());
  const double thickness = std::max(spread[k90], 0.1 * double(tolerance));  // an exact plane is not infinitely thin
  size_t held = 0, front = 0;
  for (size_t i = 0; i < views.size(); ++i) {
    const double eye_side = glm::dot(n, glm::dvec3(views[i].camera.center()) - centre);
    for (size_t p = 0; p < detected[i].size(); ++p) {
      if (!detected[i][p]) continue;
      const glm::vec3 x = surface_point(views[i], p);
      if (std::any_of(others.begin(), others.end(), [&](const Plane& o) { return o.distance(x) <= tolerance; })) continue;
      const double d = glm::dot(n, glm::dvec3(x) - centre);
      ++held;
      front += d * eye_side > 0 && std::abs(d) > thickness;
    }
  }
  return held > 0 ? float(double(front) / double(held)) : 0.0f;
}

// Where a plane is: the cells of a grid in the plane's coordinates that the views see on it (surface points
// within the tolerance), closed over small gaps, with holes filled (an object's footprint, a patch that
// every view sees with a reflection in it), keeping only the pieces that hold detections (not a wall
// that crosses the plane's height far away).
class PlaneExtent {
 public:
  PlaneExtent(const Plane& pl, const std::vector<glm::vec2>& on_plane, const std::vector<glm::vec2>& seeds) : pl_(pl) {
    // An orthonormal basis of the plane, its origin the point nearest the world's.
    const glm::vec3 a = std::abs(pl.n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    e1_ = glm::normalize(glm::cross(pl.n, a));
    e2_ = glm::cross(pl.n, e1_);
    origin_ = -pl.d * pl.n;
    if (on_plane.empty()) return;
    // The grid spans the points' 0.5 - 99.5 percentiles (a stray far point does not coarsen it).
    auto percentile = [&](int axis, double q) {
      std::vector<float> c;
      c.reserve(on_plane.size());
      for (const glm::vec2& x : on_plane) c.push_back(x[axis]);
      const size_t k = std::min(c.size() - 1, size_t(q * double(c.size())));
      std::nth_element(c.begin(), c.begin() + long(k), c.end());
      return c[k];
    };
    lo_ = {percentile(0, 0.005), percentile(1, 0.005)};
    const glm::vec2 hi(percentile(0, 0.995), percentile(1, 0.995));
    cell_ = std::max(hi.x - lo_.x, hi.y - lo_.y) / float(kCells);
    if (!(cell_ > 0)) return;
    const int gw = int((hi.x - lo_.x) / cell_) + 1, gh = int((hi.y - lo_.y) / cell_) + 1;
    // Cells the views see often: stray points near the plane's height (floaters beside a table) are sparse.
    cv::Mat count = cv::Mat::zeros(gh, gw, CV_32S);
    for (const glm::vec2& x : on_plane) {
      const cv::Point c = cell(x);
      if (c.x >= 0 && c.y >= 0 && c.x < gw && c.y < gh) count.at<int>(c.y, c.x) += 1;
    }
    std::vector<int> seen;
    for (int y = 0; y < gh; ++y)
      for (int x = 0; x < gw; ++x)
        if (count.at<int>(y, x) > 0) seen.push_back(count.at<int>(y, x));
    if (seen.empty()) return;
    std::nth_element(seen.begin(), seen.begin() + long(seen.size() * 3 / 4), seen.end());
    // A fifth of the upper-quartile count: on steel_snowman (radiance 4K, 128 px) the table's cells hold
    // 40+ points, the floaters around it ~10; the masks do not change between a tenth and a half.
    const int min_count = std::max(1, int(std::lround(0.2f * float(seen[seen.size() * 3 / 4]))));
    cv::Mat occ = cv::Mat::zeros(gh + 2, gw + 2, CV_8U);  // a free border for the hole filling
    for (int y = 0; y < gh; ++y)
      for (int x = 0; x < gw; ++x) occ.at<std::uint8_t>(y + 1, x + 1) = count.at<int>(y, x) >= min_count ? 1 : 0;
    const cv::Mat disc = cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(5, 5));
    cv::morphologyEx(occ, occ, cv::MORPH_CLOSE, disc);
    occ.row(0).setTo(0), occ.row(occ.rows - 1).setTo(0);  // the closing may have reached the free border
    occ.col(0).setTo(0), occ.col(occ.cols - 1).setTo(0);
    cv::Mat outside = occ.clone();
    cv::floodFill(outside, cv::Point(0, 0), cv::Scalar(2));
    occ.setTo(1, outside == 0);  // holes: not reached from the border
    cv::Mat labels;
    cv::connectedComponents(occ, labels, 8, CV_32S);
    std::vector<std::uint8_t> keep(size_t(gw + 2) * size_t(gh + 2) + 1, 0);
    for (const glm::vec2& x : seeds) {
      const cv::Point c = cell(x);
      if (c.x >= 0 && c.y >= 0 && c.x < gw && c.y < gh) keep[size_t(labels.at<int>(c.y + 1, c.x + 1))] = 1;
    }
    keep[0] = 0;  // the background label
    grid_ = cv::Mat::zeros(gh, gw, CV_8U);
    for (int y = 0; y < gh; ++y)
      for (int x = 0; x < gw; ++x) grid_.at<std::uint8_t>(y, x) = keep[size_t(labels.at<int>(y + 1, x + 1))];
  }

  glm::vec2 coordinates(const glm::vec3& x) const { return {glm::dot(x - origin_, e1_), glm::dot(x - origin_, e2_)}; }

  // Whether the ray from `eye` through the surface point `x` crosses the plane inside its extent before
  // reaching x: x then lies behind the plane - the virtual geometry a radiance model puts behind a mirror.
  bool seen_through(const glm::vec3& eye, const glm::vec3& x, float tolerance) const {
    if (grid_.empty()) return false;
    const float se = glm::dot(pl_.n, eye) + pl_.d, sx = glm::dot(pl_.n, x) + pl_.d;
    if (!(se * sx < 0) || !(std::abs(sx) > tolerance)) return false;
    const glm::vec3 hit = eye + (se / (se - sx)) * (x - eye);
    const cv::Point c = cell(coordinates(hit));
    return c.x >= 0 && c.y >= 0 && c.x < grid_.cols && c.y < grid_.rows && grid_.at<std::uint8_t>(c.y, c.x) != 0;
  }

 private:
  static constexpr int kCells = 160;  // along the longer side
  cv::Point cell(glm::vec2 x) const {
    return {int(std::floor((x.x - lo_.x) / cell_)), int(std::floor((x.y - lo_.y) / cell_))};
  }
  Plane pl_;
  glm::vec3 e1_{0.0f}, e2_{0.0f}, origin_{0.0f};
  glm::vec2 lo_{0.0f};
  float cell_ = 0;
  cv::Mat grid_;  // [rows][cols] 1 = the plane is there
};

// A pixel joins the masks when its surface point lies on one of the planes, or behind one seen through its
// extent.
void grow_masks(const std::vector<ConsistencyView>& views, const std::vector<Plane>& planes,
                const std::vector<PlaneExtent>& extents, float tolerance, GlossyDetection& out) {
  for (size_t i = 0; i < views.size(); ++i) {
    const ConsistencyView& v = views[i];
    const glm::vec3 eye = v.camera.center();
    for (size_t p = 0; p < out.masks[i].size(); ++p) {
      if (out.masks[i][p] || !(v.alpha[p] > 0.5f) || !(v.depth[p] > 0)) continue;
      const glm::vec3 x = surface_point(v, p);
      bool on = false, behind = false;
      for (size_t k = 0; k < planes.size() && !on; ++k) {
        on = planes[k].distance(x) <= tolerance;
        behind = behind || (!on && extents[k].seen_through(eye, x, tolerance));
      }
      if (on || behind) {
        out.masks[i][p] = 1;
        ++(on ? out.on_planes : out.behind_planes);
      }
    }
  }
}

// Grows the masks over the planes the detected pixels lie on: a glossy table top or mirror is glossy
// everywhere, but reflections are only seen (detected) where they show something that changes. A pixel
// joins when its surface point lies on a plane, or behind it seen through the plane's extent: a radiance
// model renders a mirror's reflections as geometry behind it, and those are the pixels that matter most.
void grow_on_planes(const std::vector<ConsistencyView>& views, GlossyDetection& out, const GlossyDetectionSettings& s) {
  std::vector<glm::vec3> pts;
  std::vector<float> dist;
  for (size_t i = 0; i < views.size(); ++i)
    for (size_t p = 0; p < out.masks[i].size(); ++p)
      if (out.masks[i][p]) {
        pts.push_back(surface_point(views[i], p));
        dist.push_back(glm::length(pts.back() - views[i].camera.center()));
      }
  if (pts.size() < size_t(s.plane_min_points)) return;
  const std::vector<glm::vec3> seeds = pts;
  if (pts.size() > 20000) {  // a spread subset is plenty for the fit
    std::vector<glm::vec3> sub;
    const size_t step = pts.size() / 20000 + 1;
    for (size_t k = 0; k < pts.size(); k += step) sub.push_back(pts[k]);
    pts = std::move(sub);
  }
  std::nth_element(dist.begin(), dist.begin() + long(dist.size() / 2), dist.end());
  const float tolerance = s.plane_tolerance * dist[dist.size() / 2];
  const std::vector<Plane> found = fit_planes(std::move(pts), tolerance, s);
  // Each plane kept (not a backdrop) and its extent, from every covered surface point on it.
  std::vector<Plane> planes;
  std::vector<PlaneExtent> extents;
  for (size_t k = 0; k < found.size(); ++k) {
    const Plane& pl = found[k];
    std::vector<glm::vec3> on;
    for (size_t i = 0; i < views.size(); ++i)
      for (size_t p = 0; p < out.masks[i].size(); ++p)
        if (views[i].alpha[p] > 0.5f && views[i].depth[p] > 0) {
          const glm::vec3 x = surface_point(views[i], p);
          if (pl.distance(x) <= tolerance) on.push_back(x);
        }
    std::vector<Plane> others = found;
    others.erase(others.begin() + long(k));
    const float in_front = evidence_in_front(views, out.masks, pl, on, others, tolerance);
    out.rejected_planes.push_back(in_front > s.plane_max_in_front);
    out.plane_in_front.push_back(in_front);
    if (out.rejected_planes.back()) continue;
    planes.push_back(pl);
    out.plane_normals.push_back(pl.n);
    PlaneExtent probe(pl, {}, {});
    std::vector<glm::vec2> on_plane, seeded;
    for (const glm::vec3& x : on) on_plane.push_back(probe.coordinates(x));
    for (const glm::vec3& x : seeds)
      if (pl.distance(x) <= tolerance) seeded.push_back(probe.coordinates(x));
    extents.emplace_back(pl, on_plane, seeded);
  }
  out.planes = int(planes.size());
  grow_masks(views, planes, extents, tolerance, out);
}

// The masks grown over the plane of a mirror world (mirror_world_detection.h) that no detection marked: its
// extent is where the views see the plane itself or see through it to what lies behind it.
void grow_over_mirror_world(const std::vector<ConsistencyView>& views, GlossyDetection& out,
                            const GlossyDetectionSettings& s) {
  const MirrorWorldPlane& mw = out.mirror_world;
  const Plane pl{mw.normal, -mw.height};
  std::vector<glm::vec3> points, eyes;  // every covered surface point and the camera that sees it
  std::vector<float> dist;
  for (const ConsistencyView& v : views)
    for (size_t p = 0; p < size_t(v.camera.width) * size_t(v.camera.height); ++p)
      if (v.alpha[p] > 0.5f && v.depth[p] > 0) {
        points.push_back(surface_point(v, p));
        eyes.push_back(v.camera.center());
        dist.push_back(glm::length(points.back() - eyes.back()));
      }
  if (dist.empty()) return;
  const float tolerance = s.plane_tolerance * median_of(std::move(dist));
  std::vector<glm::vec3> on, through;
  for (size_t k = 0; k < points.size(); ++k) {
    const float se = glm::dot(pl.n, eyes[k]) + pl.d, sx = glm::dot(pl.n, points[k]) + pl.d;
    if (std::abs(sx) <= tolerance) on.push_back(points[k]);
    else if (se * sx < 0) through.push_back(eyes[k] + (se / (se - sx)) * (points[k] - eyes[k]));
  }
  PlaneExtent probe(pl, {}, {});
  std::vector<glm::vec2> on_plane, seeds;
  for (const glm::vec3& x : on) on_plane.push_back(probe.coordinates(x));
  for (const glm::vec3& x : through) seeds.push_back(probe.coordinates(x)), on_plane.push_back(seeds.back());
  const std::vector<Plane> planes{pl};
  const std::vector<PlaneExtent> extents{PlaneExtent(pl, on_plane, seeds)};
  out.planes = 1;
  out.plane_normals.push_back(pl.n);
  grow_masks(views, planes, extents, tolerance, out);
}

}  // namespace

GlossyDetection detect_glossy_regions(const std::vector<ConsistencyView>& views, const GlossyDetectionSettings& s,
                                      int model_gaussians) {
  if (s.neighbours < 1 || s.neighbours > 16) throw Error("glossy detection: neighbours must lie in 1..16");
  std::vector<Camera> cameras;
  for (size_t i = 0; i < views.size(); ++i) {
    const ConsistencyView& v = views[i];
    if (!v.image || !v.depth || !v.alpha)
      throw Error("glossy detection: view " + std::to_string(i) + " has no image, depth or alpha");
    if (v.camera.has_distortion() || v.camera.width < 1 || v.camera.height < 1 || !(v.camera.fx > 0) || !(v.camera.fy > 0))
      throw Error("glossy detection: view " + std::to_string(i) + " needs an undistorted pinhole camera");
    cameras.push_back(v.camera);
  }
  if (s.search_radius < 0) throw Error("glossy detection: the search radius must be >= 0");
  if (s.depth_window < 0) throw Error("glossy detection: the depth window must be >= 0");
  std::vector<ColourRange> ranges;
  for (const ConsistencyView& v : views) ranges.push_back(colour_range(v, s.search_radius));
  GlossyDetection out;
  for (int i = 0; i < int(views.size()); ++i) {
    const ConsistencyView& v = views[size_t(i)];
    const int w = v.camera.width, h = v.camera.height;
    std::vector<float> score = score_view(views, ranges, i, nearest_views(cameras, i, s.neighbours), s);
    std::vector<std::uint8_t> mask(score.size(), 0);
    for (size_t p = 0; p < score.size(); ++p) {
      out.covered += v.alpha[p] > 0.5f;
      out.scored += score[p] >= 0;
      mask[p] = score[p] > s.threshold ? 1 : 0;
    }
    clean_mask(mask, v.alpha, w, h, s.morph_radius);
    out.detected += std::size_t(std::accumulate(mask.begin(), mask.end(), std::size_t(0)));
    out.masks.push_back(std::move(mask));
    out.scores.push_back(std::move(score));
    out.score_widths.push_back(w);
  }
  out.fraction = out.covered > 0 ? double(out.detected) / double(out.covered) : 0.0;
  if (s.mirror_world && model_gaussians >= 0 && model_gaussians < s.mirror_world_min_gaussians) {
    out.mirror_world.summary = "not searched: the model holds " + std::to_string(model_gaussians) +
                               " Gaussians, fewer than " + std::to_string(s.mirror_world_min_gaussians) +
                               " (not densified yet: blobs, not geometry)";
  } else if (s.mirror_world) {
    std::vector<glm::vec3> surface, centres;
    for (const ConsistencyView& v : views) {
      centres.push_back(v.camera.center());
      for (size_t p = 0; p < size_t(v.camera.width) * size_t(v.camera.height); ++p)
        if (v.alpha[p] > 0.5f && v.depth[p] > 0) surface.push_back(surface_point(v, p));
    }
    out.mirror_world = find_mirror_world_plane(surface, centres);
  }
  out.glossy = out.detected > 0 && out.fraction >= s.min_fraction;
  if (s.grow_planes && out.glossy) grow_on_planes(views, out, s);  // masks of a Lambertian scene stay the evidence
  // The method's case is a planar reflector (a table, a floor, a mirror): view-dependent pixels spread over
  // no plane - a varnished frame, fur or foliage that a warmed-up model has not settled - are left to the
  // radiance model, which shows them as well at a fraction of the cost.
  if (s.grow_planes && s.require_plane && out.glossy && out.planes == 0) out.glossy = false;
  // Reflections the radiance model has already turned into a mirror world are photo-consistent: its
  // geometry shows them instead.
  if (!out.glossy && s.mirror_world && out.mirror_world.found) {
    out.glossy = out.by_mirror_world = true;
    if (s.grow_planes) grow_over_mirror_world(views, out, s);
  }
  for (const auto& m : out.masks) out.in_masks += std::size_t(std::accumulate(m.begin(), m.end(), std::size_t(0)));
  return out;
}

GlossyDetection detect_glossy_regions(const GaussianView& gaussians, const std::vector<TrainView>& views,
                                      const RasterSettings& raster, Device device, const GlossyDetectionSettings& s) {
  // Photos, depth and alpha at the working size, kept on the host.
  struct Work {
    std::vector<float> image, depth, alpha;
  };
  std::vector<Work> work(views.size());
  std::vector<ConsistencyView> cv_views(views.size());
  for (size_t i = 0; i < views.size(); ++i) {
    const TrainView& v = views[i];
    const Camera& full = v.camera;
    if (v.image.size() != size_t(3) * full.width * full.height)
      throw Error(v.name, "glossy detection: the training image does not match its camera");
    Camera cam = full;
    work[i].image = v.image;
    if (s.work_width > 0 && full.width > s.work_width) {
      const int ww = s.work_width, wh = std::max(1, int(std::lround(double(full.height) * ww / full.width)));
      cam = full.resized(ww, wh);
      work[i].image = to_planar_rgb(resize_image(from_planar(v.image.data(), 3, full.width, full.height), ww, wh));
    }
    const RasterOutput r = rasterize(gaussians, cam, raster, device);
    work[i].depth = r.gbuffer.median_depth.to_host();
    work[i].alpha = r.gbuffer.alpha.to_host();
    cv_views[i] = {cam, work[i].image.data(), work[i].depth.data(), work[i].alpha.data()};
  }
  GlossyDetection out = detect_glossy_regions(cv_views, s, gaussians.count);
  // Masks back at the views' sizes (bilinear, then > 0.5); the counts and the decision stay those of the
  // working size.
  for (size_t i = 0; i < views.size(); ++i) {
    const Camera& full = views[i].camera;
    const Camera& cam = cv_views[i].camera;
    if (cam.width == full.width && cam.height == full.height) continue;
    Image m(cam.width, cam.height, 1);
    for (size_t p = 0; p < out.masks[i].size(); ++p) m.pixels[p] = float(out.masks[i][p]);
    const Image up = resize_image(m, full.width, full.height);
    std::vector<std::uint8_t> mask(up.pixel_count());
    for (size_t p = 0; p < mask.size(); ++p) mask[p] = up.pixels[p] > 0.5f ? 1 : 0;
    out.masks[i] = std::move(mask);
  }
  return out;
}

double MaskAgreement::iou() const {
  const std::size_t uni = detected + reference - both;
  return uni > 0 ? double(both) / double(uni) : 1.0;
}
double MaskAgreement::recall() const { return reference > 0 ? double(both) / double(reference) : 1.0; }
double MaskAgreement::precision() const { return detected > 0 ? double(both) / double(detected) : 1.0; }

MaskAgreement compare_masks(const std::vector<std::uint8_t>& detected, const std::vector<float>& reference) {
  if (detected.size() != reference.size()) throw Error("compare_masks: the masks differ in size");
  MaskAgreement a;
  for (size_t p = 0; p < detected.size(); ++p) {
    const bool d = detected[p] != 0, r = reference[p] > 0.5f;
    a.detected += d;
    a.reference += r;
    a.both += d && r;
  }
  return a;
}

}  // namespace goris
