#include "ui/panels/plots_panel.h"

#include <imgui.h>

#include <algorithm>
#include <cstdio>

namespace goris::ui {

namespace {
void plot(const char* name, const std::vector<float>& v, const char* format) {
  if (v.empty()) return;
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  char overlay[96];
  std::snprintf(overlay, sizeof overlay, format, double(v.back()));
  const float pad = (*hi - *lo) * 0.05f + 1e-6f;
  // ImGui 1.86's PlotLines takes no negative (right-aligned) width: leave room for the label by hand.
  const float w = std::max(ImGui::GetContentRegionAvail().x - 80.0f, 40.0f);
  ImGui::PlotLines(name, v.data(), int(v.size()), 0, overlay, *lo - pad, *hi + pad, ImVec2(w, 56));
}
}  // namespace

void PlotsPanel::draw(AppState& st) {
  const TrainingHistory h = st.session().history();
  if (h.samples().empty()) {
    ImGui::TextDisabled("No training yet.");
    return;
  }
  ImGui::Text("iterations %d .. %d", h.samples().front().iteration, h.samples().back().iteration);
  plot("loss", h.series(&ProgressSample::loss), "%.4f");
  plot("PSNR", h.series(&ProgressSample::psnr), "%.2f dB");
  plot("Gaussians", h.series(&ProgressSample::gaussians), "%.0f");
  plot("it/s", h.series(&ProgressSample::it_per_s), "%.1f");
}

}  // namespace goris::ui
