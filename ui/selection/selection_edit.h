#pragma once
// The editor's selection as a short list of edits over one model (docs/design/architecture.md, The editor),
// evaluated with the library's selection rules (removal/selection/selection.h):
//
//   click        the Gaussian under the cursor; with the slider g > 0 grown over similar neighbours
//                (grow_selection) and closed (close_selection), as `goris select --click --grow g`
//   labels/masks a rule's closed result (select_by_label, labels_from_masks), or a saved selection
//   mode         replace starts over, add unions, remove subtracts (plain / shift / ctrl click)
//   region       a rectangle, lasso or brush stroke of a view, a sphere or box, a colour range
//                (ui/selection/region_masks.h), or a whole-selection edit (invert, one grow / shrink step):
//                a fixed mask, not grown
//   slider g     in [-1, 1]: g > 0 is the grow of every clicked region (moving it re-runs the growth);
//                g < 0 erodes the whole selection by ceil(-g * kMaxShrinkSteps) shrink_selection steps
//   guard        hidden and locked Gaussians: never part of the result (hidden ones are also not drawn)
//
// Every edit is one entry of a SelectionHistory (undo / redo); a slider drag merges into one entry.
// Nothing here touches threads or the GUI.
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/scene/selection_points.h"
#include "removal/selection/selection_grow.h"

namespace goris::ui {

enum class SelectMode { Replace, Add, Remove };
const char* select_mode_id(SelectMode m);  // "replace", "add", "remove"
std::optional<SelectMode> select_mode_from_id(const std::string& id);

struct SelectionPart {
  SelectMode mode = SelectMode::Replace;
  SelectionMask seeds;
  bool grows = false;  // a click: grown with the slider
  std::string method;  // "click", "labels", "masks", "saved", "region", ... (selection.json's method)
  std::string what;    // for the panel, e.g. "click at (40, 52)", "labels > 0.3"
};

// Gaussians no edit selects: hidden ones (the viewports do not draw them) and locked ones. Null = none.
struct SelectionGuard {
  std::shared_ptr<const SelectionMask> hidden, locked;
  std::size_t hidden_count = 0, locked_count = 0;
};

struct SelectionState {
  std::vector<SelectionPart> parts;  // since the last replace
  float grow = 0.5f;
  std::shared_ptr<const SelectionMask> mask;  // the result; null = nothing selected
  std::size_t selected = 0;
  SelectionGuard guard;
};

constexpr int kMaxShrinkSteps = 4;
constexpr float kDefaultGrow = 0.5f;

// What evaluating needs of the model.
struct SelectionModel {
  SelectionPoints points;
  SelectionGraph graph;
};

// The selection `parts` and the slider describe, less what `guard` hides or locks. A replace part drops the
// parts before it. Throws goris::Error for a slider outside [-1, 1], parts or guard masks of the wrong size,
// or a growth that leaks into more than half of the scene (as `goris select` refuses it).
SelectionState evaluate_selection(const SelectionModel& model, std::vector<SelectionPart> parts, float grow,
                                  SelectionGuard guard = {});

// `guard` with the Gaussians of `mask` added to its hidden (hide = true) or locked ones.
SelectionGuard guard_adding(SelectionGuard guard, const SelectionMask& mask, bool hide);

// The undo stack: states, the current one last-but-redo. Bounded: the oldest entries go first.
class SelectionHistory {
 public:
  explicit SelectionHistory(std::size_t capacity = 64);
  // Starts over with `initial` as the only entry (not undoable).
  void reset(SelectionState initial);
  const SelectionState& current() const { return entries_[index_]; }
  // Adds `s` after the current entry, dropping the redo tail. `merge`: replaces the current entry instead,
  // when it was pushed last and nothing was undone since (a slider drag's later edits: one undo step).
  void push(SelectionState s, bool merge = false);
  bool can_undo() const { return index_ > 0; }
  bool can_redo() const { return index_ + 1 < entries_.size(); }
  bool undo();  // false when there is nothing to undo
  bool redo();
  std::size_t size() const { return entries_.size(); }

 private:
  std::size_t capacity_;
  std::vector<SelectionState> entries_{SelectionState{}};
  std::size_t index_ = 0;
  bool can_merge_ = false;  // the current entry was pushed last
};

}  // namespace goris::ui
