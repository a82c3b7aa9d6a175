#include "ui/panels/open_panel.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include "core/util/error.h"

namespace goris::ui {

namespace {
void try_open(AppState& st, const std::string& path) {
  try {
    st.open(path);
  } catch (const Error& e) {
    st.message(e.what(), true);
  }
}
}  // namespace

void OpenPanel::draw(AppState& st) {
  ImGui::TextWrapped("A data set folder (NeRF-synthetic, COLMAP, ...), a run folder (config.json) or a model file "
                     "(.ply, .compressed.ply, .spz, .splat, .glb).");
  ImGui::SetNextItemWidth(-60);
  const bool enter = ImGui::InputTextWithHint("##path", "path", &path_, ImGuiInputTextFlags_EnterReturnsTrue);
  ImGui::SameLine();
  ImGui::BeginDisabled(st.opening() || path_.empty());
  if (ImGui::Button("Open") || (enter && !path_.empty())) try_open(st, path_);
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
  if (st.opening()) ImGui::TextColored(ImVec4(1, 0.85f, 0.3f, 1), "opening %s ...", st.opening_path().c_str());
  if (!st.open_error().empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", st.open_error().c_str());
  if (const OpenedScene* s = st.scene()) {
    ImGui::Separator();
    ImGui::TextWrapped("%s: %s", scene_kind_name(s->kind), s->path.string().c_str());
    if (s->dataset)
      ImGui::Text("%s, %zu train / %zu test views", s->dataset->format.c_str(), s->dataset->train.size(),
                  s->dataset->test.size());
    if (s->model) ImGui::Text("%zu Gaussians (%s)", s->model->count(), s->model_source.c_str());
  }
}

}  // namespace goris::ui
