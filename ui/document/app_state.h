#pragma once
// The editor's document: what is open, what the viewports show and from where, the training session, the
// selection, the removal and the last click. Every user action (panels, mouse, keys, script lines) goes
// through these members, so the GUI and the scripted mode share one code path. No OpenGL or ImGui here.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/io/camera.h"
#include "render/maps/channels.h"
#include "ui/document/capture_job.h"
#include "ui/display/display_frame.h"
#include "ui/document/export_job.h"
#include "ui/display/model_snapshot.h"
#include "ui/display/orbit_camera.h"
#include "ui/document/removal_session.h"
#include "ui/document/scene_loader.h"
#include "ui/selection/selection_tools.h"
#include "ui/document/two_click_flow.h"
#include "ui/selection/selection_session.h"
#include "ui/document/settings_store.h"
#include "ui/document/trainer_session.h"

namespace goris::ui {

enum class CompareMode { Off, SideBySide, Slider };
const char* compare_mode_id(CompareMode m);
std::optional<CompareMode> compare_mode_from_id(const std::string& id);

class AppState {
 public:
  static constexpr int kMaxGrid = 8;

  explicit AppState(StudioSettings& settings);
  ~AppState();
  AppState(const AppState&) = delete;
  AppState& operator=(const AppState&) = delete;

  StudioSettings& settings() { return settings_; }

  // --- Opening (on a background thread; poll() completes it) ---
  // Throws goris::Error while training runs (stop it first) or while another open is in flight.
  void open(const std::filesystem::path& path);
  bool opening() const { return pending_open_.valid(); }
  std::string opening_path() const { return opening_path_.string(); }
  const OpenedScene* scene() const { return scene_ ? &*scene_ : nullptr; }
  // Grows with every successful open (the scene's address stays the same across opens).
  std::uint64_t scene_version() const { return scene_version_; }
  // The error of the last open that failed (cleared by the next open).
  const std::string& open_error() const { return open_error_; }

  // Once per frame: completes a finished open, picks up the trainer's newest snapshot, reports how training,
  // selection edits and removals went.
  void poll();

  // --- The model the viewports show: the opened run's, or the training session's newest snapshot ---
  std::shared_ptr<const ModelSnapshot> model() const { return model_; }
  std::uint64_t model_version() const { return model_version_; }

  // --- Training ---
  TrainerSession& session() { return session_; }
  const TrainerSession& session() const { return session_; }
  // The run folder of the next training; empty = a new folder under runs_root() for a data set.
  std::filesystem::path run_folder;
  // `set KEY VALUE` overrides for a new run (validated when added).
  void add_override(const std::string& key, const std::string& value);
  const std::vector<std::pair<std::string, std::string>>& overrides() const { return overrides_; }
  // Forgets the overrides of `key`: the Training panel's own field for it was edited.
  void drop_override(const std::string& key);
  // Trains until `iterations` in total, or `more` iterations beyond the run's current one.
  void start_training(int iterations, bool more);
  bool training_active() const;  // running, paused or stopping

  // The run folder the shown model belongs to (an opened run, or the one trained into); empty when none.
  std::filesystem::path current_run() const;

  // --- Selection (ui/selection/selection_session.h) of the shown model ---
  SelectionSession& selection() { return selection_; }
  const SelectionSession& selection() const { return selection_; }
  // Why selection edits are refused now (training runs, nothing shown, ...); null when they are not.
  const char* selection_blocked() const;
  // A click at (x, y) pixels of the main viewport's image shown at display_w x display_h: reports what lies
  // there (as click()) and picks the Gaussian under it for the selection in `mode`; returns the selection
  // job. Throws goris::Error without a frame, outside the image, or when selecting is blocked.
  std::uint64_t select_click(float x, float y, float display_w, float display_h, SelectMode mode);
  // The mouse's click: as select_click, but when selecting is blocked the reason is only reported (returns 0).
  std::uint64_t mouse_click(float x, float y, float display_w, float display_h, SelectMode mode);
  std::uint64_t select_grow(float grow, bool merge = false);
  std::uint64_t select_labels();
  std::uint64_t select_masks();  // the data set's training object masks (mask_XXX.png)
  std::uint64_t select_clear();
  std::uint64_t undo_selection();
  std::uint64_t redo_selection();
  std::filesystem::path save_selection();  // RUN/selection.json

  // --- Selection tools (ui/selection/selection_tools.h; defined in ui/document/tool_actions.cpp) ---
  SelectionTools tools;
  // Shapes on the main viewport's image shown at `display` (w, h): points in its window pixels. Only what
  // the view shows is taken unless tools.through_all. Throw goris::Error without a frame or when selecting
  // is blocked.
  std::uint64_t select_rect(glm::vec2 a, glm::vec2 b, glm::vec2 display, SelectMode mode);
  std::uint64_t select_polygon(const std::vector<glm::vec2>& points, glm::vec2 display, SelectMode mode);
  std::uint64_t select_brush(const std::vector<glm::vec2>& stroke, float radius, glm::vec2 display, SelectMode mode);
  std::uint64_t select_volume(const VolumeRegion& volume, SelectMode mode);
  std::uint64_t select_colour(glm::vec3 rgb, float distance, SelectMode mode);
  std::uint64_t select_invert();
  std::uint64_t select_step(int rings);  // > 0 grows, < 0 shrinks by that many graph steps
  std::uint64_t hide_selected();
  std::uint64_t lock_selected();
  std::uint64_t unhide_all();
  std::uint64_t unlock_all();
  // Use as target masks: every training view's object mask of the selection into `dir` (empty:
  // RUN/target_masks), and the selection becomes their votes, which Remove then takes.
  std::uint64_t use_as_target_masks(std::filesystem::path dir);
  // The guided two-click flow (ui/document/two_click_flow.h); poll() keeps it in step.
  TwoClickFlow two_click;
  // Puts the sphere and box at the last picked point (else the surface in the middle of the view) unless
  // placed already.
  void place_volumes_if_needed();

  // --- Removal (stage 2, ui/document/removal_session.h) of the current run ---
  RemovalSession& removal() { return removal_; }
  const RemovalSession& removal() const { return removal_; }
  // Starts the removal of current_run() with the settings' options (fine-tune iterations: `iterations`
  // when positive). An unsaved selection is saved first, so the removal uses what is shown.
  void start_removal(int iterations = 0);
  // Whether poll() has taken in the end of the last removal (masks folder, messages).
  bool removal_reported() const { return removal_.runs_ended() == removal_runs_seen_; }
  // When a removal finishes, the cleaned scene (RUN/removal) is opened in its place, the view kept.

  // --- Before / after of an opened cleaned scene (OpenedScene::before_model: the run with the target) ---
  bool has_before() const { return scene_ && scene_->before_model; }
  bool showing_before() const { return has_before() && model_ == scene_->before_model; }
  // Shows the scene with the target (true) or the cleaned one; throws goris::Error without a before model.
  void show_before(bool before);
  // The compare modes (side by side, slider) set the cleaned scene against the scene with the target when
  // there is one and this is true; against the nearest photo otherwise.
  bool compare_with_before = true;
  bool comparing_with_before() const { return compare_with_before && has_before() && compare != CompareMode::Off; }

  // RUN/removal (or the opened cleaned scene itself) when it holds stage 2's masks; empty otherwise.
  const std::filesystem::path& removal_masks_dir() const { return removal_masks_dir_; }

  // --- Export (ui/document/export_job.h) of the current run or of its cleaned scene ---
  ExportJob& exporter() { return exporter_; }
  const ExportJob& exporter() const { return exporter_; }
  bool show_export_dialog = false;   // File > Export..., the Removal panel's Export, `export_dialog`
  bool export_from_removal = false;  // the dialog's source: the run, or its stage-2 result RUN/removal
  // RUN/removal of the current run when it holds a cleaned scene (a run folder with a model); else empty.
  const std::filesystem::path& removal_result() const { return removal_result_; }
  // The run folder an export reads: removal_result() when chosen and present, else current_run().
  std::filesystem::path export_source() const;
  // What the dialog's fields (the settings' export_* choices) ask for; relative paths are taken inside
  // export_source(). Throws goris::Error for a chosen part whose path is empty or an unknown render path.
  ExportRequest export_request() const;
  // The dialog's Export button (and the script's `export`): starts export_request() on the worker. Throws
  // goris::Error when nothing can be exported now (no run, training runs, an export runs, a bad choice).
  void start_export();
  // Whether poll() has taken in the end of the last export (its message).
  bool export_reported() const { return exporter_.runs_ended() == export_runs_seen_; }

  // --- Capture import (ui/document/capture_job.h): photos or a video to a data set, opened when it is done ---
  CaptureJob& importer() { return importer_; }
  const CaptureJob& importer() const { return importer_; }
  // The Open panel's import fields (input, output, max images, resolution, matcher, masks); the script's
  // `import_capture` fills them in too, so the panel shows what runs.
  capture::CaptureOptions import_form;
  // Starts the import. Throws goris::Error while one runs, training or a removal runs, or a scene opens.
  void start_import(const capture::CaptureOptions& options);
  // Whether poll() has taken in the end of the last import (its message, the open of its data set).
  bool import_reported() const { return importer_.runs_ended() == import_runs_seen_; }

  // --- View ---
  OrbitCamera orbit;
  std::optional<Camera> snapped;  // the exact data set camera, until the view moves
  std::string snapped_name;       // e.g. "train 3 (r_003)"
  size_t snapped_index = 0;       // which camera (valid while snapped)
  bool snapped_test = false;
  std::string snapped_view;  // its view name, e.g. "r_003"
  void snap(size_t index, bool test);
  void camera_moved() { snapped.reset(); }
  // The camera of a render that fills a w x h box (letterboxed for a snapped camera's aspect), at most
  // settings().display_max_side pixels on its longest side.
  Camera render_camera(float box_w, float box_h) const;

  Channel main_channel = Channel::Final;
  std::vector<Channel> grid_channels;
  // viewport -1 = main, 0.. = grid tile. Throws goris::Error for a tile that does not exist or a channel
  // that cannot be shown now (naming why).
  void set_channel(int viewport, Channel c);
  ChannelContext channel_context() const;
  const char* channel_unavailable(Channel c) const { return goris::channel_unavailable(c, channel_context()); }
  void set_grid_count(int n);
  bool label_overlay = false;
  CompareMode compare = CompareMode::Off;
  float compare_split = 0.5f;
  void set_compare(CompareMode m, float split);

  // --- The frame on screen and clicks on it ---
  std::shared_ptr<const DisplayFrame> frame;  // set by the app when a render arrives
  std::optional<PickResult> last_pick;
  // A click at (x, y) pixels of the main viewport's image shown at display_w x display_h: what lies
  // there (selection builds on this). Throws goris::Error without a frame or outside the image.
  PickResult click(float x, float y, float display_w, float display_h);

  // --- Messages for the status bar (and stdout in scripted mode) ---
  void message(const std::string& text, bool error = false);
  const std::string& last_message() const { return last_message_; }
  bool last_message_is_error() const { return last_message_error_; }
  std::function<void(const std::string&, bool)> on_message;

 private:
  void finish_open();
  void show_model(std::shared_ptr<const ModelSnapshot> m);
  void require_selectable(const char* what) const;
  // An empty region of `kind` on the main frame's camera, through what the toggle says; throws as the
  // tools do when selecting is blocked or no image is shown.
  ScreenRegion screen_region(ScreenRegion::Kind kind, glm::vec2 display, const char* what) const;
  void find_removal_masks();

  StudioSettings& settings_;
  std::optional<OpenedScene> scene_;
  std::uint64_t scene_version_ = 0;
  std::future<OpenedScene> pending_open_;
  std::filesystem::path opening_path_;
  std::string open_error_;
  TrainerSession session_;
  JobState last_session_state_ = JobState::Idle;  // to report how a run ended, once
  std::uint64_t session_version_seen_ = 0;                // snapshots up to this one belong to an earlier document
  std::shared_ptr<const ModelSnapshot> model_;
  std::uint64_t model_version_ = 0;
  bool model_from_session_ = false;              // the shown model is the training session's
  JobState last_removal_state_ = JobState::Idle;
  std::vector<std::pair<std::string, std::string>> overrides_;
  // Declared after the trainer: destroyed first (their workers may still read the shown model).
  SelectionSession selection_;
  RemovalSession removal_;
  std::uint64_t removal_runs_seen_ = 0;
  std::filesystem::path removal_masks_dir_;
  std::filesystem::path removal_result_;
  bool keep_view_on_open_ = false;  // the next finish_open keeps the camera (the cleaned scene after Remove)
  ExportJob exporter_;  // reads its own copy of the run from disk: nothing shared with the display
  std::uint64_t export_runs_seen_ = 0;
  CaptureJob importer_;  // writes a new data set folder: nothing shared with the display
  std::uint64_t import_runs_seen_ = 0;
  std::string last_message_;
  bool last_message_error_ = false;
};

}  // namespace goris::ui
