#include "ui/shell/studio_app.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

#include "ui/gl/gl_api.h"
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include "core/io/dataset.h"
#include "core/io/image.h"
#include "core/util/error.h"
#include "ui/display/dataset_cameras.h"
#include "ui/panels/cameras_panel.h"
#include "ui/panels/display_panel.h"
#include "ui/panels/open_panel.h"
#include "ui/panels/plots_panel.h"
#include "ui/panels/removal_panel.h"
#include "ui/panels/selection_panel.h"
#include "ui/panels/two_click_panel.h"
#include "ui/panels/training_panel.h"
#include "ui/shell/screenshot.h"
#include "ui/display/shader_paths.h"

namespace goris::ui {

namespace fs = std::filesystem;

namespace {

bool same_camera(const Camera& a, const Camera& b) {
  return a.width == b.width && a.height == b.height && a.fx == b.fx && a.fy == b.fy && a.cx == b.cx && a.cy == b.cy &&
         a.R == b.R && a.t == b.t;
}

}  // namespace

StudioApp::StudioApp(const StudioOptions& options) : options_(options), limiter_(options.max_fps) {
  try {
    settings_ = load_settings(settings_path());
  } catch (const Error& e) {
    std::fprintf(stderr, "warning: %s; using default settings\n", e.what());
  }
  if (!options_.script.empty()) script_actions_ = load_script(options_.script);
  const int w = options_.width > 0 ? options_.width : settings_.window_width;
  const int h = options_.height > 0 ? options_.height : settings_.window_height;
  window_ = std::make_unique<StudioWindow>(w, h, "GOR-IS Studio");
  textures_.create_turbo_table();
  renderer_ = std::make_unique<ChannelRenderer>(find_shader_dir());
  state_ = std::make_unique<AppState>(settings_);
  worker_ = std::make_unique<RenderWorker>();
  before_worker_ = std::make_unique<RenderWorker>();
  for (int i = 0; i < AppState::kMaxGrid; ++i) grid_.push_back(std::make_unique<Viewport>(i));
  // The sidebar, top to bottom: the workflow's steps, then the view's settings.
  panels_.push_back(std::make_unique<OpenPanel>());
  panels_.push_back(std::make_unique<TrainingPanel>());
  panels_.push_back(std::make_unique<PlotsPanel>());
  panels_.push_back(std::make_unique<SelectionPanel>());
  panels_.push_back(std::make_unique<TwoClickPanel>());
  panels_.push_back(std::make_unique<RemovalPanel>());
  panels_.push_back(std::make_unique<CamerasPanel>(camera_mode_));
  panels_.push_back(std::make_unique<DisplayPanel>());
  if (script_actions_) {
    script_ = std::make_unique<ScriptRunner>(std::move(*script_actions_), options_.script.string());
    state_->on_message = [](const std::string& text, bool error) {
      std::fprintf(error ? stderr : stdout, "%s\n", text.c_str());
      std::fflush(error ? stderr : stdout);
    };
  }
  if (!options_.open_path.empty()) state_->open(options_.open_path);
}

StudioApp::~StudioApp() {
  // Remember the window and the choices; a failure to save must not hide the session's real outcome.
  const glm::ivec2 size = window_->window_size();
  if (size.x > 0 && size.y > 0) {
    settings_.window_width = size.x;
    settings_.window_height = size.y;
  }
  try {
    save_settings(settings_path(), settings_);
  } catch (const Error& e) {
    std::fprintf(stderr, "warning: %s\n", e.what());
  }
  worker_.reset();
  state_.reset();  // stops training (a checkpoint is written) before the window goes
}

void StudioApp::quit() { window_->request_close(); }

void StudioApp::show_panels(const std::vector<std::string>& titles) {
  auto lower = [](std::string s) {
    for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
    return s;
  };
  std::vector<bool> open(panels_.size(), false);
  for (const std::string& t : titles) {
    bool found = false;
    for (size_t i = 0; i < panels_.size(); ++i)
      if (lower(panels_[i]->title()) == lower(t)) open[i] = found = true;
    if (!found) {
      std::string known;
      for (const auto& p : panels_) known += (known.empty() ? "" : ", ") + std::string(p->title());
      throw Error("panels: there is no panel '" + t + "' (" + known + ")");
    }
  }
  panels_open_ = std::move(open);
}

int StudioApp::run() {
  last_frame_time_ = std::chrono::steady_clock::now();
  while (!window_->should_close()) {
    window_->process_events(busy() ? 0.0 : 0.25);
    frame();
  }
  return exit_status_;
}

bool StudioApp::busy() const {
  if (script_ && script_->status() == ScriptRunner::Status::Running) return true;
  const JobState s = state_->session().state();
  if (s == JobState::Running || s == JobState::Cancelling) return true;
  if (state_->opening() || !worker_->idle() || stable_frames_ < 3) return true;
  if (state_->removal().active() || state_->selection().busy() || state_->exporter().active() ||
      state_->importer().active())
    return true;
  return ImGui::IsAnyMouseDown() || glfwGetKey(window_->handle(), GLFW_KEY_W) == GLFW_PRESS ||
         glfwGetKey(window_->handle(), GLFW_KEY_A) == GLFW_PRESS ||
         glfwGetKey(window_->handle(), GLFW_KEY_S) == GLFW_PRESS ||
         glfwGetKey(window_->handle(), GLFW_KEY_D) == GLFW_PRESS ||
         glfwGetKey(window_->handle(), GLFW_KEY_Q) == GLFW_PRESS ||
         glfwGetKey(window_->handle(), GLFW_KEY_E) == GLFW_PRESS;
}

void StudioApp::pace_frames() {
  // Frames cost CPU (a lot under a software GL): while nobody interacts and only engine work runs, a
  // progress display needs no more than this many.
  constexpr double kBackgroundFps = 20.0;
  const ImGuiIO& io = ImGui::GetIO();
  const auto now = std::chrono::steady_clock::now();
  bool input = io.MouseDelta.x != 0 || io.MouseDelta.y != 0 || io.MouseWheel != 0 || ImGui::IsAnyMouseDown() ||
               io.WantTextInput;
  for (bool down : io.KeysDown) input |= down;
  if (input) last_input_time_ = now;
  const bool recent_input = now - last_input_time_ < std::chrono::seconds(1);
  limiter_.set_target_fps(recent_input || stable_frames_ < 3 ? options_.max_fps : kBackgroundFps);
}

void StudioApp::frame() {
  limiter_.begin_frame();
  const auto now = std::chrono::steady_clock::now();
  const double dt = std::min(std::chrono::duration<double>(now - last_frame_time_).count(), 0.1);
  last_frame_time_ = now;

  // Frame times while the trainer runs, restarted with each training (the debug overlay shows them).
  const bool training = state_->session().active();
  if (training && !training_seen_) training_frames_ = {};
  if (training && limiter_.frames() > 1) {
    FrameStats& f = training_frames_;
    f.mean_ms = (f.mean_ms * double(f.frames) + limiter_.last_frame_ms()) / double(f.frames + 1);
    f.max_ms = std::max(f.max_ms, limiter_.last_frame_ms());
    ++f.frames;
  }
  training_seen_ = training;

  window_->begin_frame(scripted_mouse_);
  const std::uint64_t scene_before = state_->scene_version();
  state_->poll();
  if (state_->scene_version() != scene_before) {
    try {
      save_settings(settings_path(), settings_);  // the recent paths survive a crash
    } catch (const Error& e) {
      state_->message(std::string("settings: ") + e.what(), true);
    }
  }
  update_layout();
  handle_keys(dt);
  request_render();
  receive_frame();
  update_photo();
  update_removal_masks();

  // Anything shown changed? (Scripts wait for a few quiet frames before the next line.)
  DisplaySignature sig{textures_.version,       state_->model_version(), state_->selection().version(),
                       state_->main_channel,    state_->grid_channels,   state_->compare,
                       state_->compare_split,   settings_.show_grid,     settings_.show_sidebar,
                       state_->label_overlay,   state_->show_export_dialog};
  if (sig != display_signature_) {
    display_signature_ = std::move(sig);
    stable_frames_ = 0;
  } else {
    ++stable_frames_;
  }

  if (script_ && script_->status() == ScriptRunner::Status::Running) {
    if (script_->step(*this) == ScriptRunner::Status::Failed) {
      std::fprintf(stderr, "error: %s\n", script_->error().c_str());
      exit_status_ = 1;
    }
  }
  // A script ends the editor at its last line, with or without `quit`.
  if (script_ && script_->status() != ScriptRunner::Status::Running) window_->request_close();

  draw_menu();
  if (settings_.show_sidebar) draw_sidebar();
  draw_viewports();
  draw_status();
  export_dialog_.draw(*state_);
  if (settings_.show_debug_overlay) draw_debug_overlay();
  window_->render();
  if (screenshot_path_) take_screenshot();
  window_->present();
  pace_frames();
  limiter_.end_frame_and_sleep();
}

void StudioApp::update_layout() {
  const ImGuiIO& io = ImGui::GetIO();
  LayoutInput in;
  in.width = io.DisplaySize.x;
  in.height = io.DisplaySize.y;
  menu_height_ = ImGui::GetFrameHeight();
  in.menu_height = menu_height_;
  in.status_height = ImGui::GetFrameHeight() + 4;
  in.sidebar = settings_.show_sidebar;
  in.grid_count = settings_.show_grid ? int(state_->grid_channels.size()) : 0;
  const StudioLayout l = compute_layout(in);
  sidebar_ = l.sidebar;
  main_rect_ = l.main;
  grid_rects_ = l.grid;
  status_rect_ = l.status;
}

void StudioApp::request_render() {
  const auto model = state_->model();
  if (!model || main_rect_.w < 2 || main_rect_.h < 2) return;
  const float scale = ImGui::GetIO().DisplayFramebufferScale.x > 0 ? ImGui::GetIO().DisplayFramebufferScale.x : 1.0f;
  float box_w = main_rect_.w, box_h = main_rect_.h;
  if (state_->compare == CompareMode::SideBySide) box_w *= 0.5f;
  const Camera cam = state_->render_camera(box_w * scale, box_h * scale);
  // The selection is drawn only over the model it was made on (a new snapshot clears it anyway).
  const SelectionView sel = state_->selection().view();
  std::shared_ptr<const SelectionMask> selection = sel.mask, hidden = sel.hidden;
  if (state_->selection().model() != model) selection.reset(), hidden.reset();
  const bool camera_changed = !requested_camera_ || !same_camera(cam, *requested_camera_);
  const bool model_changed = model.get() != requested_model_ || state_->model_version() != requested_model_version_ ||
                             selection != requested_selection_ || hidden != requested_hidden_;
  if (!camera_changed && !model_changed) return;
  const auto now = std::chrono::steady_clock::now();
  if (!camera_changed && state_->session().state() == JobState::Running) {
    // New snapshots while training: render at most a fifth of the time, the trainer needs the CPU more.
    const double gap = std::max(0.25, 5e-3 * (state_->frame ? state_->frame->render_ms : 0.0));
    if (std::chrono::duration<double>(now - last_request_time_).count() < gap) return;  // asked again next frame
  }
  last_request_time_ = now;
  requested_model_ = model.get();
  requested_model_version_ = state_->model_version();
  requested_camera_ = cam;
  requested_selection_ = selection;
  requested_hidden_ = hidden;
  requested_id_ = worker_->request({model, cam, selection, hidden});
}

void StudioApp::receive_frame() {
  std::shared_ptr<const DisplayFrame> f = worker_->take();
  const std::string err = worker_->error();
  if (err != render_error_) {
    render_error_ = err;
    if (!err.empty()) state_->message("render: " + err, true);
  }
  if (!f) return;
  const auto t0 = std::chrono::steady_clock::now();
  textures_.upload(*f);
  last_upload_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  state_->frame = std::move(f);
}

// The final colour of a frame as an RGB image on the CPU (CUDA frames keep it on the device, RGBA).
static Image frame_color(const DisplayFrame& f) {
  Image img(f.width, f.height, 3);
  if (!f.color.empty()) {
    std::copy(f.color.begin(), f.color.end(), img.pixels.data());
    return img;
  }
  const std::vector<float> rgba = f.gpu.color.to_host();
  for (size_t i = 0; i < img.pixel_count() && 4 * i + 3 < rgba.size(); ++i)
    for (int k = 0; k < 3; ++k) img.pixels[3 * i + k] = rgba[4 * i + k];
  return img;
}

void StudioApp::update_before_image() {
  const auto& before = state_->scene()->before_model;
  if (requested_camera_ && (before.get() != before_requested_model_ || !before_requested_camera_ ||
                            !same_camera(*requested_camera_, *before_requested_camera_))) {
    before_requested_model_ = before.get();
    before_requested_camera_ = requested_camera_;
    before_requested_id_ = before_worker_->request({before, *requested_camera_, nullptr, nullptr});
  }
  if (std::shared_ptr<const DisplayFrame> f = before_worker_->take()) {
    textures_.upload_photo(frame_color(*f));
    before_shown_id_ = f->id;
    photo_scene_ = 0;  // a photo is uploaded again when the comparison goes back to photos
  } else if (before_worker_->idle() && before_shown_id_ != before_requested_id_) {
    const std::string err = before_worker_->error();
    if (!err.empty()) {
      state_->message("render of the scene with the target: " + err, true);
      before_shown_id_ = before_requested_id_;  // nothing more will come for this request
    }
  }
}

void StudioApp::update_photo() {
  if (state_->comparing_with_before()) return update_before_image();
  before_requested_model_ = nullptr;
  const OpenedScene* scene = state_->scene();
  if (state_->compare == CompareMode::Off || !scene || !scene->dataset || scene->dataset->train.empty() ||
      !requested_camera_)
    return;
  const std::optional<size_t> k = nearest_view(scene->dataset->train, *requested_camera_, scene->radius);
  const glm::vec3 bg = state_->model() ? state_->model()->settings().background : scene->dataset_options.background;
  if (!k || (state_->scene_version() == photo_scene_ && k == photo_index_ && bg == photo_background_)) return;
  photo_scene_ = state_->scene_version();
  photo_index_ = k;
  photo_background_ = bg;
  try {
    // Composited on the background the shown model was trained with, so the two compare like for like.
    DatasetOptions o = scene->dataset_options;
    if (state_->model()) o.background = state_->model()->settings().background;
    textures_.upload_photo(load_view_image(scene->dataset->train[*k], o));
  } catch (const Error& e) {
    state_->message(e.what(), true);
  }
}

void StudioApp::update_removal_masks() {
  // The removal masks of the snapped training view (RUN/removal/{lighting,inpaint}_masks/VIEW.png, and the
  // target's shadow, RUN/removal/shadow/VIEW.png, over the lighting mask).
  const fs::path& dir = state_->removal_masks_dir();
  const bool wanted = !dir.empty() && state_->snapped && !state_->snapped_test;
  const std::string key = wanted ? (dir / state_->snapped_view).string() + "#" +
                                       std::to_string(state_->removal().runs_ended())
                                 : std::string();
  if (key == textures_.masks_key) return;
  std::optional<Image> lighting, inpaint;
  if (wanted) {
    for (auto [sub, out] : {std::pair{"lighting_masks", &lighting}, std::pair{"inpaint_masks", &inpaint}}) {
      const fs::path png = dir / sub / (state_->snapped_view + ".png");
      if (!fs::exists(png)) continue;
      try {
        *out = read_image(png);
      } catch (const Error& e) {
        state_->message(e.what(), true);
      }
    }
    // The target's shadow (share of the light it took, grey) shows in the lighting-aware mask's viewport.
    const fs::path shadow_png = dir / "shadow" / (state_->snapped_view + ".png");
    if (fs::exists(shadow_png)) {
      try {
        Image shadow = read_image(shadow_png);
        if (!lighting) lighting = std::move(shadow);  // a radiance run: no reflection mask
        else if (shadow.width == lighting->width && shadow.height == lighting->height && shadow.channels == 1 &&
            lighting->channels == 1)
          for (std::size_t p = 0; p < lighting->pixel_count(); ++p)
            lighting->pixels[p] = std::max(lighting->pixels[p], shadow.pixels[p]);
      } catch (const Error& e) {
        state_->message(e.what(), true);
      }
    }
  }
  textures_.upload_masks(key, lighting ? &*lighting : nullptr, inpaint ? &*inpaint : nullptr);
}

void StudioApp::handle_keys(double dt) {
  GLFWwindow* w = window_->handle();
  const ImGuiIO& io = ImGui::GetIO();
  if (ImGui::IsKeyPressed(GLFW_KEY_F3, false)) settings_.show_debug_overlay = !settings_.show_debug_overlay;
  // Selection undo / redo: Ctrl+Z, Ctrl+Shift+Z or Ctrl+Y (not while typing in a field).
  if (!io.WantTextInput && io.KeyCtrl &&
      (ImGui::IsKeyPressed(GLFW_KEY_Z, false) || ImGui::IsKeyPressed(GLFW_KEY_Y, false))) {
    const bool redo = io.KeyShift || ImGui::IsKeyPressed(GLFW_KEY_Y, false);
    try {
      if (redo)
        state_->redo_selection();
      else
        state_->undo_selection();
    } catch (const Error& e) {
      state_->message(e.what(), true);
    }
  }
  bool over_view = main_.hovered();
  for (const auto& g : grid_) over_view |= g->hovered();
  if (io.WantTextInput || !over_view) return;
  // B: before / after of a cleaned scene (the scene with the target, the cleaned one).
  if (!io.KeyCtrl && state_->has_before() && ImGui::IsKeyPressed(GLFW_KEY_B, false))
    state_->show_before(!state_->showing_before());
  auto down = [&](int key) { return glfwGetKey(w, key) == GLFW_PRESS ? 1.0f : 0.0f; };
  const float speed = state_->orbit.scene_radius() * 0.6f * float(dt) * (io.KeyShift ? 4.0f : 1.0f);
  const float f = down(GLFW_KEY_W) - down(GLFW_KEY_S), r = down(GLFW_KEY_D) - down(GLFW_KEY_A),
              u = down(GLFW_KEY_E) - down(GLFW_KEY_Q);
  if (f != 0 || r != 0 || u != 0) {
    state_->orbit.fly(f * speed, r * speed, u * speed);
    state_->camera_moved();
  }
}

void StudioApp::draw_viewports() {
  const char* empty = state_->opening()  ? "opening ..."
                      : !state_->scene() ? "Open a data set or a run folder (Open panel)"
                      : !state_->model() ? "No model yet: train in the Training panel"
                                         : "rendering ...";
  ViewportContext ctx{*state_,
                      textures_,
                      *renderer_,
                      camera_mode_,
                      ImGui::GetIO().DisplayFramebufferScale.x > 0 ? ImGui::GetIO().DisplayFramebufferScale.x : 1.0f,
                      empty};
  main_.draw(main_rect_, ctx, state_->compare == CompareMode::SideBySide);
  for (size_t i = 0; i < grid_rects_.size() && i < grid_.size(); ++i) grid_[i]->draw(grid_rects_[i], ctx);
}

bool StudioApp::settled() const {
  if (state_->opening() || state_->session().active()) return false;
  if (!worker_->idle()) return false;
  if (state_->selection().busy() || state_->removal().active() || !state_->removal_reported()) return false;
  if (state_->exporter().active() || !state_->export_reported()) return false;
  if (state_->importer().active() || !state_->import_reported()) return false;
  // What the frame loop last looked at is still current (an edit may have finished since).
  if (state_->selection().version() != display_signature_.selection ||
      state_->model_version() != display_signature_.model)
    return false;
  if (state_->model() && requested_id_ != 0 && textures_.frame_id != requested_id_ && render_error_.empty())
    return false;
  if (state_->comparing_with_before() && (!before_worker_->idle() || before_shown_id_ != before_requested_id_))
    return false;
  return stable_frames_ >= 2;
}

glm::vec2 StudioApp::main_image_size() const { return {main_.image_rect().w, main_.image_rect().h}; }

void StudioApp::request_screenshot(const fs::path& png) {
  screenshot_error_.reset();
  screenshot_path_ = png;
}

void StudioApp::take_screenshot() {
  const fs::path png = *screenshot_path_;
  screenshot_path_.reset();
  const glm::ivec2 fb = window_->framebuffer_size();
  const glm::ivec2 win = window_->window_size();
  const float sx = win.x > 0 ? float(fb.x) / float(win.x) : 1.0f, sy = win.y > 0 ? float(fb.y) / float(win.y) : 1.0f;
  auto to_fb = [&](const Rect& r) { return Rect{r.x * sx, r.y * sy, r.w * sx, r.h * sy}; };
  std::vector<ViewportRecord> records;
  records.push_back({main_.name(), channel_info(state_->main_channel).id, to_fb(main_.image_rect())});
  for (size_t i = 0; i < grid_rects_.size() && i < state_->grid_channels.size(); ++i)
    records.push_back({grid_[i]->name(), channel_info(state_->grid_channels[i]).id, to_fb(grid_[i]->image_rect())});
  try {
    save_screenshot(png, fb.x, fb.y, records);
  } catch (const Error& e) {
    screenshot_error_ = e.what();
  }
}

}  // namespace goris::ui
