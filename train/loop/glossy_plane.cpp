#include "train/loop/glossy_plane.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/gtc/quaternion.hpp>

#include "core/compute/parallel_for.h"
#include "core/scene/plane_from_masks.h"
#include "core/scene/selection_points.h"
#include "train/loop/trainer.h"
#include "train/optimizer/densify.h"

namespace goris {

std::vector<std::uint8_t> over_glossy_pixels(const GaussianModel& model, const std::vector<TrainView>& views) {
  const std::vector<float> pos = model.tensor(Param::Position).value.to_host();
  const std::size_t n = model.count();
  std::vector<std::uint32_t> on_glossy(n, 0), in_frame(n, 0);
  for (const TrainView& v : views) {
    const Camera& c = v.camera;
    if (v.glossy_mask.size() != std::size_t(c.width) * std::size_t(c.height)) continue;
    parallel_for(Device::CPU, n, [&](std::size_t i) {
      const long long pixel = c.pixel_of(c.to_camera(glm::vec3(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2])));
      if (pixel < 0) return;
      ++in_frame[i];
      if (v.glossy_mask[std::size_t(pixel)] > 0.5f) ++on_glossy[i];
    }, 1024);
  }
  std::vector<std::uint8_t> over(n, 0);
  for (std::size_t i = 0; i < n; ++i) over[i] = 2 * on_glossy[i] > in_frame[i];
  return over;
}

namespace {

// The masks give the height of the surface's outline (a top's glossy side can pull it down); the constraint
// holds the model's own surface: the densest layer, one tolerance thick, of the centres over glossy pixels
// within kReach tolerances of the masks' plane, when there is one - at least kMinLayer centres and a third of
// those within reach, twice what a layer holds of an even spread. On the generalization suite's tables the
// warm-up's layer lay 0.015-0.07 below the masks' plane on 10 of 11, and moving there was worth 0.7-3.2 dB on
// the three mirror-like tables of six measured (level on the other three); the floors' warm-ups, still a fog,
// had none and kept the masks' height (docs/lab/2026-12-05-the-glossy-plane-from-the-masks.md). Sets the
// plane's inlier counts to the model's; returns how far it moved the plane.
double snap_to_surface_layer(MirrorPlane& plane, const std::vector<float>& pos, const std::vector<std::uint8_t>& over) {
  constexpr double kReach = 3.0;
  constexpr std::size_t kMinLayer = 10;
  auto distance = [&](std::size_t i) {
    return plane.signed_distance(glm::dvec3(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]));
  };
  std::vector<double> near;
  for (std::size_t i = 0; i < over.size(); ++i)
    if (over[i] && std::abs(distance(i)) <= kReach * plane.tolerance) near.push_back(distance(i));
  std::sort(near.begin(), near.end());
  std::size_t best = 0, best_count = 0;  // the window [near[best], near[best] + tolerance]
  for (std::size_t a = 0, b = 0; a < near.size(); ++a) {
    while (b < near.size() && near[b] <= near[a] + plane.tolerance) ++b;
    if (b - a > best_count) best = a, best_count = b - a;
  }
  double moved = 0;
  if (best_count >= kMinLayer && 3 * best_count >= near.size()) moved = near[best + best_count / 2];  // its median
  plane.offset += moved;
  plane.glossy = plane.inliers = 0;
  for (std::size_t i = 0; i < over.size(); ++i)
    if (over[i]) ++plane.glossy, plane.inliers += std::abs(distance(i)) <= plane.tolerance;
  return moved;
}

// The views' glossy masks' plane, level: its normal the cameras' mean up. The masks cannot tell a small tilt:
// their tilt search gained at most 0.017 IoU over the level plane on the generalization suite's level surfaces
// and was 2-7 degrees off on 12 of 13, while a true 4-degree tilt gains 0.009 on clean masks; a reflected ray
// is off by twice the surface normal's error. (The removal keeps the tilt search: level, its planar
// reflection mask lost 0.10 dB on the suite's mean.) found = false without masks or when they agree at no
// height.
MirrorPlane level_plane_from_masks(const std::vector<TrainView>& views) {
  PlaneFromMasksSettings level;
  level.tilt_steps = 0;
  return plane_from_glossy_masks(cameras_of(views), glossy_masks_of(views), level).plane;
}

}  // namespace

MirrorPlane glossy_surface_plane(const GaussianModel& model, const std::vector<TrainView>& views,
                                 const std::vector<std::uint8_t>& over_glossy, std::string* source) {
  if (MirrorPlane plane = level_plane_from_masks(views); plane.found) {
    const double moved = snap_to_surface_layer(plane, model.tensor(Param::Position).value.to_host(), over_glossy);
    if (source) {
      char buf[120];
      std::snprintf(buf, sizeof buf, "from the glossy masks, level, moved %+.3f onto the model's surface layer", moved);
      *source = moved != 0 ? buf : "from the glossy masks, level";
    }
    return plane;
  }
  const SelectionPoints points = selection_points(model);
  const std::vector<glm::vec3> flat = flat_normals(model);
  std::vector<glm::vec3> centres, normals;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (over_glossy[i]) centres.push_back(points.position[i]), normals.push_back(flat[i]);
  MirrorPlane plane = fit_mirror_plane(centres, {}, normals);
  if (source) *source = "fitted to the flat glossy Gaussians";
  if (!plane.found) return plane;
  std::size_t above = 0, n_cameras = 0;
  for (const TrainView& v : views) above += plane.signed_distance(glm::dvec3(v.camera.center())) > 0, ++n_cameras;
  if (2 * above < n_cameras) plane.normal = -plane.normal, plane.offset = -plane.offset;
  return plane;
}

namespace {

// Within the plane's inlier distance: the surface's own Gaussians.
bool in_band(const MirrorPlane& plane, const glm::dvec3& p) {
  return std::abs(plane.signed_distance(p)) <= plane.tolerance;
}

}  // namespace

PlaneFootprint::PlaneFootprint(const std::vector<float>& pos, const MirrorPlane& plane,
                               const std::vector<std::uint8_t>& flags) {
  if (!plane.found) return;
  const glm::dvec3 other = std::abs(plane.normal.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  u_ = glm::normalize(glm::cross(plane.normal, other));
  v_ = glm::cross(plane.normal, u_);
  std::vector<glm::dvec2> centres;  // in-plane coordinates of the flagged in-band centres
  glm::dvec2 lo(1e300), hi(-1e300);
  for (std::size_t i = 0; i < flags.size(); ++i) {
    const glm::dvec3 p(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]);
    if (!flags[i] || !in_band(plane, p)) continue;
    centres.emplace_back(glm::dot(p, u_), glm::dot(p, v_));
    lo = glm::min(lo, centres.back()), hi = glm::max(hi, centres.back());
  }
  if (centres.empty()) return;
  // At least the centres' mean spacing, so that the closing bridges the gaps between sparse centres.
  const glm::dvec2 size = hi - lo;
  cell_ = std::max({glm::length(size) / kCells, std::sqrt(size.x * size.y / double(centres.size())), 1e-9});
  const int pad = kClose + 1;  // room for the closing's dilation
  origin_ = lo - double(pad) * cell_;
  nu_ = int((hi.x - lo.x) / cell_) + 1 + 2 * pad, nv_ = int((hi.y - lo.y) / cell_) + 1 + 2 * pad;
  std::vector<std::uint8_t> grid(std::size_t(nu_) * std::size_t(nv_), 0);
  for (const glm::dvec2& q : centres) grid[index(cell_of(q))] = 1;
  // A square window of radius r: any (dilate) or all (erode) of its cells set. Off the grid counts as unset.
  auto morph = [&](int r, bool dilate) {
    std::vector<std::uint8_t> out(grid.size(), 0);
    for (int y = 0; y < nv_; ++y)
      for (int x = 0; x < nu_; ++x) {
        bool any = false, all = true;
        for (int dy = -r; dy <= r; ++dy)
          for (int dx = -r; dx <= r; ++dx) {
            const int xx = x + dx, yy = y + dy;
            const bool set = xx >= 0 && yy >= 0 && xx < nu_ && yy < nv_ && grid[index({xx, yy})];
            any |= set, all &= set;
          }
        out[index({x, y})] = dilate ? any : all;
      }
    grid.swap(out);
  };
  morph(kClose, true);  // close the gaps between sparse centres,
  // fill the holes (what the border cannot reach through unset cells: a mirror's reflections are seen
  // through it, and its top can be sparse there after the warm-up),
  std::vector<std::uint8_t> outside(grid.size(), 0);
  std::vector<glm::ivec2> stack;
  auto reach = [&](glm::ivec2 c) {
    if (c.x < 0 || c.y < 0 || c.x >= nu_ || c.y >= nv_ || grid[index(c)] || outside[index(c)]) return;
    outside[index(c)] = 1;
    stack.push_back(c);
  };
  for (int x = 0; x < nu_; ++x) reach({x, 0}), reach({x, nv_ - 1});
  for (int y = 0; y < nv_; ++y) reach({0, y}), reach({nu_ - 1, y});
  while (!stack.empty()) {
    const glm::ivec2 c = stack.back();
    stack.pop_back();
    reach(c + glm::ivec2(1, 0)), reach(c - glm::ivec2(1, 0)), reach(c + glm::ivec2(0, 1)), reach(c - glm::ivec2(0, 1));
  }
  for (std::size_t k = 0; k < grid.size(); ++k) grid[k] = !outside[k];
  morph(kClose + kMargin, false);  // then keep only what lies kMargin cells inside the outline
  inside_.swap(grid);
}

bool PlaneFootprint::contains(const glm::dvec3& p) const {
  if (inside_.empty()) return false;
  const glm::ivec2 c = cell_of({glm::dot(p, u_), glm::dot(p, v_)});
  return c.x >= 0 && c.y >= 0 && c.x < nu_ && c.y < nv_ && inside_[index(c)];
}

glm::ivec2 PlaneFootprint::cell_of(const glm::dvec2& q) const {
  const glm::dvec2 c = glm::floor((q - origin_) / cell_);
  return {int(std::clamp(c.x, -1.0, double(nu_))), int(std::clamp(c.y, -1.0, double(nv_)))};
}

namespace {

// The flagged centres more than the plane's tolerance beyond it, inside the surface's footprint (what lies
// beyond the outline - the table's own edge, its legs - is real geometry seen directly).
template <typename F>
void for_each_beyond(const std::vector<float>& pos, const MirrorPlane& plane, const PlaneFootprint& footprint,
                     const std::vector<std::uint8_t>& flags, F&& f) {
  for (std::size_t i = 0; i < flags.size(); ++i) {
    if (!flags[i]) continue;
    const glm::dvec3 p(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]);
    const double d = plane.signed_distance(p);
    if (d < -plane.tolerance && footprint.contains(p)) f(i, p, d);
  }
}

}  // namespace

std::string GlossyPlaneConstraint::start(GaussianModel& model, const std::vector<TrainView>& views) {
  started_ = true;
  over_glossy_ = over_glossy_pixels(model, views);
  std::string source;
  plane_ = glossy_surface_plane(model, views, over_glossy_, &source);
  if (!plane_.found) return "glossy plane: none found, not constrained";
  const std::vector<float> pos = model.tensor(Param::Position).value.to_host();
  footprint_ = PlaneFootprint(pos, plane_, over_glossy_);
  std::vector<std::uint8_t> keep(model.count(), 1);
  for_each_beyond(pos, plane_, footprint_, over_glossy_,
                  [&](std::size_t i, const glm::dvec3&, double) { keep[i] = 0; });
  const std::size_t before = model.count();
  pruned_ = prune_gaussians(model, keep);
  over_glossy_.clear();  // refreshed at the first apply()
  char buf[200];
  std::snprintf(buf, sizeof buf,
                "n = (%.3f, %.3f, %.3f), n . x = %.3f (%zu of %zu centres): pruned %zu of %zu beyond it",
                plane_.normal.x, plane_.normal.y, plane_.normal.z, plane_.offset, plane_.inliers, plane_.glossy,
                pruned_, before);
  return "glossy plane " + source + ": " + buf;
}

GlossyPlaneConstraint::Step GlossyPlaneConstraint::apply(GaussianModel& model, const std::vector<TrainView>& views,
                                                         int it, bool prune_sinkers) {
  Step step;
  if (!plane_.found) return step;
  const bool refresh = over_glossy_.size() != model.count() || it - refreshed_at_ >= kRefreshInterval;
  if (refresh && prune_sinkers && sank_.size() == model.count()) {
    std::vector<std::uint8_t> keep(sank_.size());
    for (std::size_t i = 0; i < keep.size(); ++i) keep[i] = !sank_[i];
    step.pruned = prune_gaussians(model, keep);
    sinkers_pruned_ += step.pruned;
  }
  ParamTensor& t = model.tensor(Param::Position);
  std::vector<float> pos = t.value.to_host();
  if (refresh) {
    over_glossy_ = over_glossy_pixels(model, views);
    footprint_ = PlaneFootprint(pos, plane_, over_glossy_);
    sank_.assign(model.count(), 0);
    refreshed_at_ = it;
  }
  for_each_beyond(pos, plane_, footprint_, over_glossy_, [&](std::size_t i, const glm::dvec3& p, double d) {
    const glm::dvec3 q = p - (d + 0.5 * plane_.tolerance) * plane_.normal;  // inside the band, float-safe
    pos[3 * i] = float(q.x), pos[3 * i + 1] = float(q.y), pos[3 * i + 2] = float(q.z);
    sank_[i] = 1;
    ++step.moved;
  });
  if (step.moved) t.value.upload(pos.data(), pos.size());
  return step;
}

std::size_t GlossyPlaneConstraint::align_normals(GaussianModel& model) const {
  if (!plane_.found || over_glossy_.size() != model.count()) return 0;
  const std::vector<float> pos = model.tensor(Param::Position).value.to_host();
  const std::vector<glm::vec3> flat = flat_normals(model);  // zero where a Gaussian is not flat
  ParamTensor& t = model.tensor(Param::Rotation);
  std::vector<float> rot = t.value.to_host();
  const glm::dvec3 n = plane_.normal;
  std::size_t turned = 0;
  for (std::size_t i = 0; i < flat.size(); ++i) {
    if (!over_glossy_[i] || flat[i] == glm::vec3(0.0f)) continue;
    const glm::dvec3 p(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]);
    if (!in_band(plane_, p)) continue;
    const glm::dvec3 a = glm::normalize(glm::dvec3(flat[i]));
    const glm::dvec3 target = glm::dot(a, n) < 0 ? -n : n;  // the nearer of the two sides
    const double c = glm::dot(a, target);
    if (c > 1.0 - 1e-12) continue;
    // The shortest rotation taking a to target, (1 + a.t, a x t) normalised, applied before the stored one;
    // the stored quaternion's length is kept (it is stored unnormalised, docs/design/conventions.md).
    const glm::dvec3 axis = glm::cross(a, target);
    const glm::dquat turn = glm::normalize(glm::dquat(1.0 + c, axis.x, axis.y, axis.z));
    float* r = &rot[4 * i];
    const glm::dquat q(r[0], r[1], r[2], r[3]);
    const glm::dquat out = turn * q;
    r[0] = float(out.w), r[1] = float(out.x), r[2] = float(out.y), r[3] = float(out.z);
    ++turned;
  }
  if (turned) t.value.upload(rot.data(), rot.size());
  return turned;
}

}  // namespace goris
