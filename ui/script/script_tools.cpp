// ScriptRunner's actions for the selection tool bar, the volume handles and the two-click flow
// (ui/script/script.h: press, drag_handle, two_click).
#include <cstdio>

#include "core/util/error.h"
#include "ui/script/script_runner.h"
#include "ui/panels/tool_bar.h"
#include "ui/viewport/viewport_tools.h"

namespace goris::ui {

bool ScriptRunner::run_press(ScriptHost& host, const ScriptAction& a) {
  if (phase_ == 0) {
    if (!host.settled()) return false;
    const std::optional<Rect> r = tool_bar_button(a.text);
    if (!r) throw Error("no tool-bar button '" + a.text + "' is shown (panels Selection; is its section open?)");
    // Hover, press, release at the button's centre, then the real pointer again.
    ScriptedMouse m;
    m.pos = glm::vec2(r->x + 0.5f * r->w, r->y + 0.5f * r->h);
    drag_ = {m, m};
    m.left_down = true;
    drag_.push_back(m);
    m.left_down = false;
    drag_.push_back(m);
    drag_.push_back(m);
    phase_ = 1;
  }
  if (!run_drag(host, a)) return false;  // plays the mouse, waits for the edit
  std::printf("pressed %s\n", a.text.c_str());
  std::fflush(stdout);
  return true;
}

bool ScriptRunner::run_drag_handle(ScriptHost& host, const ScriptAction& a) {
  AppState& st = host.state();
  if (phase_ == 0) {
    if (!host.settled()) return false;
    if (!st.tools.volume_tool()) throw Error("choose the sphere or box tool first (select_tool sphere)");
    const glm::vec2 size = host.main_image_size();
    using H = ViewportTools::Handle;
    const H want = a.what == "centre" ? H::Centre : a.what == "radius" ? H::Radius : a.what == "x" ? H::AxisX
                   : a.what == "y"    ? H::AxisY
                                      : H::AxisZ;
    std::optional<glm::vec2> at, centre;
    for (const auto& [h, p] : ViewportTools().handles(st, Rect{0, 0, size.x, size.y})) {
      if (h == want) at = p;
      if (h == H::Centre) centre = p;
    }
    if (!at || !centre)
      throw Error("the " + std::string(select_tool_id(st.tools.tool)) + " has no " + a.what + " handle in view");
    // A size handle's drag is along its own direction on screen (outward) and across it.
    glm::vec2 delta(a.values[0], a.values[1]);
    if (want != H::Centre) {
      const glm::vec2 d = *at - *centre;
      if (glm::length(d) < 1.0f) throw Error("the " + a.what + " handle points at the camera: orbit first");
      const glm::vec2 out = d / glm::length(d), across(-out.y, out.x);
      delta = a.values[0] * out + a.values[1] * across;
    }
    handle_drag_ = a;
    handle_drag_.coords.clear();
    for (const float v : {at->x, at->y, at->x + delta.x, at->y + delta.y}) handle_drag_.coords.push_back({v, false});
    std::printf("dragging the %s handle from (%.1f, %.1f) by (%.1f, %.1f)\n", a.what.c_str(), double(at->x),
                double(at->y), double(delta.x), double(delta.y));
    std::fflush(stdout);
  }
  return run_drag(host, handle_drag_);
}

bool ScriptRunner::run_two_click(ScriptHost& host, const ScriptAction& a) {
  AppState& st = host.state();
  TwoClickFlow& f = st.two_click;
  if (phase_ == 0) {
    if (!host.settled() || f.busy()) return false;
    const std::string& w = a.what;
    job_ = 0;
    if (w == "start") {
      f.start(st, a.count >= 0 ? std::optional<std::size_t>(std::size_t(a.count)) : std::nullopt);
    } else if (w == "view") {
      f.show_view(st, std::size_t(a.count));
    } else if (w == "click") {
      const glm::vec2 size = host.main_image_size();
      const float x = a.x_fraction ? std::min(a.x * size.x, size.x - 0.5f) : a.x;
      const float y = a.y_fraction ? std::min(a.y * size.y, size.y - 0.5f) : a.y;
      job_ = f.click(st, x, y, size);
    } else if (w == "offered") {
      job_ = f.click_offered(st);
    } else if (w == "take_back") {
      job_ = f.remove_click(st, std::size_t(a.count - 1));
    } else if (w == "undo") {
      job_ = f.undo(st);
    } else if (w == "cancel") {
      f.cancel(st);
    } else if (w == "use") {
      job_ = f.use_and_remove(st, std::max(0, a.count));
    } else if (w == "expect") {
      std::string at = flow_step_name(f.step());
      for (char& c : at)
        if (c == ' ') c = '_';
      if (at != a.text) throw Error("the flow is at '" + at + "', expected '" + a.text + "'");
      std::printf("two-click at %s\n", at.c_str());
      std::fflush(stdout);
      return true;
    }
    phase_ = 1;
    return false;
  }
  if (phase_ == 1) {
    // The flow takes in its job in AppState::poll; a removal it started runs to its end.
    if (f.busy() || (job_ != 0 && !st.selection().finished(job_))) return false;
    if (a.what == "cancel" && f.active()) return false;
    if (f.step() == FlowStep::Removing) return false;
    if (const auto err = job_ != 0 ? st.selection().job_error(job_) : std::nullopt; err && a.what != "undo") {
      fail(a, *err);
      return false;
    }
    if (a.what == "use" && f.step() != FlowStep::Done) {
      fail(a, std::string("the removal ended ") + job_state_name(st.removal().state()) + ": " +
                  st.removal().status());
      return false;
    }
    phase_ = 2;
  }
  if (!host.settled()) return false;
  if (phase_ == 2) {
    const std::shared_ptr<const FlowResult>& r = f.result();
    std::printf("two-click %s: at %s, %zu clicks", a.what.c_str(), flow_step_name(f.step()), f.clicks().size());
    if (r && f.active()) {
      std::printf(", %zu of %zu Gaussians selected, masks in %s", r->selected, r->total, r->dir.string().c_str());
      if (f.step() == FlowStep::SecondClick && r->offered && st.scene() && st.scene()->dataset)
        std::printf(", offered %s (%d, %d)", st.scene()->dataset->train[r->offered->view].name.c_str(),
                    r->offered->x, r->offered->y);
    }
    std::printf("\n");
    std::fflush(stdout);
    phase_ = 3;
  }
  return true;
}

}  // namespace goris::ui
