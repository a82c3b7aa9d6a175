// SelectionSession::click_regions (ui/selection/selection_session.h): the two-click flow's evaluation on the
// selection worker, with `goris select --click`'s own steps (removal/selection/selection_click_flow.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/util/error.h"
#include "removal/selection/selection_click_flow.h"
#include "removal/selection/selection_view_masks.h"
#include "ui/selection/flow_result.h"
#include "ui/selection/session_context.h"

namespace goris::ui {

namespace fs = std::filesystem;

namespace {

// As `goris select`: a selection of more than this fraction of the scene is not one object.
constexpr float kMaxFraction = 0.5f;

// The pixel deepest inside `m` (chamfer distance to the nearest pixel outside or the border) and that
// distance in pixels (0: the mask is empty).
std::pair<float, glm::ivec2> deepest_pixel(const Mask& m) {
  const int w = m.width, h = m.height;
  constexpr float kBig = 1e9f;
  std::vector<float> d(std::size_t(w) * std::size_t(h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) d[std::size_t(y) * w + x] = m(x, y) ? kBig : 0.0f;
  auto at = [&](int x, int y) -> float { return x < 0 || y < 0 || x >= w || y >= h ? 0.0f : d[std::size_t(y) * w + x]; };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float& v = d[std::size_t(y) * w + x];
      v = std::min({v, at(x - 1, y) + 1.0f, at(x, y - 1) + 1.0f, at(x - 1, y - 1) + 1.4142f, at(x + 1, y - 1) + 1.4142f});
    }
  float best = 0.0f;
  glm::ivec2 best_at(0);
  for (int y = h - 1; y >= 0; --y)
    for (int x = w - 1; x >= 0; --x) {
      float& v = d[std::size_t(y) * w + x];
      v = std::min({v, at(x + 1, y) + 1.0f, at(x, y + 1) + 1.0f, at(x + 1, y + 1) + 1.4142f, at(x - 1, y + 1) + 1.4142f});
    }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (d[std::size_t(y) * w + x] > best) best = d[std::size_t(y) * w + x], best_at = {x, y};
  return {best, best_at};
}

// The view for the second click. Candidates: the views turned kMinTurn..kMaxTurn from the first one (any
// other view when none is), the kCandidates that show the first click's object largest (its mask's
// deepest pixel farthest from the mask's edge). Each is clicked at that pixel as the flow will click it
// (the view's glossy mask the region's barrier), and the one whose click region agrees best with the first
// click's mask there (IoU) is offered: a click whose region leaks into the table or lands on another object
// disagrees. No candidate either: a pixel that shows a Gaussian the first click did not select, or whose
// region covers less than a twentieth of the mask (a holed object's mask can close over its hole, whose
// deepest pixel then shows what lies behind, in a region too small to lift).
std::optional<FlowClick> offer_second_view(const GaussianModel& model, const std::vector<View>& views,
                                           const DatasetOptions& photos, const std::vector<Mask>& masks,
                                           const SelectionMask& selected, std::size_t first,
                                           const RasterSettings& raster,
                                           const std::vector<const std::vector<float>*>& gloss) {
  constexpr float kMinTurn = 30.0f, kMaxTurn = 100.0f;
  constexpr std::size_t kCandidates = 5;
  struct Candidate {
    std::size_t view;
    float depth, turn;
    glm::ivec2 at;
  };
  std::vector<Candidate> all;
  const glm::vec3 f0 = views[first].camera.forward();
  for (std::size_t v = 0; v < views.size(); ++v) {
    if (v == first) continue;
    const auto [depth, at] = deepest_pixel(masks[v]);
    if (depth < 1.0f) continue;
    const float c = std::clamp(glm::dot(f0, views[v].camera.forward()), -1.0f, 1.0f);
    all.push_back({v, depth, std::acos(c) * 57.29578f, at});
  }
  std::vector<Candidate> turned;
  for (const Candidate& c : all)
    if (c.turn >= kMinTurn && c.turn <= kMaxTurn) turned.push_back(c);
  std::vector<Candidate>& pool = turned.empty() ? all : turned;
  std::sort(pool.begin(), pool.end(), [](const Candidate& a, const Candidate& b) { return a.depth > b.depth; });
  if (pool.size() > kCandidates) pool.resize(kCandidates);
  std::optional<FlowClick> offer;
  double best = -1.0;
  for (const Candidate& c : pool) {
    double agree = 0.0;
    try {
      const Image photo = load_view_image(views[c.view], photos, Device::CPU);
      const ClickOutcome o = click_in_view(model, views[c.view], photo, c.at.x, c.at.y, raster, true,
                                           c.view < gloss.size() ? gloss[c.view] : nullptr);
      if (!o.pick.hit || o.pick.gaussian >= selected.size() || !selected[o.pick.gaussian]) continue;
      if (o.region.area * 20 < count_set(masks[c.view])) continue;
      agree = mask_iou(o.region.mask, masks[c.view]);
    } catch (const Error&) {
      continue;  // background there
    }
    if (agree > best) best = agree, offer = FlowClick{c.view, c.at.x, c.at.y};
  }
  return offer;
}

void check_cancel(const FlowProgress& p) {
  if (p.cancel) throw Error("two-click: cancelled");
}

}  // namespace

std::uint64_t SelectionSession::click_regions(std::vector<View> views, DatasetOptions photos,
                                              std::shared_ptr<FlowResult> out, std::shared_ptr<FlowProgress> progress,
                                              GlossyMasks glossy_masks) {
  return submit([this, views = std::move(views), photos, out, progress, glossy_masks](const Job& job) {
    if (out->clicks.empty()) throw Error("two-click: no click to select from");
    Context& c = prepared(job.model);
    const SelectionState cur = current_state();
    // What the viewports show: hidden Gaussians neither draw the clicked pixels nor cover the masks.
    const GaussianModel& model = c.shown_model(cur.guard.hidden);
    const RasterSettings& raster = job.model->settings();
    const int n_clicks = int(out->clicks.size());
    progress->done = 0;
    progress->total = n_clicks + 1 + int(views.size());

    // The glossy masks the run trained with (select_by_click_regions): one per view or none.
    const std::shared_ptr<const std::vector<std::vector<float>>> gloss_store = glossy_masks ? glossy_masks() : nullptr;
    const std::vector<const std::vector<float>*> gloss =
        gloss_store ? glossy_mask_pointers(*gloss_store) : std::vector<const std::vector<float>*>{};
    std::vector<ClickView> regions;
    std::string what = "two-click:";
    for (const FlowClick& k : out->clicks) {
      if (k.view >= views.size()) throw Error("two-click: no training view " + std::to_string(k.view));
      const View& view = views[k.view];
      progress->set_stage("region of the click in " + view.name);
      check_cancel(*progress);
      const Image photo = load_view_image(view, photos, Device::CPU);
      const ClickOutcome o =
          click_in_view(model, view, photo, k.x, k.y, raster, true, k.view < gloss.size() ? gloss[k.view] : nullptr);
      char b[200];
      std::snprintf(b, sizeof b, "two-click: %s (%d, %d): picked Gaussian %u, region %zu pixels at colour tolerance %.2f",
                    view.name.c_str(), k.x, k.y, o.pick.gaussian, o.region.area, double(o.region.tolerance));
      message(b, false);
      regions.push_back({view.name, view.camera, o.region.mask});
      out->click_regions.push_back(o.region.mask);
      what += " " + view.name + " (" + std::to_string(k.x) + ", " + std::to_string(k.y) + ")";
      ++progress->done;
    }
    progress->set_stage(n_clicks > 1 ? "lifting the regions, every view's vote" : "lifting the region");
    check_cancel(*progress);
    const ClickSelection cs = select_by_click_regions(model, c.selection.points, regions, views, raster, {}, gloss);
    if (cs.result.summary.seeds == 0)
      throw Error("two-click: no Gaussian lies inside the clicked region of every clicked view that sees it: are the "
                  "clicks on the same object?");
    if (cs.result.summary.fraction() > kMaxFraction)
      throw Error("two-click: the clicks select " + std::to_string(cs.result.summary.selected) + " of " +
                  std::to_string(job.model->count()) +
                  " Gaussians, more than half of the scene: that is not one object (click inside the object)");
    ++progress->done;

    fs::create_directories(out->dir);
    SelectionViewMasks vm = selection_view_masks(model, cs.result.mask, cameras_of(views), raster, {}, [&](std::size_t v) {
      progress->set_stage("mask of " + views[v].name);
      check_cancel(*progress);
      ++progress->done;
    });
    if (vm.lowered) {
      char b[200];
      std::snprintf(b, sizeof b, "two-click: the selection covers no pixel by more than half (at most %.2f): masks cut at %.2f",
                    double(vm.peak), double(vm.threshold));
      message(b, false);
    }
    out->masks = std::move(vm.masks);
    for (std::size_t v = 0; v < views.size(); ++v)
      save_mask_png(out->dir / object_mask_file_name(views[v].name), out->masks[v]);
    if (n_clicks == 1) {
      progress->set_stage("choosing a second view");
      out->offered =
          offer_second_view(model, views, photos, out->masks, cs.result.mask, out->clicks[0].view, raster, gloss);
    }
    out->total = job.model->count();

    SelectionPart part;
    part.seeds = cs.result.mask;
    part.method = "click";
    part.what = what;
    char done[200];
    std::snprintf(done, sizeof done, "%s, %zu from the clicked views%s; %zu masks in %s", what.c_str(),
                  cs.from_clicked_views, cs.revoted ? ", voted by every view" : "", views.size(),
                  out->dir.string().c_str());
    push_state(job, {std::move(part)}, cur.grow, done);
    const SelectionState now = current_state();
    out->selection = now.mask;
    out->selected = now.selected;
    progress->set_stage("");
  });
}

}  // namespace goris::ui
