#pragma once
// The selection of the shown model for the editor (docs/design/architecture.md, The editor): click -> picked
// Gaussian -> grown selection, shift-click adds, ctrl-click removes, the grow / shrink slider, the learned
// labels or the data set's object masks instead, the tools' regions, hide / lock (ui/selection/), undo /
// redo of every edit, and saving RUN/selection.json for `goris remove`. The edits themselves are
// ui/selection/selection_edit.h; this class runs them on a worker thread (the picker's BVH, the kNN graph and the mask
// votes take a while on large models) so the GUI never waits: it submits an edit, gets a job id, and polls.
//
// A selection is a mask over one model's Gaussians: binding another model clears it (and its history).
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "core/io/camera.h"
#include "core/io/dataset.h"
#include "ui/display/model_snapshot.h"
#include "ui/selection/region_masks.h"
#include "ui/selection/selection_edit.h"

namespace goris::ui {

struct FlowProgress;
struct FlowResult;

// What the panel and the viewports show of the selection.
struct SelectionView {
  std::shared_ptr<const SelectionMask> mask;  // null = nothing selected
  std::size_t selected = 0, total = 0;
  float grow = kDefaultGrow;
  std::vector<std::string> parts;  // what the selection was made of, e.g. "click at (40, 52)" (+ / - prefixed)
  bool can_undo = false, can_redo = false;
  bool saved = false;  // the current mask is the one in RUN/selection.json
  std::shared_ptr<const SelectionMask> hidden;  // not drawn (null = none)
  std::size_t hidden_count = 0, locked_count = 0;
};

class SelectionSession {
 public:
  SelectionSession();
  ~SelectionSession();  // finishes the edit in flight, drops the queued ones
  SelectionSession(const SelectionSession&) = delete;
  SelectionSession& operator=(const SelectionSession&) = delete;

  // The model the selection belongs to (null: none). Another model than the bound one clears the selection
  // and its history and drops queued edits. `run_dir` (empty = none) is where save() writes;
  // `model_source` names the file the model came from (recorded in selection.json). With `load_saved`, a
  // RUN/selection.json made on this very model becomes the selection (one that does not match is reported).
  void bind(std::shared_ptr<const ModelSnapshot> model, const std::filesystem::path& run_dir,
            const std::string& model_source, bool load_saved);
  const std::shared_ptr<const ModelSnapshot>& model() const { return model_; }

  // Edits, queued for the worker (each one undo step); they return a job id for finished()/job_error().
  // `camera` and (u, v) (continuous pixel coordinates) say where the click was.
  std::uint64_t click(const Camera& camera, float u, float v, SelectMode mode);
  // The slider; `merge` folds consecutive slider edits into one undo step (a drag).
  std::uint64_t set_grow(float grow, bool merge);
  std::uint64_t from_labels(float threshold = 0.3f);
  // Votes of the Gaussian centres in these views' object masks (labels_from_masks), closed: the data set's
  // masks, or those in `dir` (mask_XXX.png).
  std::uint64_t from_masks(std::vector<View> views, std::optional<std::filesystem::path> dir = std::nullopt);

  // The selection tools (ui/selection/session_tools.cpp): a region in `mode` (ui/selection/region_masks.h).
  std::uint64_t screen_region(ScreenRegion region, SelectMode mode);
  std::uint64_t volume(VolumeRegion volume, SelectMode mode);
  std::uint64_t colour(glm::vec3 reference, float max_distance, SelectMode mode);
  // Everything else (hidden and locked Gaussians stay out).
  std::uint64_t invert();
  // `rings` graph steps out (> 0, dilate_selection) or in (< 0, shrink_selection) of the whole selection.
  std::uint64_t step(int rings);
  // Hides or locks the selected Gaussians (the selection becomes empty), or shows / unlocks all again.
  std::uint64_t hide_selected();
  std::uint64_t lock_selected();
  std::uint64_t unhide_all();
  std::uint64_t unlock_all();
  // Writes every view's object mask of the selection into `dir` (mask_XXX.png, selection_view_mask), then
  // selects by those masks' votes (as `goris select --masks DIR`): the target a removal takes.
  std::uint64_t target_masks(std::vector<View> views, std::filesystem::path dir);
  // The two-click flow's evaluation (ui/selection/two_click_session.cpp): `goris select --click`'s regions
  // of out->clicks in `views` lifted to a selection that replaces the current one, then every view's object
  // mask written into out->dir; fills `out`, follows `progress` (whose cancel stops it). `glossy_masks`, called
  // on the worker, gives the views' glossy masks the run trained with (one per view; null or empty for none;
  // select_by_click_regions reads them); empty function: none.
  using GlossyMasks = std::function<std::shared_ptr<const std::vector<std::vector<float>>>()>;
  std::uint64_t click_regions(std::vector<View> views, DatasetOptions photos, std::shared_ptr<FlowResult> out,
                              std::shared_ptr<FlowProgress> progress, GlossyMasks glossy_masks = {});
  std::uint64_t clear();
  std::uint64_t undo();
  std::uint64_t redo();

  // Writes RUN/selection.json (+ .npy) with write_selection; returns its path. Synchronous; throws
  // goris::Error while an edit is queued, with nothing selected, or without a run folder.
  std::filesystem::path save();

  bool busy() const;
  bool finished(std::uint64_t job) const;
  // The error of a finished job (nullopt: it succeeded, or it is not known).
  std::optional<std::string> job_error(std::uint64_t job) const;
  SelectionView view() const;
  std::uint64_t version() const;  // grows whenever view() changes
  // Messages for the status bar since the last call (text, is_error).
  std::vector<std::pair<std::string, bool>> take_messages();

 private:
  struct Context;
  struct Job {
    std::uint64_t id = 0, generation = 0;
    std::shared_ptr<const ModelSnapshot> model;
    std::function<void(const Job&)> run;
    bool merge = false;  // set_grow merging
  };
  std::uint64_t submit(std::function<void(const Job&)> run, bool merge = false);
  std::uint64_t step_history(bool forward);  // undo / redo
  void loop();
  Context& prepared(const std::shared_ptr<const ModelSnapshot>& model);  // worker thread
  SelectionState current_state() const;
  // Evaluates the edit and makes it the current state, unless the model changed meanwhile.
  // `guard`: the hidden / locked Gaussians of the new state (default: the current state's).
  void push_state(const Job& job, std::vector<SelectionPart> parts, float grow, const std::string& done,
                  std::optional<SelectionGuard> guard = std::nullopt);
  // Hide / lock the selection (add) or show / unlock everything (!add).
  std::uint64_t change_guard(bool hide, bool add);
  // A region edit: `part` in `mode` added to the current parts.
  void push_part(const Job& job, SelectionPart part, SelectMode mode, const std::string& done);
  void message(const std::string& text, bool error);

  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<Job> queue_;
  bool running_job_ = false, quit_ = false;
  std::uint64_t next_id_ = 1, generation_ = 0, version_ = 0;
  std::map<std::uint64_t, std::string> results_;  // finished jobs -> error text (empty = success)
  std::shared_ptr<const ModelSnapshot> model_;
  std::filesystem::path run_dir_;
  std::string model_source_;
  SelectionHistory history_;
  std::shared_ptr<const SelectionMask> saved_mask_;
  std::vector<std::pair<std::string, bool>> messages_;
  std::unique_ptr<Context> context_;  // worker thread only
  std::thread thread_;
};

}  // namespace goris::ui
