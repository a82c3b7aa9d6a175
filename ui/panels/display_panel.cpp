#include "ui/panels/display_panel.h"

#include <imgui.h>

namespace goris::ui {

void DisplayPanel::draw(AppState& st) {
  int grid = int(st.grid_channels.size());
  ImGui::SetNextItemWidth(150);
  if (ImGui::SliderInt("grid tiles", &grid, 0, AppState::kMaxGrid)) st.set_grid_count(grid);
  ImGui::SetNextItemWidth(150);
  ImGui::SliderInt("render size cap", &st.settings().display_max_side, 64, 2048, "%d px");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("viewports render on the engine at most this many pixels on the longest side");
  ImGui::Checkbox("tint the object label (> 0.5)", &st.label_overlay);
  if (st.has_before()) {
    // A cleaned scene: its run with the target is at hand for the toggle and the compare modes.
    bool before = st.showing_before();
    if (ImGui::Checkbox("before (with the target)  [B]", &before)) st.show_before(before);
    ImGui::Checkbox("compare with the scene with the target", &st.compare_with_before);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("off: compare with the nearest input photo");
  }
  int mode = int(st.compare);
  ImGui::Text(st.comparing_with_before() || (st.has_before() && st.compare_with_before)
                  ? "compare with the scene with the target"
                  : "compare with the input photo");
  bool changed = ImGui::RadioButton("off", &mode, int(CompareMode::Off));
  ImGui::SameLine();
  changed |= ImGui::RadioButton("side by side", &mode, int(CompareMode::SideBySide));
  ImGui::SameLine();
  changed |= ImGui::RadioButton("slider", &mode, int(CompareMode::Slider));
  float split = st.compare_split;
  if (st.compare == CompareMode::Slider) {
    ImGui::SetNextItemWidth(150);
    changed |= ImGui::SliderFloat("split", &split, 0.0f, 1.0f, "%.2f");
  }
  if (changed) st.set_compare(CompareMode(mode), split);
}

}  // namespace goris::ui
