// The editor's frame around the viewports: menu bar, sidebar of panels, status bar and the debug overlay
// (members of StudioApp, apart from the frame loop in studio_app.cpp).
#include <algorithm>

#include "ui/gl/gl_api.h"
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include "core/util/error.h"
#include "ui/shell/studio_app.h"

namespace goris::ui {

void StudioApp::draw_menu() {
  if (!ImGui::BeginMainMenuBar()) return;
  if (ImGui::BeginMenu("File")) {
    if (ImGui::BeginMenu("Open recent", !settings_.recent_paths.empty() && !state_->opening())) {
      for (const std::string& p : settings_.recent_paths)
        if (ImGui::MenuItem(p.c_str())) {
          try {
            state_->open(p);
          } catch (const Error& e) {
            state_->message(e.what(), true);
          }
          break;
        }
      ImGui::EndMenu();
    }
    if (ImGui::MenuItem("Export...", nullptr, false, !state_->current_run().empty() || state_->exporter().active()))
      state_->show_export_dialog = true;
    ImGui::Separator();
    if (ImGui::MenuItem("Quit", "Ctrl+Q")) quit();
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("View")) {
    ImGui::MenuItem("Sidebar", nullptr, &settings_.show_sidebar);
    ImGui::MenuItem("Viewport grid", nullptr, &settings_.show_grid);
    ImGui::MenuItem("Plots", nullptr, &settings_.show_plots);
    ImGui::MenuItem("Debug overlay", "F3", &settings_.show_debug_overlay);
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Help")) {
    ImGui::TextUnformatted(
        "Viewports: left drag orbits (fly mode: looks around), right or middle drag pans,\n"
        "the wheel zooms, W A S D Q E move (Shift: faster).\n"
        "A left click selects the object under it (grown by the Selection panel's slider);\n"
        "Shift+click adds, Ctrl+click removes; Ctrl+Z / Ctrl+Y undo and redo selection edits.\n"
        "Each viewport's channel is chosen in its top-left corner.");
    ImGui::EndMenu();
  }
  ImGui::EndMainMenuBar();
  if (ImGui::GetIO().KeyCtrl && ImGui::IsKeyPressed(GLFW_KEY_Q, false)) quit();
}

void StudioApp::draw_sidebar() {
  ImGui::SetNextWindowPos(ImVec2(sidebar_.x, sidebar_.y));
  ImGui::SetNextWindowSize(ImVec2(sidebar_.w, sidebar_.h));
  ImGui::Begin("##sidebar", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings |
                   ImGuiWindowFlags_NoBringToFrontOnFocus | ImGuiWindowFlags_AlwaysVerticalScrollbar);
  for (size_t i = 0; i < panels_.size(); ++i) {
    const auto& p = panels_[i];
    if (!p->visible(settings_)) continue;
    if (panels_open_)
      ImGui::SetNextItemOpen((*panels_open_)[i], ImGuiCond_Always);
    else
      ImGui::SetNextItemOpen(p->open_by_default(), ImGuiCond_Once);
    if (ImGui::CollapsingHeader(p->title())) {
      ImGui::PushID(p->title());
      p->draw(*state_);
      ImGui::PopID();
    }
  }
  panels_open_.reset();
  ImGui::End();
}

void StudioApp::draw_status() {
  ImGui::SetNextWindowPos(ImVec2(status_rect_.x, status_rect_.y));
  ImGui::SetNextWindowSize(ImVec2(status_rect_.w, status_rect_.h));
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(6, 2));
  ImGui::Begin("##status", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings);
  ImGui::PopStyleVar();
  const TrainerSession& s = state_->session();
  if (state_->removal().active())
    ImGui::Text("[removal %s]", job_state_name(state_->removal().state()));
  else if (state_->exporter().active())
    ImGui::Text("[export %s]", job_state_name(state_->exporter().state()));
  else if (state_->importer().active())
    ImGui::Text("[import %s]", job_state_name(state_->importer().state()));
  else
    ImGui::Text("[%s]", training_state_name(s.state()));
  ImGui::SameLine();
  if (state_->last_message_is_error())
    ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", state_->last_message().c_str());
  else
    ImGui::TextUnformatted(state_->last_message().c_str());
  if (script_ && script_->status() == ScriptRunner::Status::Running) {
    ImGui::SameLine(std::max(status_rect_.w - 160, 0.0f));
    ImGui::TextDisabled("script line %d", script_->current_line());
  }
  ImGui::End();
}

void StudioApp::draw_debug_overlay() {
  ImGui::SetNextWindowPos(ImVec2(main_rect_.x + main_rect_.w - 8, main_rect_.y + 30), ImGuiCond_Always, ImVec2(1, 0));
  ImGui::SetNextWindowBgAlpha(0.6f);
  ImGui::Begin("##debug", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings |
                   ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoInputs);
  ImGui::Text("frame %.1f ms (%.0f fps, cap %.0f)", limiter_.frame_ms(),
              limiter_.frame_ms() > 0 ? 1000.0 / limiter_.frame_ms() : 0.0, limiter_.target_fps());
  ImGui::Text("GUI work %.1f ms", limiter_.work_ms());
  if (state_->frame) {
    ImGui::Text("render %dx%d: %.1f ms, upload %.1f ms", state_->frame->width, state_->frame->height,
                state_->frame->render_ms, last_upload_ms_);
    ImGui::Text("%zu Gaussians (iteration %d)", state_->frame->gaussians, state_->frame->model_iteration);
  }
  const TrainProgress p = state_->session().progress();
  if (p.total > 0) ImGui::Text("trainer %.1f it/s", p.it_per_s);
  if (training_frames_.frames > 0)
    ImGui::Text("while training: %.1f ms mean, %.1f ms max frame", training_frames_.mean_ms, training_frames_.max_ms);
  ImGui::TextDisabled("%s", window_->gl_description().c_str());
  ImGui::End();
}

}  // namespace goris::ui
