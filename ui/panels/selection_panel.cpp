#include "ui/panels/selection_panel.h"

#include <imgui.h>

#include "ui/panels/tool_bar.h"

namespace goris::ui {

void SelectionPanel::draw(AppState& st) {
  const SelectionSession& sel = st.selection();
  const SelectionView v = sel.view();
  const char* blocked = st.selection_blocked();
  if (v.total > 0)
    ImGui::Text("%zu of %zu Gaussians (%.1f%%)%s", v.selected, v.total,
                100.0 * double(v.selected) / double(v.total), v.selected == 0 ? "" : v.saved ? ", saved" : ", not saved");
  else
    ImGui::TextDisabled("Nothing to select in yet.");
  if (sel.busy()) {
    ImGui::SameLine();
    ImGui::TextColored(ImVec4(1, 0.85f, 0.3f, 1), "working ...");
  }
  if (blocked) ImGui::TextWrapped("(%s)", blocked);

  ImGui::BeginDisabled(blocked != nullptr);
  draw_selection_tools(st);
  ImGui::Separator();
  // The slider follows the selection unless the user is dragging it.
  if (!dragging_) grow_ = v.grow;
  ImGui::SetNextItemWidth(160);
  if (ImGui::SliderFloat("grow / shrink", &grow_, -1.0f, 1.0f, "%.2f")) {
    report_errors(st, [&] { st.select_grow(grow_, /*merge=*/drag_edited_); });  // a drag is one undo step
    drag_edited_ = true;
  }
  dragging_ = ImGui::IsItemActive();
  if (!dragging_) drag_edited_ = false;
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip(
        "> 0: each clicked Gaussian grows over similar connected neighbours (more with larger values)\n"
        "< 0: the whole selection is eroded (up to %d steps)\nOne undo step per drag.",
        kMaxShrinkSteps);

  if (ImGui::Button("From labels")) report_errors(st, [&] { st.select_labels(); });
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("Gaussians whose learned object label exceeds 0.3, closed by their hull (paper Sec. 3.3)");
  ImGui::SameLine();
  if (ImGui::Button("Load masks")) report_errors(st, [&] { st.select_masks(); });
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("votes of the Gaussian centres in the training views' object masks (mask_XXX.png)");
  ImGui::SameLine();
  if (ImGui::Button("Clear")) report_errors(st, [&] { st.select_clear(); });

  ImGui::BeginDisabled(!v.can_undo);
  if (ImGui::Button("Undo")) report_errors(st, [&] { st.undo_selection(); });
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::BeginDisabled(!v.can_redo);
  if (ImGui::Button("Redo")) report_errors(st, [&] { st.redo_selection(); });
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::BeginDisabled(!v.mask || sel.busy());
  if (ImGui::Button("Save")) report_errors(st, [&] { st.save_selection(); });
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("writes RUN/selection.json (+ .npy): what Remove and `goris remove` take");
  ImGui::EndDisabled();

  for (const std::string& p : v.parts) ImGui::BulletText("%s", p.c_str());
}

}  // namespace goris::ui
