#include "ui/selection/selection_edit.h"

#include <cmath>
#include <cstdio>

#include "core/util/error.h"
#include "removal/selection/selection_labels.h"
#include "removal/selection/selection_ops.h"

namespace goris::ui {

const char* select_mode_id(SelectMode m) {
  switch (m) {
    case SelectMode::Replace:
      return "replace";
    case SelectMode::Add:
      return "add";
    case SelectMode::Remove:
      return "remove";
  }
  return "replace";
}

std::optional<SelectMode> select_mode_from_id(const std::string& id) {
  for (SelectMode m : {SelectMode::Replace, SelectMode::Add, SelectMode::Remove})
    if (id == select_mode_id(m)) return m;
  return std::nullopt;
}

namespace {

void check_size(const std::shared_ptr<const SelectionMask>& m, std::size_t n, const char* what) {
  if (m && m->size() != n)
    throw Error("selection", std::string("the ") + what + " mask has " + std::to_string(m->size()) + " entries for " +
                                 std::to_string(n) + " Gaussians");
}

}  // namespace

SelectionGuard guard_adding(SelectionGuard guard, const SelectionMask& mask, bool hide) {
  std::shared_ptr<const SelectionMask>& target = hide ? guard.hidden : guard.locked;
  const SelectionMask merged = target ? combine_selections(*target, mask, Combine::Union) : mask;
  const std::size_t n = count_selected(merged);
  target = n > 0 ? std::make_shared<const SelectionMask>(merged) : nullptr;
  (hide ? guard.hidden_count : guard.locked_count) = n;
  return guard;
}

SelectionState evaluate_selection(const SelectionModel& model, std::vector<SelectionPart> parts, float grow,
                                  SelectionGuard guard) {
  if (!(grow >= -1.0f && grow <= 1.0f))
    throw Error("selection", "the grow slider " + std::to_string(grow) + " is outside -1..1");
  const std::size_t n = model.points.size();
  check_size(guard.hidden, n, "hidden");
  check_size(guard.locked, n, "locked");
  // Only the parts since the last replace matter.
  for (std::size_t k = parts.size(); k-- > 0;)
    if (parts[k].mode == SelectMode::Replace) {
      parts.erase(parts.begin(), parts.begin() + std::ptrdiff_t(k));
      break;
    }
  SelectionState s;
  s.grow = grow;
  SelectionMask result(n, 0);
  for (const SelectionPart& p : parts) {
    if (p.seeds.size() != n)
      throw Error("selection", "'" + p.what + "' has " + std::to_string(p.seeds.size()) + " entries for " +
                                   std::to_string(n) + " Gaussians");
    SelectionMask region = p.seeds;
    if (p.grows && grow > 0.0f) {
      GrowSettings gs;
      gs.grow = grow;
      const GrowResult g = grow_selection(model.points, model.graph, p.seeds, gs);
      // Growing (or closing what grew) past half of the scene is a leak, as `goris select` judges it.
      std::size_t got = g.seeds + g.added;
      if (!g.hit_limit) {
        region = close_selection(model.points, g.mask).mask;
        got = count_selected(region);
      }
      if (g.hit_limit || got > g.limit) {
        char b[256];
        std::snprintf(b, sizeof b,
                      "growing '%s' by %.2f selects more than half of the scene (%zu Gaussians): it leaks into the "
                      "surroundings - lower the grow slider",
                      p.what.c_str(), double(grow), got);
        throw Error("selection", b);
      }
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (p.mode == SelectMode::Remove)
        result[i] = result[i] && !region[i];
      else if (p.mode == SelectMode::Add)
        result[i] = result[i] || region[i];
      else
        result[i] = region[i];
    }
  }
  if (grow < 0.0f) result = shrink_selection(model.graph, result, int(std::ceil(-grow * kMaxShrinkSteps)));
  for (const auto& off : {guard.hidden, guard.locked})
    if (off) result = combine_selections(result, *off, Combine::Subtract);
  s.guard = std::move(guard);
  s.parts = std::move(parts);
  s.selected = count_selected(result);
  if (s.selected > 0) s.mask = std::make_shared<const SelectionMask>(std::move(result));
  return s;
}

SelectionHistory::SelectionHistory(std::size_t capacity) : capacity_(capacity < 2 ? 2 : capacity) {}

void SelectionHistory::reset(SelectionState initial) {
  entries_.assign(1, std::move(initial));
  index_ = 0;
  can_merge_ = false;
}

void SelectionHistory::push(SelectionState s, bool merge) {
  entries_.resize(index_ + 1);  // drop the redo tail
  if (merge && can_merge_ && index_ > 0) {
    entries_[index_] = std::move(s);
    return;
  }
  entries_.push_back(std::move(s));
  if (entries_.size() > capacity_) entries_.erase(entries_.begin());
  index_ = entries_.size() - 1;
  can_merge_ = true;
}

bool SelectionHistory::undo() {
  if (!can_undo()) return false;
  --index_;
  can_merge_ = false;
  return true;
}

bool SelectionHistory::redo() {
  if (!can_redo()) return false;
  ++index_;
  can_merge_ = false;
  return true;
}

}  // namespace goris::ui
