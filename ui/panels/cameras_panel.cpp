#include "ui/panels/cameras_panel.h"

#include <imgui.h>

#include <cmath>
#include <string>

#include "core/util/error.h"

namespace goris::ui {

namespace {
void camera_list(AppState& st, const std::vector<View>& views, bool test) {
  for (size_t i = 0; i < views.size(); ++i) {
    const std::string label = std::to_string(i) + "  " + views[i].name;
    ImGui::PushID(int(i));
    const bool current = st.snapped && st.snapped_name == std::string(test ? "test " : "train ") + std::to_string(i) +
                                                              " (" + views[i].name + ")";
    if (ImGui::Selectable(label.c_str(), current)) {
      try {
        st.snap(i, test);
      } catch (const Error& e) {
        st.message(e.what(), true);
      }
    }
    ImGui::PopID();
  }
}
}  // namespace

void CamerasPanel::draw(AppState& st) {
  int mode = mode_ == CameraMode::Orbit ? 0 : 1;
  ImGui::RadioButton("orbit", &mode, 0);
  ImGui::SameLine();
  ImGui::RadioButton("fly", &mode, 1);
  mode_ = mode == 0 ? CameraMode::Orbit : CameraMode::Fly;
  ImGui::TextDisabled("drag: %s, right drag: pan, wheel: zoom, WASD QE: move (shift: faster)",
                      mode_ == CameraMode::Orbit ? "orbit" : "look");
  float fov = st.orbit.fov_y() * 57.29578f;
  ImGui::SetNextItemWidth(150);
  if (ImGui::SliderFloat("vertical FOV", &fov, 10.0f, 120.0f, "%.0f deg")) {
    st.orbit.set_fov_y(fov / 57.29578f);
    st.camera_moved();
  }
  ImGui::Text("view: %s", st.snapped ? st.snapped_name.c_str() : "free");
  const OpenedScene* scene = st.scene();
  if (!scene || !scene->dataset) return;
  const Dataset& ds = *scene->dataset;
  if (ImGui::TreeNode("training cameras", "training cameras (%zu)", ds.train.size())) {
    ImGui::BeginChild("train_list", ImVec2(0, 140), true);
    camera_list(st, ds.train, false);
    ImGui::EndChild();
    ImGui::TreePop();
  }
  if (ImGui::TreeNode("test cameras", "test cameras (%zu)", ds.test.size())) {
    ImGui::BeginChild("test_list", ImVec2(0, 140), true);
    camera_list(st, ds.test, true);
    ImGui::EndChild();
    ImGui::TreePop();
  }
}

}  // namespace goris::ui
