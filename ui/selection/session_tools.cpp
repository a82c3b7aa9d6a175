// SelectionSession's tool edits (ui/selection/selection_session.h): regions, invert, grow / shrink steps, hide /
// lock, and object masks from the selection. Each runs on the selection worker and is one undo step.
#include <cstdio>

#include "core/inpaint/mask.h"
#include "core/util/error.h"
#include "removal/selection/selection_labels.h"
#include "removal/selection/selection_masks.h"
#include "removal/selection/selection_ops.h"
#include "removal/selection/selection_view_masks.h"
#include "ui/selection/session_context.h"

namespace goris::ui {

namespace fs = std::filesystem;

const GaussianModel& SelectionSession::Context::shown_model(const std::shared_ptr<const SelectionMask>& hidden) {
  if (shown_ && shown_hidden_ == hidden) return *shown_;
  shown_ = model->to_model();
  shown_hidden_ = hidden;
  if (hidden) {
    // Transparent: an opacity logit this low renders nothing.
    Buffer<float>& logits = shown_->tensor(Param::OpacityLogit).value;
    std::vector<float> v = logits.to_host();
    for (std::size_t i = 0; i < v.size() && i < hidden->size(); ++i)
      if ((*hidden)[i]) v[i] = -30.0f;
    logits.upload(v.data(), v.size());
  }
  return *shown_;
}

const GaussianPicker& SelectionSession::Context::shown_picker(const std::shared_ptr<const SelectionMask>& hidden) {
  if (!hidden) return *picker;
  if (!shown_picker_ || shown_picker_hidden_ != hidden) {
    shown_picker_ = std::make_unique<GaussianPicker>(shown_model(hidden));
    shown_picker_hidden_ = hidden;
  }
  return *shown_picker_;
}

void SelectionSession::push_part(const Job& job, SelectionPart part, SelectMode mode, const std::string& done) {
  SelectionState cur = current_state();
  part.mode = mode;
  if (mode == SelectMode::Replace) cur.parts.clear();
  cur.parts.push_back(std::move(part));
  push_state(job, std::move(cur.parts), cur.grow, done + ", " + select_mode_id(mode));
}

namespace {

SelectionPart region_part(SelectionMask mask, const std::string& method, const std::string& what) {
  SelectionPart p;
  p.seeds = std::move(mask);
  p.method = method;
  p.what = what;
  return p;
}

// The current selection as a mask (all zero when nothing is selected).
SelectionMask current_mask(const SelectionState& s, std::size_t n) {
  return s.mask ? *s.mask : SelectionMask(n, 0);
}

}  // namespace

std::uint64_t SelectionSession::screen_region(ScreenRegion region, SelectMode mode) {
  return submit([this, region = std::move(region), mode](const Job& job) {
    Context& c = prepared(job.model);
    const GaussianModel& shown = c.shown_model(current_state().guard.hidden);
    SelectionMask m = screen_region_mask(shown, c.selection.points, region, job.model->settings());
    const std::string what = describe(region);
    push_part(job, region_part(std::move(m), screen_region_name(region.kind), what), mode, what);
  });
}

std::uint64_t SelectionSession::volume(VolumeRegion v, SelectMode mode) {
  return submit([this, v, mode](const Job& job) {
    Context& c = prepared(job.model);
    const std::string what = describe(v);
    push_part(job, region_part(volume_mask(c.selection.points, v), volume_region_name(v.kind), what), mode, what);
  });
}

std::uint64_t SelectionSession::colour(glm::vec3 reference, float max_distance, SelectMode mode) {
  return submit([this, reference, max_distance, mode](const Job& job) {
    if (!(max_distance >= 0.0f)) throw Error("select by colour", "the distance must not be negative");
    Context& c = prepared(job.model);
    char what[128];
    std::snprintf(what, sizeof what, "colour within %.2f of (%.2f, %.2f, %.2f)", double(max_distance),
                  double(reference.r), double(reference.g), double(reference.b));
    push_part(job, region_part(select_by_colour(c.selection.points, reference, max_distance), "colour", what), mode,
              what);
  });
}

std::uint64_t SelectionSession::invert() {
  return submit([this](const Job& job) {
    const SelectionState cur = current_state();
    SelectionMask m = invert_selection(current_mask(cur, job.model->count()));
    push_part(job, region_part(std::move(m), "invert", "inverted"), SelectMode::Replace, "inverted");
  });
}

std::uint64_t SelectionSession::step(int rings) {
  return submit([this, rings](const Job& job) {
    if (rings == 0) throw Error("grow / shrink step: zero steps");
    const SelectionState cur = current_state();
    if (!cur.mask) throw Error("grow / shrink step: nothing is selected");
    const SelectionGraph& graph = prepared(job.model).selection.graph;
    SelectionMask m = rings > 0 ? dilate_selection(graph, *cur.mask, rings) : shrink_selection(graph, *cur.mask, -rings);
    const std::string what = (rings > 0 ? "grown by " : "shrunk by ") + std::to_string(std::abs(rings)) +
                             (std::abs(rings) == 1 ? " step" : " steps");
    push_part(job, region_part(std::move(m), "step", what), SelectMode::Replace, what);
  });
}

std::uint64_t SelectionSession::hide_selected() { return change_guard(/*hide=*/true, /*add=*/true); }
std::uint64_t SelectionSession::lock_selected() { return change_guard(/*hide=*/false, /*add=*/true); }
std::uint64_t SelectionSession::unhide_all() { return change_guard(/*hide=*/true, /*add=*/false); }
std::uint64_t SelectionSession::unlock_all() { return change_guard(/*hide=*/false, /*add=*/false); }

std::uint64_t SelectionSession::change_guard(bool hide, bool add) {
  return submit([this, hide, add](const Job& job) {
    SelectionState cur = current_state();
    const char* verb = hide ? "hide" : "lock";
    if (add) {
      // The selection goes into the guard: it ends up empty.
      if (!cur.mask) throw Error(std::string(verb) + ": nothing is selected");
      const SelectionGuard g = guard_adding(cur.guard, *cur.mask, hide);
      const std::size_t now = hide ? g.hidden_count : g.locked_count;
      push_state(job, {}, cur.grow,
                 std::string(hide ? "hid " : "locked ") + std::to_string(cur.selected) + " Gaussians (" +
                     std::to_string(now) + (hide ? " hidden)" : " locked)"),
                 g);
      return;
    }
    SelectionGuard g = cur.guard;
    if (!(hide ? g.hidden : g.locked)) throw Error(hide ? "unhide: nothing is hidden" : "unlock: nothing is locked");
    (hide ? g.hidden : g.locked).reset();
    (hide ? g.hidden_count : g.locked_count) = 0;
    push_state(job, std::move(cur.parts), cur.grow, hide ? "showing every Gaussian again" : "unlocked every Gaussian",
               g);
  });
}

std::uint64_t SelectionSession::target_masks(std::vector<View> views, fs::path dir) {
  return submit([this, views = std::move(views), dir](const Job& job) {
    const SelectionState cur = current_state();
    if (!cur.mask) throw Error("target masks: nothing is selected");
    if (views.empty()) throw Error("target masks: no training views");
    Context& c = prepared(job.model);
    // Masks of what the viewports show: hidden Gaussians neither count nor cover the target.
    const GaussianModel& shown = c.shown_model(cur.guard.hidden);
    fs::create_directories(dir);
    for (const View& v : views)
      save_mask_png(dir / object_mask_file_name(v.name),
                    selection_view_mask(shown, *cur.mask, v.camera, job.model->settings()));
    message("wrote " + std::to_string(views.size()) + " object masks to " + dir.string(), false);
    const MaskVotes votes = labels_from_masks(shown, load_masked_views(views, dir), {}, job.model->settings());
    const SelectionResult r = close_selection(c.selection.points, votes.selected);
    if (r.summary.seeds == 0)
      throw Error("target masks: no Gaussian falls inside the written masks in at least half of the views where it "
                  "is visible (is the selection visible in the training views?)");
    push_part(job, region_part(r.mask, "masks", "target masks in " + dir.string()), SelectMode::Replace,
              r.summary.describe("by the target masks' votes"));
  });
}

}  // namespace goris::ui
