#include "ui/shell/export_dialog.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cstdio>

#include "core/util/duration_text.h"
#include "core/util/error.h"

namespace goris::ui {

namespace fs = std::filesystem;

namespace {

// Fixed widths: the window sizes itself to its contents, so nothing may size itself to the window.
constexpr float kLabelWidth = 130, kPathWidth = 380, kPartBarWidth = 160, kWrap = 780;

const ImVec4 kErrorColour(1.0f, 0.45f, 0.45f, 1.0f);
const ImVec4 kDoneColour(0.5f, 0.9f, 0.5f, 1.0f);

// One part's row: checkbox, path field, tooltip.
bool part_row(const char* label, bool* wanted, std::string* path, const char* hint, const char* tooltip) {
  ImGui::Checkbox(label, wanted);
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) ImGui::SetTooltip("%s", tooltip);
  ImGui::SameLine(kLabelWidth);
  ImGui::SetNextItemWidth(kPathWidth);
  ImGui::PushID(label);
  const bool changed = ImGui::InputTextWithHint("##path", hint, path);
  ImGui::PopID();
  return changed;
}

}  // namespace

void ExportDialog::draw(AppState& st) {
  if (!st.show_export_dialog) return;
  const ImGuiViewport* vp = ImGui::GetMainViewport();
  ImGui::SetNextWindowPos(ImVec2(vp->WorkPos.x + vp->WorkSize.x * 0.5f, vp->WorkPos.y + vp->WorkSize.y * 0.42f),
                          ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  bool open = true;
  if (ImGui::Begin(
          "Export", &open,
          ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoSavedSettings)) {
    const bool active = st.exporter().active();
    ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + kWrap);
    if (st.current_run().empty() && !active) {
      ImGui::TextDisabled("Train a model or open a run folder first: an export reads a run folder.");
    } else {
      draw_choices(st, active);
      draw_buttons(st, active);
      draw_progress(st);
      draw_outcome(st);
    }
    ImGui::PopTextWrapPos();
  }
  ImGui::End();
  if (!open) st.show_export_dialog = false;
}

void ExportDialog::draw_choices(AppState& st, bool active) {
  StudioSettings& set = st.settings();
  ImGui::BeginDisabled(active);
  // Source: the run, or its cleaned scene when stage 2 has made one.
  const fs::path run = st.current_run();
  if (!st.removal_result().empty()) {
    ImGui::TextUnformatted("export");
    ImGui::SameLine(kLabelWidth);
    if (ImGui::RadioButton("the run", !st.export_from_removal)) st.export_from_removal = false;
    ImGui::SameLine();
    if (ImGui::RadioButton("the cleaned scene (RUN/removal)", st.export_from_removal)) st.export_from_removal = true;
  }
  const fs::path source = st.export_source();
  ImGui::TextDisabled("from %s", source.string().c_str());
  if (const auto m = st.model(); m && st.current_run() == source)
    ImGui::TextDisabled("%s run; the export reads its latest checkpoint", m->intrinsic() ? "intrinsic" : "radiance");
  ImGui::Separator();

  part_row("intrinsic PLY", &set.export_ply, &set.export_ply_path, "e.g. export/model.ply",
           "the model in the standard 3DGS layout (any viewer opens it), its intrinsic attributes\n"
           "(diffuse, F0, roughness, region, label) as extra properties, the 3D filter baked in");
  part_row("baked PLY", &set.export_baked, &set.export_baked_path, "e.g. export/baked.ply",
           "a standard SH-only model distilled from the run's shaded renders, so that plain 3DGS viewers\n"
           "show what the engine renders; OUT.json beside it has the fidelity (PSNR on held-out views)");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(110);
  ImGui::InputInt("iterations", &set.export_baked_iterations, 500);
  set.export_baked_iterations = std::clamp(set.export_baked_iterations, 1, 10000000);
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("distillation iterations (a radiance run is plain SH already and needs none)");
  // The baked model in the formats other viewers and engines read, beside the baked PLY.
  ImGui::BeginDisabled(!set.export_baked);
  ImGui::TextUnformatted("  also as");
  ImGui::SameLine(kLabelWidth);
  ImGui::Checkbox("SPZ", &set.export_baked_spz);
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("Niantic SPZ version 3 beside the baked PLY (same name, .spz): gzip, quantized,\n"
                      "about a tenth of the PLY");
  ImGui::SameLine();
  ImGui::Checkbox("compressed PLY", &set.export_baked_compressed_ply);
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("PlayCanvas compressed PLY (.compressed.ply): chunks of 256, 32 bits per attribute");
  ImGui::SameLine();
  ImGui::Checkbox(".splat", &set.export_baked_splat);
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("the antimatter15 .splat layout of web viewers: 32 bytes per Gaussian, no higher SH");
  ImGui::SameLine();
  ImGui::Checkbox("GLB", &set.export_baked_glb);
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("glTF binary with KHR_gaussian_splatting (.glb): float32, lossless");
  ImGui::EndDisabled();
  part_row("renders", &set.export_renders, &set.export_renders_dir, "e.g. export/renders",
           "one PNG per camera from the run's renderer, contact_sheet.png and cameras.json");
  ImGui::SameLine();
  static const char* kPaths[] = {"test", "train", "orbit"};
  int which = set.export_render_path == "train" ? 1 : set.export_render_path == "orbit" ? 2 : 0;
  ImGui::SetNextItemWidth(80);
  if (ImGui::Combo("##cameras", &which, kPaths, 3)) set.export_render_path = kPaths[which];
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip(
        "test / train: the data set's views; orbit: a circle around the scene at the cameras'\n"
        "mean height and distance");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(90);
  ImGui::InputInt("frames", &set.export_frames, 0);
  set.export_frames = std::clamp(set.export_frames, 0, 100000);
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("orbit: number of frames (0 = 36); test / train: that many evenly spaced views (0 = all)");
  ImGui::TextDisabled("Relative paths lie inside the exported run folder; device %s (Training panel).",
                      set.train_device.c_str());
  ImGui::EndDisabled();
}

void ExportDialog::draw_buttons(AppState& st, bool active) {
  ExportJob& job = st.exporter();
  if (!active) {
    const bool can = st.settings().export_ply || st.settings().export_baked || st.settings().export_renders;
    ImGui::BeginDisabled(!can || st.training_active());
    if (ImGui::Button("Export", ImVec2(100, 0))) {
      refused_.clear();
      try {
        st.start_export();
      } catch (const Error& e) {
        refused_ = e.what();
        st.message(e.what(), true);
      }
    }
    ImGui::EndDisabled();
    if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
      ImGui::SetTooltip("%s", st.training_active()
                                  ? "stop the training first: the export reads the run's latest checkpoint"
                                  : "writes the chosen parts on a worker; the editor stays usable");
    ImGui::SameLine();
    if (ImGui::Button("Close", ImVec2(100, 0))) st.show_export_dialog = false;
  } else {
    ImGui::BeginDisabled(job.state() == JobState::Cancelling);
    if (ImGui::Button("Cancel", ImVec2(100, 0))) job.cancel();
    ImGui::EndDisabled();
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("stops at the next progress check and writes nothing more; finished parts stay");
    if (job.distilling()) {
      ImGui::SameLine();
      if (ImGui::Button("Finish distilling now")) job.finish_early();
      if (ImGui::IsItemHovered())
        ImGui::SetTooltip("ends the distillation here and writes the baked model so far (marked \"stopped\")");
    }
  }
  if (!refused_.empty() && !active) ImGui::TextColored(kErrorColour, "%s", refused_.c_str());
}

void ExportDialog::draw_progress(AppState& st) {
  const ExportJob& job = st.exporter();
  if (job.state() == JobState::Idle) return;
  const ExportProgress p = job.progress();
  ImGui::Separator();
  char overlay[64];
  std::snprintf(overlay, sizeof overlay, "%.0f %%", 100.0 * p.fraction());
  ImGui::ProgressBar(float(p.fraction()), ImVec2(kLabelWidth + kPathWidth, 0), overlay);
  ImGui::SameLine();
  const double elapsed = job.elapsed_s(), f = p.fraction();
  if (job.active() && f > 0.02)  // the ETA from the parts' expected costs, once some of it is measured
    ImGui::Text("%s, %s, ETA %s", job_state_name(job.state()), duration_text(elapsed).c_str(),
                duration_text(elapsed * (1.0 - f) / f).c_str());
  else
    ImGui::Text("%s, %s", job_state_name(job.state()), duration_text(elapsed).c_str());
  for (int k = 0; k < kExportPartCount; ++k) {
    const ExportPartStatus& s = p.parts[size_t(k)];
    if (!s.wanted) continue;
    const char* name = export_part_name(ExportPart(k));
    if (k == p.current && job.active())
      ImGui::TextColored(ImVec4(1, 0.85f, 0.3f, 1), "%s", name);
    else if (s.complete)
      ImGui::TextUnformatted(name);
    else
      ImGui::TextDisabled("%s", name);
    ImGui::SameLine(kLabelWidth);
    char text[32];
    std::snprintf(text, sizeof text, "%.0f %%", 100.0 * (s.complete ? 1.0 : s.fraction));
    ImGui::ProgressBar(float(s.complete ? 1.0 : s.fraction), ImVec2(kPartBarWidth, 0), text);
    if (s.started) {
      ImGui::SameLine(kLabelWidth + kPartBarWidth + 16);
      ImGui::TextDisabled("%s", duration_text(s.seconds).c_str());
      ImGui::SameLine(kLabelWidth + kPartBarWidth + 66);
      ImGui::TextDisabled("%s", s.detail.c_str());
    }
  }
}

void ExportDialog::draw_outcome(AppState& st) {
  const ExportJob& job = st.exporter();
  const JobState s = job.state();
  if (s == JobState::Idle || job.active()) return;
  ImGui::Separator();
  if (s == JobState::Done) {
    ImGui::TextColored(kDoneColour, "Done in %s:", duration_text(job.elapsed_s()).c_str());
    ImGui::TextWrapped("%s", job.result().summary.c_str());
  } else if (s == JobState::Cancelled) {
    ImGui::TextWrapped("Cancelled: %s", job.status().c_str());
  } else {
    ImGui::TextColored(kErrorColour, "Export failed:");
    ImGui::PushStyleColor(ImGuiCol_Text, kErrorColour);
    ImGui::TextWrapped("%s", job.status().c_str());
    ImGui::PopStyleColor();
    const std::string kept = job.result().summary;
    if (!kept.empty()) ImGui::TextWrapped("written before the failure:\n%s", kept.c_str());
  }
}

}  // namespace goris::ui
