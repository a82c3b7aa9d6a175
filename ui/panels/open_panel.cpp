#include "ui/panels/open_panel.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cstdio>

#include "core/capture/capture_frames.h"
#include "core/util/duration_text.h"
#include "core/util/error.h"

namespace goris::ui {

namespace fs = std::filesystem;

namespace {
void try_open(AppState& st, const std::string& path) {
  try {
    st.open(path);
  } catch (const Error& e) {
    st.message(e.what(), true);
  }
}

const ImVec4 kErrorColour(1, 0.4f, 0.4f, 1);
const ImVec4 kBusyColour(1, 0.85f, 0.3f, 1);
}  // namespace

void OpenPanel::draw(AppState& st) {
  ImGui::TextWrapped("A data set folder (NeRF-synthetic, COLMAP, ...), a run folder (config.json) or a model file "
                     "(.ply, .compressed.ply, .spz, .splat, .glb); or a folder of photos or a video to import.");
  ImGui::SetNextItemWidth(-60);
  const bool enter = ImGui::InputTextWithHint("##path", "path", &path_, ImGuiInputTextFlags_EnterReturnsTrue);
  ImGui::SameLine();
  // Photos or a video: offered for import. Checked once per typed path (it lists the folder).
  if (path_ != checked_path_) {
    checked_path_ = path_;
    importable_ = !path_.empty() && is_capture_input(path_);
    if (importable_ && !st.importer().active()) {
      st.import_form.input = fs::absolute(path_).lexically_normal();
      st.import_form.out = default_capture_output(path_);
    }
  }
  ImGui::BeginDisabled(st.opening() || path_.empty() || importable_);
  if (ImGui::Button("Open") || (enter && !path_.empty() && !importable_)) try_open(st, path_);
  ImGui::EndDisabled();
  if (!st.settings().recent_paths.empty()) {
    ImGui::TextDisabled("Recent");
    for (const std::string& p : st.settings().recent_paths) {
      ImGui::PushID(p.c_str());
      if (ImGui::Selectable(p.c_str(), false, st.opening() ? ImGuiSelectableFlags_Disabled : 0)) {
        path_ = p;
        try_open(st, p);
        ImGui::PopID();
        break;  // the list may have changed order
      }
      ImGui::PopID();
    }
  }
  if (importable_ || st.importer().state() != JobState::Idle) draw_import(st);
  if (st.opening()) ImGui::TextColored(kBusyColour, "opening %s ...", st.opening_path().c_str());
  if (!st.open_error().empty()) ImGui::TextColored(kErrorColour, "%s", st.open_error().c_str());
  if (const OpenedScene* s = st.scene()) {
    ImGui::Separator();
    ImGui::TextWrapped("%s: %s", scene_kind_name(s->kind), s->path.string().c_str());
    if (s->dataset)
      ImGui::Text("%s, %zu train / %zu test views", s->dataset->format.c_str(), s->dataset->train.size(),
                  s->dataset->test.size());
    if (s->model) ImGui::Text("%zu Gaussians (%s)", s->model->count(), s->model_source.c_str());
  }
}

void OpenPanel::draw_import(AppState& st) {
  ImGui::Separator();
  const CaptureJob& job = st.importer();
  const bool active = job.active();
  if (importable_ && !active) {
    ImGui::TextWrapped("%s is %s, not a data set: import it with COLMAP (camera poses, points, undistorted photos).",
                       path_.c_str(), capture::is_video_file(path_) ? "a video" : "a folder of photos");
    capture::CaptureOptions& f = st.import_form;
    ImGui::SetNextItemWidth(120);
    ImGui::InputInt("max images", &f.max_images);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("0: every photo of a folder, 100 frames of a video (the sharpest of each stretch)");
    f.max_images = std::max(f.max_images, 0);
    ImGui::SetNextItemWidth(120);
    ImGui::InputInt("resolution (width px)", &f.width);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Shrink the photos to this width first; 0 keeps their size");
    f.width = std::max(f.width, 0);
    ImGui::SetNextItemWidth(120);
    if (ImGui::BeginCombo("matcher", f.matcher.c_str())) {
      for (const char* m : {"exhaustive", "sequential"})
        if (ImGui::Selectable(m, f.matcher == m)) f.matcher = m;
      ImGui::EndCombo();
    }
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("exhaustive: every pair (photos); sequential: each with its 10 neighbours (videos, photos "
                        "taken in order: faster)");
    std::string masks = f.masks.string(), out = f.out.string();
    ImGui::SetNextItemWidth(-110);
    if (ImGui::InputTextWithHint("masks folder", "optional: MASKS/<photo name>.png", &masks)) f.masks = masks;
    ImGui::SetNextItemWidth(-110);
    if (ImGui::InputTextWithHint("output folder", "a new folder", &out)) f.out = out;
    ImGui::BeginDisabled(st.opening() || st.training_active() || f.out.empty());
    if (ImGui::Button("Import photos / video")) report_errors(st, [&] { st.start_import(f); });
    ImGui::EndDisabled();
  }
  if (job.state() != JobState::Idle) draw_import_progress(st);
  if (active && ImGui::Button("Cancel import")) st.importer().cancel();
}

void OpenPanel::draw_import_progress(const AppState& st) {
  const CaptureJob& job = st.importer();
  const JobState js = job.state();
  const capture::CaptureOptions o = job.options();
  ImGui::TextWrapped("import %s -> %s", o.input.string().c_str(), o.out.string().c_str());
  if (js == JobState::Running || js == JobState::Cancelling) {
    const CaptureJobProgress p = job.progress();
    for (int k = 0; k < kCaptureStageCount; ++k) {
      const CaptureStageStatus& s = p.stages[size_t(k)];
      char overlay[96];
      if (s.complete)
        std::snprintf(overlay, sizeof overlay, "%s: done in %s", capture_stage_name(k),
                      duration_text(s.seconds).c_str());
      else if (s.started && s.total > 0)
        std::snprintf(overlay, sizeof overlay, "%s: %d/%d, ETA %s", capture_stage_name(k), s.done, s.total,
                      s.eta_s >= 0 ? duration_text(s.eta_s).c_str() : "--");
      else if (s.started)
        std::snprintf(overlay, sizeof overlay, "%s: %s", capture_stage_name(k), duration_text(s.seconds).c_str());
      else
        std::snprintf(overlay, sizeof overlay, "%s", capture_stage_name(k));
      ImGui::ProgressBar(s.fraction(), ImVec2(-1, 0), overlay);
    }
    ImGui::TextColored(kBusyColour, "%s   elapsed %s", job.status().c_str(), duration_text(job.elapsed_s()).c_str());
  } else if (js == JobState::Error) {
    ImGui::PushStyleColor(ImGuiCol_Text, kErrorColour);
    ImGui::TextWrapped("import failed: %s", job.status().c_str());
    ImGui::PopStyleColor();
  } else if (js == JobState::Cancelled) {
    ImGui::TextWrapped("%s", job.status().c_str());
  } else if (js == JobState::Done) {
    if (const auto r = job.report()) {
      ImGui::Text("registered %d of %d photos (%.0f %%)", r->registered, r->images,
                  r->images ? 100.0 * r->registered / r->images : 0.0);
      ImGui::Text("mean reprojection error %.3f px, %lld points", r->mean_reprojection_error_px, r->points);
      ImGui::Text("%dx%d photos, %s matching, %s", r->width, r->height, r->matcher.c_str(),
                  duration_text(r->seconds_total).c_str());
      if (r->registered < r->images * 0.9) {
        ImGui::PushStyleColor(ImGuiCol_Text, kBusyColour);
        ImGui::TextWrapped("%d photos were not placed and are left out: see %s", r->images - r->registered,
                           (r->out / "capture_report.txt").string().c_str());
        ImGui::PopStyleColor();
      }
    }
  }
}

}  // namespace goris::ui
