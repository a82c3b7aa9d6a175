#include "ui/panels/removal_panel.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <cstdio>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/io/image.h"
#include "core/util/duration_text.h"
#include "core/util/error.h"
#include "ui/gl/imgui_texture.h"

namespace goris::ui {

namespace fs = std::filesystem;

namespace {


// The inpainted maps of a reference view, in the order the pipeline makes them.
constexpr const char* kMaps[] = {"rgb", "depth", "normal", "fresnel", "roughness", "region"};

// The reference views' names from RUN/removal/reference.json (empty when it is missing or unreadable).
std::vector<std::string> reference_views(const fs::path& dir) {
  std::ifstream in(dir / "reference.json");
  if (!in) return {};
  std::stringstream text;
  text << in.rdbuf();
  const nlohmann::json j = nlohmann::json::parse(text.str(), nullptr, false);
  std::vector<std::string> views;
  if (!j.is_array()) return views;
  for (const auto& e : j)
    if (e.is_object() && e.contains("view") && e["view"].is_string()) views.push_back(e["view"].get<std::string>());
  return views;
}

}  // namespace

void RemovalPanel::draw(AppState& st) {
  const RemovalSession& rs = st.removal();
  const bool active = rs.active();
  const fs::path run = active ? rs.run_dir() : st.current_run();
  if (run.empty()) {
    ImGui::TextDisabled("Train a model or open a run first.");
    return;
  }
  ImGui::TextWrapped("run: %s", run.string().c_str());
  draw_options(st, active);
  draw_steps(st);
  draw_result(st);
}

void RemovalPanel::draw_options(AppState& st, bool active) {
  StudioSettings& set = st.settings();
  ImGui::BeginDisabled(active);
  // Entry 0 is the removal's default, stored as "" so that the settings follow it when it changes.
  static const std::string kDefaultLabel = "default (" + RemovalSession::default_inpainter() + ")";
  static const char* kInpainters[] = {kDefaultLabel.c_str(), "harmonic", "telea", "ns", "fsr", "cmd:"};
  constexpr int kCount = 6, kCommand = 5;
  int which = 0;
  const bool command = set.removal_inpainter.rfind("cmd:", 0) == 0;
  for (int i = 1; i < kCount; ++i)
    if (set.removal_inpainter == kInpainters[i] || (i == kCommand && command)) which = i;
  ImGui::SetNextItemWidth(160);
  if (ImGui::Combo("inpainter", &which, kInpainters, kCount))
    set.removal_inpainter = which == 0 ? "" : which == kCommand ? "cmd:" + custom_command_ : kInpainters[which];
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip(
        "default: the removal's own choice (follows it when it changes);\n"
        "harmonic: smooth fill that continues gradients; telea / ns: OpenCV inpainting;\n"
        "fsr: OpenCV xphoto (slow);\n"
        "cmd: your own inpainter (LaMa, SD), run per map with {image} {mask} {out} (core/inpaint/external_inpainter.h)");
  if (which == kCommand) {
    if (custom_command_.empty() && set.removal_inpainter.size() > 4) custom_command_ = set.removal_inpainter.substr(4);
    ImGui::SetNextItemWidth(-1);
    if (ImGui::InputTextWithHint("##cmd", "e.g. python lama.py --image {image} --mask {mask} --out {out}", &custom_command_))
      set.removal_inpainter = "cmd:" + custom_command_;
  }
  ImGui::SetNextItemWidth(120);
  ImGui::InputInt("fine-tune iterations", &set.removal_iterations, 100);
  set.removal_iterations = std::max(set.removal_iterations, 0);
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("0: 4000 at a 30K stage 1, scaled like the run's schedule (at least 100)");
  ImGui::Checkbox("RGB-only inpainting (ablate material)", &set.removal_ablate_material);
  ImGui::Checkbox("no lighting-aware mask (ablate lamask)", &set.removal_ablate_lamask);
  ImGui::Checkbox("keep the mirror twin (ablate twins)", &set.removal_ablate_twins);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Over a flat glossy surface the reflection is learned as a copy of the object below it;\n"
                      "by default it is removed with the target");
  ImGui::BeginDisabled(set.removal_ablate_lamask);
  ImGui::Checkbox("keep the target's shadow (ablate shadows)", &set.removal_ablate_shadows);
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("By default the light is fitted to the photos' shadow of the target on the surface it\n"
                      "stands on, and the photos are relit before the fine-tune (off with ablate lamask too)");
  ImGui::Checkbox("absolute Fresnel in the lighting-aware mask", &set.removal_absolute_fresnel);
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("The paper's (1 - M) F x label > 0.1. Default: F relative to the glossy surfaces' F0,\n"
                      "which stage 1 learns only up to the environment's brightness");
  ImGui::BeginDisabled(set.removal_ablate_lamask);
  ImGui::Checkbox("leave the reflections out of the fine-tune", &set.removal_exclude_reflections);
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("The paper's rule: no photo loss in the lighting-aware mask. Default: train there on the\n"
                      "photo minus stage 1's own estimate of the target's reflection (removal/dereflected)");
  ImGui::EndDisabled();

  if (!active) {
    ImGui::BeginDisabled(st.training_active());
    if (ImGui::Button("Remove")) report_errors(st, [&] { st.start_removal(); });
    ImGui::EndDisabled();
    if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
      ImGui::SetTooltip(
          "removes the selection (saved first when it is not) or, without one, RUN/selection.json or the\n"
          "learned labels; a folder with an earlier removal is resumed where it stopped");
  } else {
    ImGui::BeginDisabled(st.removal().state() == JobState::Cancelling);
    if (ImGui::Button("Cancel")) st.removal().cancel();
    ImGui::EndDisabled();
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("stops at the next check; the run folder stays consistent and Remove resumes");
  }
}

void RemovalPanel::draw_steps(AppState& st) {
  const RemovalSession& rs = st.removal();
  if (rs.state() == JobState::Idle) return;
  const RemovalProgressTracker p = rs.progress();
  const double elapsed = rs.elapsed_s();
  char overlay[96];
  std::snprintf(overlay, sizeof overlay, "%.0f %%", 100.0 * p.fraction());
  ImGui::ProgressBar(float(p.fraction()), ImVec2(-1, 0), overlay);
  const double eta = p.eta_s(elapsed);
  ImGui::Text("%s   elapsed %s   ETA %s", job_state_name(rs.state()), duration_text(elapsed).c_str(),
              rs.active() && eta >= 0 ? duration_text(eta).c_str() : "--");
  ImGui::TextWrapped("%s", rs.status().c_str());
  if (!ImGui::BeginTable("steps", 3, ImGuiTableFlags_SizingStretchProp | ImGuiTableFlags_RowBg)) return;
  ImGui::TableSetupColumn("step", ImGuiTableColumnFlags_WidthFixed, 100);
  ImGui::TableSetupColumn("progress", ImGuiTableColumnFlags_WidthStretch);
  ImGui::TableSetupColumn("time", ImGuiTableColumnFlags_WidthFixed, 44);
  for (int k = 0; k < kRemovalStepCount; ++k) {
    const RemovalStepStatus& s = p.steps()[size_t(k)];
    ImGui::TableNextRow();
    ImGui::TableSetColumnIndex(0);
    if (k == p.current_step() && rs.active())
      ImGui::TextColored(ImVec4(1, 0.85f, 0.3f, 1), "%s", removal_step_name(RemovalStep(k)));
    else if (s.complete)
      ImGui::TextUnformatted(removal_step_name(RemovalStep(k)));
    else
      ImGui::TextDisabled("%s", removal_step_name(RemovalStep(k)));
    ImGui::TableSetColumnIndex(1);
    char text[64];
    if (s.total > 1)
      std::snprintf(text, sizeof text, "%zu / %zu", s.done, s.total);
    else
      std::snprintf(text, sizeof text, "%.0f %%", 100.0 * double(s.fraction()));
    ImGui::ProgressBar(s.fraction(), ImVec2(-1, 0), text);
    if (!s.detail.empty()) {
      ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
      ImGui::TextWrapped("%s", s.detail.c_str());
      ImGui::PopStyleColor();
    }
    ImGui::TableSetColumnIndex(2);
    if (s.started) ImGui::Text("%s", duration_text(s.seconds).c_str());
  }
  ImGui::EndTable();
}

void RemovalPanel::update_thumbnails(AppState& st, const fs::path& dir, const std::string& key) {
  if (key == thumbnails_key_) return;
  thumbnails_key_ = key;
  thumbnails_.clear();
  if (dir.empty()) return;
  for (const std::string& view : reference_views(dir))
    for (const char* map : kMaps) {
      const fs::path png = dir / "inpainted" / (view + "_" + map + ".png");
      if (!fs::exists(png)) continue;
      try {
        const Image im = read_image(png);
        const std::vector<float> px = im.pixels.to_host();
        Thumbnail t{view, map, {}};
        t.texture.upload(im.width, im.height, im.channels, px.data());
        thumbnails_.push_back(std::move(t));
      } catch (const Error& e) {
        st.message(e.what(), true);
      }
    }
}

void RemovalPanel::draw_result(AppState& st) {
  const RemovalSession& rs = st.removal();
  // The inpainted maps: while a removal runs, once its 2D inpainting is complete; else what the run has.
  fs::path dir;
  std::string key;
  if (rs.active() || rs.state() != JobState::Idle) {
    const bool inpainted = rs.progress().steps()[size_t(RemovalStep::Inpaint2D)].complete;
    if (inpainted || !rs.active()) dir = rs.run_dir() / "removal";
    key = dir.string() + "#" + std::to_string(rs.runs_ended()) + (inpainted ? "+" : "-");
  } else if (!st.removal_masks_dir().empty()) {
    dir = st.removal_masks_dir();
    key = dir.string();
  }
  update_thumbnails(st, dir, key);
  if (!thumbnails_.empty()) {
    ImGui::Separator();
    ImGui::Text("inpainted reference views");
    const float side = 46;
    std::string row;
    for (const Thumbnail& t : thumbnails_) {
      if (t.view != row) {
        row = t.view;
        ImGui::TextDisabled("%s", row.c_str());
      } else {
        ImGui::SameLine();
      }
      const float h = side * float(t.texture.height()) / float(std::max(t.texture.width(), 1));
      ImGui::Image(imgui_texture(t.texture.id()), ImVec2(side, h));
      if (ImGui::IsItemHovered()) {
        ImGui::BeginTooltip();
        ImGui::Text("%s %s", t.view.c_str(), t.map.c_str());
        ImGui::Image(imgui_texture(t.texture.id()), ImVec2(4 * side, 4 * h));
        ImGui::EndTooltip();
      }
    }
  }
  if (rs.state() == JobState::Done) {
    ImGui::Separator();
    const fs::path cleaned = rs.run_dir() / "removal";
    ImGui::TextWrapped("The cleaned scene is a run folder: %s", cleaned.string().c_str());
    if (ImGui::Button("Open the cleaned scene")) report_errors(st, [&] { st.open(cleaned); });
  }
  if (!st.removal_result().empty() && !rs.active()) {
    if (ImGui::Button("Export the cleaned scene...")) {
      st.export_from_removal = true;
      st.show_export_dialog = true;
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("the Export dialog for RUN/removal: PLYs and renders");
  }
  if (!st.removal_masks_dir().empty()) {
    ImGui::BeginDisabled(st.channel_unavailable(Channel::LightingMask) != nullptr || st.grid_channels.size() < 2);
    if (ImGui::Button("Show the masks in the grid"))
      report_errors(st, [&] {
        st.set_channel(0, Channel::LightingMask);
        st.set_channel(1, Channel::InpaintMask);
      });
    ImGui::EndDisabled();
    if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
      ImGui::SetTooltip("the lighting-aware and inpainting masks of the snapped training camera in tiles 0 and 1%s",
                        st.channel_unavailable(Channel::LightingMask) ? "\n(snap to a training camera first)" : "");
  }
}

}  // namespace goris::ui
