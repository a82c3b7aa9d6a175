#include "ui/panels/two_click_panel.h"

#include <imgui.h>

#include <algorithm>
#include <cstdio>

namespace goris::ui {

namespace {

// "1. ..." with a mark: done, current, or still to come.
void step_line(int n, const char* text, FlowStep at, FlowStep step) {
  const bool done = int(at) > int(step), current = at == step;
  const ImVec4 colour = done ? ImVec4(0.5f, 0.85f, 0.5f, 1) : current ? ImVec4(1, 0.85f, 0.3f, 1) : ImVec4(0.6f, 0.6f, 0.6f, 1);
  ImGui::TextColored(colour, "%s %d. %s", done ? "[x]" : current ? "[>]" : "[ ]", n, text);
}

// Prev / next over the training views (snapping the main viewport).
void view_chooser(AppState& st, TwoClickFlow& f, std::size_t current, std::size_t n) {
  ImGui::PushID("views");
  if (ImGui::ArrowButton("prev", ImGuiDir_Left))
    report_errors(st, [&] { f.show_view(st, (current + n - 1) % n); });
  ImGui::SameLine();
  const std::string name = st.scene()->dataset->train[current].name;
  ImGui::Text("%s (%zu / %zu)", name.c_str(), current + 1, n);
  ImGui::SameLine();
  if (ImGui::ArrowButton("next", ImGuiDir_Right)) report_errors(st, [&] { f.show_view(st, (current + 1) % n); });
  ImGui::PopID();
}

// The review's strip: one bar per training view, as high as its mask's area; a click shows that view.
void mask_strip(AppState& st, TwoClickFlow& f, const FlowResult& r, std::size_t current) {
  const std::size_t n = r.masks.size();
  if (n == 0) return;
  std::size_t most = 1;
  for (const Mask& m : r.masks) most = std::max(most, count_set(m));
  const float w = std::max(3.0f, std::min(10.0f, (ImGui::GetContentRegionAvail().x - 4) / float(n))), h = 28.0f;
  const ImVec2 o = ImGui::GetCursorScreenPos();
  ImDrawList* dl = ImGui::GetWindowDrawList();
  for (std::size_t v = 0; v < n; ++v) {
    const std::size_t area = count_set(r.masks[v]);
    const float bh = area == 0 ? 2.0f : std::max(2.0f, h * float(area) / float(most));
    const ImU32 c = v == current ? IM_COL32(255, 210, 60, 255) : area == 0 ? IM_COL32(220, 80, 60, 255) : IM_COL32(90, 170, 255, 255);
    dl->AddRectFilled(ImVec2(o.x + float(v) * w, o.y + h - bh), ImVec2(o.x + float(v + 1) * w - 1, o.y + h), c);
  }
  ImGui::InvisibleButton("strip", ImVec2(w * float(n), h));
  if (ImGui::IsItemHovered()) {
    const std::size_t v = std::min(n - 1, std::size_t(std::max(0.0f, (ImGui::GetIO().MousePos.x - o.x) / w)));
    ImGui::SetTooltip("%s: %zu mask pixels", st.scene()->dataset->train[v].name.c_str(), count_set(r.masks[v]));
    if (ImGui::IsItemClicked()) report_errors(st, [&] { f.show_view(st, v); });
  }
}

}  // namespace

void TwoClickPanel::draw(AppState& st) {
  TwoClickFlow& f = st.two_click;
  const FlowStep at = f.step();
  const OpenedScene* scene = st.scene();
  const bool has_views = scene && scene->dataset && !scene->dataset->train.empty();
  if (!f.active()) {
    ImGui::TextWrapped("Select an object without object masks: two clicks, every view's mask, then Remove.");
    ImGui::BeginDisabled(!has_views || st.selection_blocked() != nullptr);
    if (ImGui::Button("Start")) report_errors(st, [&] { f.start(st); });
    ImGui::EndDisabled();
    if (const char* why = st.selection_blocked()) ImGui::TextDisabled("(%s)", why);
    return;
  }
  if (!has_views) return;
  const std::size_t n = scene->dataset->train.size();
  const std::size_t shown = st.snapped && !st.snapped_test ? st.snapped_index : f.review_view();
  const std::shared_ptr<const FlowResult>& r = f.result();

  step_line(1, "Click the object in one view", at, FlowStep::FirstClick);
  if (at == FlowStep::FirstClick) view_chooser(st, f, shown, n);
  step_line(2, "Click it in a second view", at, FlowStep::SecondClick);
  if (at == FlowStep::SecondClick) {
    view_chooser(st, f, shown, n);
    if (r && r->offered) {
      const FlowClick& o = *r->offered;
      ImGui::TextWrapped("Offered: %s, from another direction (the point at (%d, %d) lies on the object).",
                         scene->dataset->train[o.view].name.c_str(), o.x, o.y);
      ImGui::BeginDisabled(f.busy());
      if (ImGui::Button("Click the offered point")) report_errors(st, [&] { f.click_offered(st); });
      ImGui::EndDisabled();
    }
  }
  step_line(3, "Review every view's mask", at, FlowStep::Review);
  if (at == FlowStep::Review && r) {
    view_chooser(st, f, shown, n);
    mask_strip(st, f, *r, shown);
    ImGui::Text("%zu of %zu Gaussians, %zu clicks", r->selected, r->total, f.clicks().size());
    ImGui::TextDisabled("a click on the view adds its region");
    for (std::size_t k = 0; k < f.clicks().size(); ++k) {
      const FlowClick& c = f.clicks()[k];
      ImGui::PushID(int(k));
      ImGui::BeginDisabled(f.busy() || f.clicks().size() <= 1);
      if (ImGui::SmallButton("take back")) report_errors(st, [&] { f.remove_click(st, k); });
      ImGui::EndDisabled();
      ImGui::SameLine();
      ImGui::Text("%s (%d, %d)", scene->dataset->train[c.view].name.c_str(), c.x, c.y);
      ImGui::PopID();
    }
  }
  step_line(4, "Use as target masks and remove", at, FlowStep::Removing);
  if (at == FlowStep::Review) {
    ImGui::BeginDisabled(f.busy());
    if (ImGui::Button("Use as target masks and remove")) report_errors(st, [&] { f.use_and_remove(st); });
    ImGui::EndDisabled();
  }
  if (at == FlowStep::Done) ImGui::TextColored(ImVec4(0.5f, 0.85f, 0.5f, 1), "Done: the cleaned scene is shown.");

  // The running step's progress.
  if (f.busy() && f.progress().total > 0) {
    const float frac = float(f.progress().done) / float(std::max(1, f.progress().total.load()));
    ImGui::ProgressBar(frac, ImVec2(-1, 0), f.progress().get_stage().c_str());
  } else if (f.busy()) {
    ImGui::ProgressBar(0.0f, ImVec2(-1, 0), "waiting for the selection worker");
  } else if (at == FlowStep::Removing) {
    ImGui::ProgressBar(float(st.removal().progress().fraction()), ImVec2(-1, 0), "removing (Removal panel: each step)");
  }
  ImGui::BeginDisabled(f.undo_steps() == 0 && !f.busy() && at != FlowStep::Removing);
  if (ImGui::Button("Undo step")) report_errors(st, [&] { f.undo(st); });
  ImGui::EndDisabled();
  ImGui::SameLine();
  if (ImGui::Button(at == FlowStep::Done ? "Close" : "Cancel")) report_errors(st, [&] { f.cancel(st); });
}

}  // namespace goris::ui
