#include "ui/panels/tool_bar.h"

#include <imgui.h>

#include <iterator>
#include <map>

#include "ui/panels/panel.h"

namespace goris::ui {

namespace {

// The buttons drawn in the frame before (label -> rectangle) and in this one.
struct DrawnButtons {
  int frame = -1;
  std::map<std::string, Rect> last, current;
};
DrawnButtons& drawn() {
  static DrawnButtons d;
  return d;
}

// Remembers where the last item was drawn under `label`.
void remember(const std::string& label) {
  DrawnButtons& d = drawn();
  if (d.frame != ImGui::GetFrameCount()) {
    d.last = std::move(d.current);
    d.current.clear();
    d.frame = ImGui::GetFrameCount();
  }
  const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
  d.current[label] = Rect{a.x, a.y, b.x - a.x, b.y - a.y};
}

// ImGui::Button, remembered for scripts (`prefix` tells apart buttons of the same label).
bool button(const char* label, const char* prefix = nullptr) {
  const bool pressed = ImGui::Button(label);
  remember(prefix ? std::string(prefix) + " " + label : std::string(label));
  return pressed;
}

constexpr SelectTool kTools[] = {SelectTool::Click, SelectTool::Rect,   SelectTool::Lasso,
                                 SelectTool::Brush, SelectTool::Sphere, SelectTool::Box};

const char* tool_tip(SelectTool t) {
  switch (t) {
    case SelectTool::Click:
      return "click: the Gaussian under the cursor, grown with the slider";
    case SelectTool::Rect:
      return "drag a rectangle on the main viewport";
    case SelectTool::Lasso:
      return "drag a lasso (a free polygon) on the main viewport";
    case SelectTool::Brush:
      return "paint on the main viewport with a round brush";
    case SelectTool::Sphere:
      return "a sphere: drag its centre and radius handles, then Select";
    case SelectTool::Box:
      return "a box: drag its centre and axis handles, then Select";
  }
  return "";
}

// Select / Add / Subtract buttons for a region that `run` selects in a mode.
template <class Run>
void mode_buttons(AppState& st, const char* id, Run run) {
  ImGui::PushID(id);
  if (button("Select", id)) report_errors(st, [&] { run(SelectMode::Replace); });
  ImGui::SameLine();
  if (button("Add", id)) report_errors(st, [&] { run(SelectMode::Add); });
  ImGui::SameLine();
  if (button("Subtract", id)) report_errors(st, [&] { run(SelectMode::Remove); });
  ImGui::PopID();
}

void volume_fields(AppState& st) {
  SelectionTools& t = st.tools;
  st.place_volumes_if_needed();
  VolumeRegion& v = t.volume();
  const float speed = 0.005f * (st.scene() ? st.scene()->radius : 1.0f);
  ImGui::SetNextItemWidth(200);
  ImGui::DragFloat3("centre", &v.centre.x, speed, 0, 0, "%.3f");
  ImGui::SetNextItemWidth(200);
  if (v.kind == VolumeRegion::Kind::Sphere) {
    ImGui::DragFloat("radius", &v.radius, speed, 1e-4f, 1e6f, "%.3f");
  } else {
    ImGui::DragFloat3("half size", &v.half_extent.x, speed, 1e-4f, 1e6f, "%.3f");
    ImGui::SetNextItemWidth(200);
    ImGui::DragFloat3("rotation", &v.rotation_degrees.x, 0.5f, -180.0f, 180.0f, "%.1f deg");
  }
  if (button("Place at the picked point")) {
    if (st.last_pick && st.last_pick->hit)
      v.centre = st.last_pick->world;
    else
      st.message("place: click on the scene first (the picked point is where the volume goes)", true);
  }
  mode_buttons(st, "volume", [&](SelectMode m) { st.select_volume(v, m); });
}

void colour_range(AppState& st) {
  SelectionTools& t = st.tools;
  ImGui::SetNextItemWidth(200);
  ImGui::ColorEdit3("colour", &t.colour.x, ImGuiColorEditFlags_Float);
  ImGui::SetNextItemWidth(200);
  ImGui::SliderFloat("within", &t.colour_distance, 0.0f, 1.0f, "%.2f");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("RGB distance of the Gaussians' base (SH DC) colour");
  if (button("Colour of the picked pixel")) {
    const auto& f = st.frame;
    if (f && st.last_pick && st.last_pick->hit && !f->color.empty()) {
      const size_t i = 3 * (size_t(st.last_pick->y) * size_t(f->width) + size_t(st.last_pick->x));
      if (i + 2 < f->color.size()) t.colour = {f->color[i], f->color[i + 1], f->color[i + 2]};
    } else {
      st.message("colour: click on the scene first", true);
    }
  }
  mode_buttons(st, "colour", [&](SelectMode m) { st.select_colour(t.colour, t.colour_distance, m); });
}

}  // namespace

void draw_selection_tools(AppState& st) {
  SelectionTools& t = st.tools;
  for (std::size_t k = 0; k < std::size(kTools); ++k) {  // three to a row, in columns
    const SelectTool tool = kTools[k];
    if (k % 3 != 0) ImGui::SameLine(8.0f + 90.0f * float(k % 3));
    const bool chosen = ImGui::RadioButton(select_tool_label(tool), t.tool == tool);
    remember(select_tool_label(tool));
    if (chosen) {
      t.tool = tool;
      if (t.volume_tool()) st.place_volumes_if_needed();
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", tool_tip(tool));
  }
  ImGui::TextDisabled("shift: add   ctrl: remove");
  if (t.tool == SelectTool::Rect || t.tool == SelectTool::Lasso || t.tool == SelectTool::Brush) {
    ImGui::TextDisabled("drag on the view to select, alt+drag orbits");
    ImGui::Checkbox("through everything", &t.through_all);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("on: every Gaussian whose centre lies inside, also those hidden behind the surface\n"
                        "off: only what the view shows");
  }
  if (t.tool == SelectTool::Brush) {
    ImGui::SetNextItemWidth(160);
    ImGui::SliderFloat("brush radius", &t.brush_radius, 2.0f, 100.0f, "%.0f px");
  }
  if (t.volume_tool()) volume_fields(st);

  if (ImGui::CollapsingHeader("Colour range")) colour_range(st);

  if (button("Invert")) report_errors(st, [&] { st.select_invert(); });
  ImGui::SameLine();
  if (button("Grow step")) report_errors(st, [&] { st.select_step(t.step_rings); });
  ImGui::SameLine();
  if (button("Shrink step")) report_errors(st, [&] { st.select_step(-t.step_rings); });
  ImGui::SameLine();
  ImGui::SetNextItemWidth(60);
  ImGui::InputInt("##rings", &t.step_rings, 0, 0);
  if (t.step_rings < 1) t.step_rings = 1;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("rings of graph neighbours per step");

  const SelectionView v = st.selection().view();
  if (button("Hide")) report_errors(st, [&] { st.hide_selected(); });
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("hidden Gaussians are not drawn and cannot be selected");
  ImGui::SameLine();
  if (button("Lock")) report_errors(st, [&] { st.lock_selected(); });
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("locked Gaussians are drawn but cannot be selected");
  ImGui::SameLine();
  ImGui::BeginDisabled(v.hidden_count == 0);
  if (button("Unhide all")) report_errors(st, [&] { st.unhide_all(); });
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::BeginDisabled(v.locked_count == 0);
  if (button("Unlock all")) report_errors(st, [&] { st.unlock_all(); });
  ImGui::EndDisabled();
  if (v.hidden_count || v.locked_count) ImGui::TextDisabled("%zu hidden, %zu locked", v.hidden_count, v.locked_count);

  ImGui::BeginDisabled(!v.mask);
  if (button("Use as target masks")) report_errors(st, [&] { st.use_as_target_masks({}); });
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("writes every training view's object mask of the selection to RUN/target_masks and selects "
                      "by their votes: the target Remove takes");
}

std::optional<Rect> tool_bar_button(const std::string& label) {
  const DrawnButtons& d = drawn();
  if (d.frame < ImGui::GetFrameCount() - 1) return std::nullopt;  // not drawn lately
  // The frame being drawn may not have reached the tool bar yet: the one before has it whole.
  const std::map<std::string, Rect>& m = d.frame == ImGui::GetFrameCount() ? d.last : d.current;
  const auto it = m.find(label);
  if (it == m.end()) return std::nullopt;
  return it->second;
}

}  // namespace goris::ui
