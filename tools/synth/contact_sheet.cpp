#include "tools/synth/contact_sheet.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "core/util/error.h"

namespace goris::synth {
namespace fs = std::filesystem;

namespace {
constexpr int kMaxViews = 8;      // "a few" test views: enough to judge the scene, small enough to look at
constexpr int kViewsPerRow = 2;   // each view is a triplet full_ | r_ | mask
constexpr int kMinCell = 256;     // small renders are enlarged (nearest) so reflections can be seen
constexpr int kLabel = 22;        // height of the caption strip above each triplet
constexpr int kGap = 8;

std::string view_id(int i) {
  char b[16];
  std::snprintf(b, sizeof b, "%03d", i);
  return b;
}

cv::Mat read_as_bgr(const fs::path& p) {
  cv::Mat m = cv::imread(p.string(), cv::IMREAD_UNCHANGED);
  if (m.empty()) throw Error(p.string(), "cannot read the image for the contact sheet");
  if (m.depth() != CV_8U) throw Error(p.string(), "expected an 8-bit image for the contact sheet");
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

// full_ | r_ | mask of one test view under a caption naming it.
cv::Mat triplet(const fs::path& test_dir, const std::string& id) {
  std::vector<cv::Mat> cells{read_as_bgr(test_dir / ("full_" + id + ".png")), read_as_bgr(test_dir / ("r_" + id + ".png")),
                             read_as_bgr(test_dir / ("mask_" + id + ".png"))};
  for (size_t i = 1; i < cells.size(); ++i)
    if (cells[i].size() != cells[0].size())
      throw Error((test_dir / ("full_" + id + ".png")).string(), "the test view's images differ in size");
  int scale = std::max(1, (kMinCell + cells[0].cols - 1) / cells[0].cols);
  for (auto& c : cells) cv::resize(c, c, {}, scale, scale, cv::INTER_NEAREST);
  cv::Mat images;
  cv::hconcat(cells, images);
  cv::Mat out(images.rows + kLabel, images.cols, CV_8UC3, cv::Scalar(40, 40, 40));
  images.copyTo(out(cv::Rect(0, kLabel, images.cols, images.rows)));
  const std::string caption = "test " + id + ":  full_ (with target)  |  r_ (removed)  |  mask_";
  cv::putText(out, caption, {6, kLabel - 7}, cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(235, 235, 235), 1, cv::LINE_AA);
  return out;
}
}  // namespace

void write_contact_sheet(const fs::path& dir, const fs::path& png_path) {
  const fs::path test_dir = dir / "test";
  int count = 0;
  while (fs::exists(test_dir / ("full_" + view_id(count) + ".png"))) ++count;
  if (count == 0) throw Error(test_dir.string(), "no full_XXX.png test views for the contact sheet");

  // Views spread evenly over the test set (consecutive test cameras sit close together on the spiral).
  const int shown = std::min(count, kMaxViews);
  std::vector<cv::Mat> tiles;
  for (int k = 0; k < shown; ++k) {
    tiles.push_back(triplet(test_dir, view_id(int(int64_t(k) * count / shown))));
  }
  const int tw = tiles[0].cols, th = tiles[0].rows;
  const int cols = std::min(shown, kViewsPerRow), rows = (shown + cols - 1) / cols;
  cv::Mat sheet(rows * th + (rows + 1) * kGap, cols * tw + (cols + 1) * kGap, CV_8UC3, cv::Scalar(20, 20, 20));
  for (int k = 0; k < shown; ++k) {
    int r = k / cols, c = k % cols;
    tiles[size_t(k)].copyTo(sheet(cv::Rect(kGap + c * (tw + kGap), kGap + r * (th + kGap), tw, th)));
  }
  fs::path tmp = png_path;
  tmp += ".tmp.png";
  if (!cv::imwrite(tmp.string(), sheet)) throw Error(tmp.string(), "cannot write the contact sheet");
  fs::rename(tmp, png_path);
}

}  // namespace goris::synth
