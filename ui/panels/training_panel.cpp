#include "ui/panels/training_panel.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "core/compute/device_choice.h"
#include "core/util/duration_text.h"
#include "core/util/error.h"
#include "train/config/config_presets.h"
#include "ui/document/train_options.h"

namespace goris::ui {

void TrainingPanel::draw(AppState& st) {
  TrainerSession& session = st.session();
  const JobState s = session.state();
  const bool active = job_active(s);
  const OpenedScene* scene = st.scene();
  StudioSettings& set = st.settings();
  if (!scene) {
    ImGui::TextDisabled("Open a data set or a run first.");
    return;
  }
  if (scene->kind == OpenedScene::Kind::Model) {
    ImGui::TextDisabled("A model file has no photos to train on: open its data set or run folder.");
    return;
  }
  const bool is_run = scene->kind == OpenedScene::Kind::Run;

  // The run folder: editable for a data set (empty = a new folder under the runs root).
  if (st.run_folder.string() != seen_run_folder_) run_folder_ = seen_run_folder_ = st.run_folder.string();
  ImGui::BeginDisabled(active || is_run);
  ImGui::SetNextItemWidth(-1);
  if (ImGui::InputTextWithHint("##run", "run folder (empty: a new one)", &run_folder_)) {
    st.run_folder = run_folder_;
    seen_run_folder_ = run_folder_;
  }
  ImGui::EndDisabled();
  if (is_run) ImGui::TextDisabled("continues this run from its latest checkpoint");

  ImGui::BeginDisabled(active);
  if (is_run && scene->run_config) {
    // A run keeps its own settings; only where it trains is this machine's choice.
    const TrainConfig& c = *scene->run_config;
    ImGui::TextDisabled("mode %s, %s, background (%.2g, %.2g, %.2g)", enum_name(c.mode),
                        c.input.resolution > 0 ? ("width " + std::to_string(c.input.resolution)).c_str() : "full size",
                        double(c.input.background.x), double(c.input.background.y), double(c.input.background.z));
  } else {
    // The fields show the settings in effect: the panel's own, with a script's `set` overrides on top; editing
    // a field drops the override of its key.
    TrainConfig eff;
    try {
      eff = new_run_config(set, st.overrides());
    } catch (const Error&) {  // an override that no longer fits the panel's settings: show the panel's own
      eff = new_run_config(set, {});
    }
    auto overridden = [&](const char* key) {
      if (!ImGui::IsItemHovered()) return;
      for (const auto& [k, v] : st.overrides())
        if (k == key) ImGui::SetTooltip("set by `set %s %s`", k.c_str(), v.c_str());
    };
    ImGui::SetNextItemWidth(120);
    if (ImGui::BeginCombo("mode", enum_name(eff.mode))) {  // the names config.json and `--mode` use
      for (const auto& [value, name] : EnumNames<TrainMode>::names)
        if (ImGui::Selectable(name, value == eff.mode)) {
          set.train_mode = name;
          st.drop_override("mode");
        }
      ImGui::EndCombo();
    }
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip(
          "radiance: SH colour only; intrinsic: materials, tracing and shading (stage 1);\n"
          "auto: intrinsic for a glossy scene, radiance otherwise");
    overridden("mode");
    // Presets: the files of resources/presets (as `goris train --preset`), applied before a script's `set`
    // lines. The folder is listed again, and the tooltip's file read again, whenever the chooser opens.
    static std::vector<std::string> presets = config_preset_names();
    static std::string tip_of, tip;
    ImGui::SetNextItemWidth(120);
    if (ImGui::BeginCombo("preset", set.train_preset.empty() ? "none" : set.train_preset.c_str())) {
      if (ImGui::IsWindowAppearing()) presets = config_preset_names(), tip_of = "\n";
      if (ImGui::Selectable("none", set.train_preset.empty())) set.train_preset.clear();
      for (const std::string& p : presets)
        if (ImGui::Selectable(p.c_str(), set.train_preset == p)) set.train_preset = p;
      ImGui::EndCombo();
    }
    if (ImGui::IsItemHovered()) {
      if (tip_of != set.train_preset) {
        tip_of = set.train_preset;
        tip = "settings applied on top of the fields above (goris train --preset):";
        if (set.train_preset.empty()) {
          tip += "\n  none";
          for (const std::string& p : presets) tip += "; " + p;
        } else {
          try {
            const ConfigPreset preset = load_config_preset(set.train_preset);
            tip += "\n" + preset.description + "\n" + preset.file.string();
            for (const std::string& kv : preset.settings) tip += "\n  " + kv;
          } catch (const std::exception& e) {
            tip += "\n" + std::string(e.what());
          }
        }
      }
      ImGui::SetTooltip("%s", tip.c_str());
    }
    int resolution = eff.input.resolution, points = eff.init.random_points;
    ImGui::SetNextItemWidth(120);
    if (ImGui::InputInt("resolution (0 = full)", &resolution, 0)) {
      set.train_resolution = std::max(resolution, 0);
      st.drop_override("resolution");
    }
    overridden("resolution");
    ImGui::SetNextItemWidth(120);
    if (ImGui::InputInt("initial points", &points, 0)) {
      set.train_init_points = std::max(points, 1);
      st.drop_override("random_init_points");
    }
    overridden("random_init_points");
    bool white = eff.input.background == glm::vec3(1.0f);
    if (ImGui::Checkbox("white background", &white)) {
      set.train_white_background = white;
      st.drop_override("background");
    }
    overridden("background");
  }
  ImGui::SetNextItemWidth(120);
  if (ImGui::BeginCombo("device", set.train_device.c_str())) {  // the names config.json and `--device` use
    for (const auto& [value, name] : EnumNames<DeviceChoice>::names)
      if (ImGui::Selectable(name, set.train_device == name)) set.train_device = name;
    ImGui::EndCombo();
  }
  ImGui::EndDisabled();
  ImGui::BeginDisabled(active);
  ImGui::SetNextItemWidth(120);
  ImGui::InputInt("iterations", &set.train_iterations, 1000);
  set.train_iterations = std::max(set.train_iterations, 1);
  ImGui::EndDisabled();
  for (const auto& [k, v] : st.overrides()) ImGui::TextDisabled("set %s = %s", k.c_str(), v.c_str());

  if (!active) {
    if (ImGui::Button("Train")) report_errors(st, [&] { st.start_training(set.train_iterations, false); });
    ImGui::SameLine();
    if (ImGui::Button("+1000")) report_errors(st, [&] { st.start_training(1000, true); });
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("train 1000 more iterations");
  } else {
    if (s == JobState::Paused) {
      if (ImGui::Button("Resume")) session.resume();
    } else {
      ImGui::BeginDisabled(s == JobState::Cancelling);
      if (ImGui::Button("Pause")) session.pause();
      ImGui::EndDisabled();
    }
    ImGui::SameLine();
    ImGui::BeginDisabled(s == JobState::Cancelling);
    if (ImGui::Button("Stop")) session.stop();
    ImGui::EndDisabled();
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("finish the iteration, write a checkpoint and stop");
  }

  const TrainProgress p = session.progress();
  const float fraction = p.total > 0 ? float(p.iteration) / float(p.total) : 0.0f;
  char overlay[64];
  std::snprintf(overlay, sizeof overlay, "%d / %d", p.iteration, p.total);
  ImGui::ProgressBar(fraction, ImVec2(-1, 0), overlay);
  ImGui::Text("state: %s", training_state_name(s));
  ImGui::TextWrapped("%s", session.status().c_str());
  if (p.total > 0) {
    ImGui::Text("loss %.4f   PSNR %.2f dB", p.loss, p.psnr);
    ImGui::Text("%zu Gaussians   %.1f it/s", p.gaussians, p.it_per_s);
    ImGui::Text("elapsed %s   ETA %s", duration_text(p.elapsed_s).c_str(),
                active ? duration_text(p.eta_s).c_str() : "--");
  }
}

}  // namespace goris::ui
