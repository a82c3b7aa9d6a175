#include "core/synth/contact_sheet.h"

#include <algorithm>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "core/util/error.h"

namespace goris::synth {
namespace fs = std::filesystem;

namespace {
cv::Mat read_as_bgr(const fs::path& p) {
  cv::Mat m = cv::imread(p.string(), cv::IMREAD_UNCHANGED);
  if (m.empty()) throw Error(p.string(), "cannot read the image for the contact sheet");
  if (m.channels() == 1) cv::cvtColor(m, m, cv::COLOR_GRAY2BGR);
  if (m.channels() == 4) {  // composite over grey so the transparent background is visible as such
    cv::Mat out(m.size(), CV_8UC3);
    m.forEach<cv::Vec4b>([&](const cv::Vec4b& px, const int* pos) {
      float a = px[3] / 255.0f;
      for (int c = 0; c < 3; ++c) out.at<cv::Vec3b>(pos[0], pos[1])[c] = cv::saturate_cast<uchar>(px[c] * a + 96 * (1 - a));
    });
    m = out;
  }
  return m;
}
}  // namespace

void write_contact_sheet(const fs::path& dir, const fs::path& png_path) {
  std::vector<cv::Mat> rows;
  for (int i = 0;; ++i) {
    char name[16];
    std::snprintf(name, sizeof name, "%03d.png", i);
    fs::path full = dir / "test" / ("full_" + std::string(name));
    if (!fs::exists(full)) break;
    std::vector<cv::Mat> cells{read_as_bgr(full), read_as_bgr(dir / "test" / ("r_" + std::string(name))),
                               read_as_bgr(dir / "test" / ("mask_" + std::string(name)))};
    int scale = std::max(1, (128 + cells[0].cols - 1) / cells[0].cols);
    for (auto& c : cells) cv::resize(c, c, {}, scale, scale, cv::INTER_NEAREST);
    cv::Mat row;
    cv::hconcat(cells, row);
    rows.push_back(row);
  }
  if (rows.empty()) throw Error((dir / "test").string(), "no full_XXX.png test views for the contact sheet");
  cv::Mat sheet;
  cv::vconcat(rows, sheet);
  fs::path tmp = png_path;
  tmp += ".tmp.png";
  if (!cv::imwrite(tmp.string(), sheet)) throw Error(tmp.string(), "cannot write the contact sheet");
  fs::rename(tmp, png_path);
}

}  // namespace goris::synth
