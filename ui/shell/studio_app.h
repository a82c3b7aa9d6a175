#pragma once
// The editor: one window with a menu bar, the sidebar panels, the main viewport above a grid of tiles, a
// status bar and a debug overlay; the frame loop that ties the document (AppState) to the render worker,
// the textures and the viewports; and the scripted mode. app/studio/main.cpp only parses arguments.
#include <chrono>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ui/document/app_state.h"
#include "ui/display/channel_renderer.h"
#include "ui/shell/export_dialog.h"
#include "ui/shell/frame_limiter.h"
#include "ui/display/frame_textures.h"
#include "ui/panels/panel.h"
#include "ui/display/render_worker.h"
#include "ui/script/script_runner.h"
#include "ui/document/settings_store.h"
#include "ui/shell/studio_window.h"
#include "ui/viewport/viewport.h"

namespace goris::ui {

struct StudioOptions {
  std::string open_path;         // a data set or run folder to open at start (empty = none)
  std::filesystem::path script;  // --script FILE (empty = interactive)
  int width = 0, height = 0;     // window size (0 = the remembered one)
  double max_fps = 60.0;
};

class StudioApp final : public ScriptHost {
 public:
  // Loads the settings and the script (a bad script throws goris::Error before any window opens), then
  // opens the window (throws goris::Error("display", ...) without a display).
  explicit StudioApp(const StudioOptions& options);
  ~StudioApp() override;

  // Runs until the window closes or the script quits; returns the exit status (1 when the script failed).
  int run();

  // ScriptHost
  AppState& state() override { return *state_; }
  bool settled() const override;
  glm::vec2 main_image_size() const override;
  glm::vec2 main_image_origin() const override { return {main_.image_rect().x, main_.image_rect().y}; }
  void set_scripted_mouse(const std::optional<ScriptedMouse>& mouse) override { scripted_mouse_ = mouse; }
  void request_screenshot(const std::filesystem::path& png) override;
  bool screenshot_pending() const override { return screenshot_path_.has_value(); }
  std::optional<std::string> screenshot_error() const override { return screenshot_error_; }
  void quit() override;
  void show_panels(const std::vector<std::string>& titles) override;
  FrameStats training_frame_stats() const override { return training_frames_; }

 private:
  void frame();
  void update_layout();
  void request_render();
  void receive_frame();
  void update_photo();
  void update_before_image();  // update_photo when comparing with the scene with the target
  void update_removal_masks();
  void handle_keys(double dt);
  void draw_menu();
  void draw_sidebar();
  void draw_viewports();
  void draw_status();
  void draw_debug_overlay();
  void take_screenshot();
  bool busy() const;
  // The frame cap: full while someone interacts or the display changes, lower while only background
  // work (training, removal, selection edits) runs, which then gets the CPU.
  void pace_frames();

  StudioOptions options_;
  StudioSettings settings_;
  std::optional<std::vector<ScriptAction>> script_actions_;
  std::unique_ptr<StudioWindow> window_;  // first: GL objects below die before the context
  std::unique_ptr<AppState> state_;
  std::unique_ptr<RenderWorker> worker_;
  std::unique_ptr<RenderWorker> before_worker_;  // the scene with the target, for the compare modes
  FrameTextures textures_;
  std::unique_ptr<ChannelRenderer> renderer_;
  Viewport main_{-1};
  std::vector<std::unique_ptr<Viewport>> grid_;
  std::vector<std::unique_ptr<Panel>> panels_;
  ExportDialog export_dialog_;
  std::optional<std::vector<bool>> panels_open_;  // set by a script: applied at the next sidebar draw
  std::unique_ptr<ScriptRunner> script_;
  FrameLimiter limiter_;
  CameraMode camera_mode_ = CameraMode::Orbit;
  std::optional<ScriptedMouse> scripted_mouse_;

  // Layout of this frame (window pixels).
  Rect sidebar_, main_rect_, status_rect_;
  std::vector<Rect> grid_rects_;
  float menu_height_ = 0;

  // What the last render request asked for, to request again only on a change.
  const ModelSnapshot* requested_model_ = nullptr;
  std::uint64_t requested_model_version_ = 0;
  std::shared_ptr<const SelectionMask> requested_selection_, requested_hidden_;
  std::optional<Camera> requested_camera_;
  std::uint64_t requested_id_ = 0;
  std::chrono::steady_clock::time_point last_request_time_{};
  double last_upload_ms_ = 0;
  std::string render_error_;

  // The comparison photo on the GPU: which scene and training view it is.
  std::uint64_t photo_scene_ = 0;  // AppState::scene_version() of the photo
  std::optional<size_t> photo_index_;
  glm::vec3 photo_background_{0.0f};
  // The comparison image when it is the scene with the target (AppState::comparing_with_before): what was
  // asked of before_worker_ and which answer is on the GPU.
  const ModelSnapshot* before_requested_model_ = nullptr;
  std::optional<Camera> before_requested_camera_;
  std::uint64_t before_requested_id_ = 0, before_shown_id_ = 0;

  // Settling for scripts: frames since anything shown last changed.
  struct DisplaySignature {
    std::uint64_t textures = 0, model = 0, selection = 0;
    Channel main = Channel::Final;
    std::vector<Channel> grid;
    CompareMode compare = CompareMode::Off;
    float split = 0;
    bool grid_shown = false, sidebar = false, label_overlay = false, export_dialog = false;
    bool operator==(const DisplaySignature&) const = default;
  };
  DisplaySignature display_signature_;
  int stable_frames_ = 0;
  std::optional<std::filesystem::path> screenshot_path_;
  std::optional<std::string> screenshot_error_;
  int exit_status_ = 0;
  FrameStats training_frames_;  // frames while the trainer ran
  bool training_seen_ = false;  // the session was active last frame
  std::chrono::steady_clock::time_point last_frame_time_;
  std::chrono::steady_clock::time_point last_input_time_{};
};

}  // namespace goris::ui
