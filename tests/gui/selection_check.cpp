// gui_selection_check: helpers of the GUI selection test.
//
//   gui_selection_check target DATASET
//       picks the training view whose object mask has the deepest interior point (the easiest click on
//       the target) and prints "VIEW X% Y%": its index and that point in percent of the image.
//   gui_selection_check tint BEFORE.png AFTER.png MASK.png
//       compares two screenshots of the same view (AFTER.layout.json gives the main viewport's image)
//       before and after selecting: the pixels that changed are the selection tint. Passes when there are
//       enough of them, most lie inside the (dilated) object mask scaled onto the viewport, and they
//       cover some of the mask (a click on a model of a few dozen iterations selects a few Gaussians, not
//       the whole object). Prints the counts; exits 1 with the reason on failure.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

#include "core/io/dataset.h"
#include "core/io/image.h"
#include "tests/gui/layout_file.h"

namespace {

int fail(const std::string& why) {
  std::fflush(stdout);
  std::fprintf(stderr, "FAILED: %s\n", why.c_str());
  return 1;
}

cv::Mat binary_mask(const goris::Image& m) {
  cv::Mat b(m.height, m.width, CV_8UC1);
  for (int y = 0; y < m.height; ++y)
    for (int x = 0; x < m.width; ++x) b.at<uint8_t>(y, x) = m.pixels[size_t(y) * m.width + x] > 0.5f ? 255 : 0;
  return b;
}

int target(const std::string& dataset) {
  const goris::Dataset ds = goris::load_dataset(dataset, {});
  int best = -1;
  double best_depth = 0;
  cv::Point best_at;
  cv::Size best_size;
  for (size_t i = 0; i < ds.train.size(); ++i) {
    if (!ds.train[i].object_mask) continue;
    const cv::Mat b = binary_mask(goris::load_view_object_mask(ds.train[i]));
    cv::Mat dist;
    cv::distanceTransform(b, dist, cv::DIST_L2, 3);
    double depth = 0;
    cv::Point at;
    cv::minMaxLoc(dist, nullptr, &depth, nullptr, &at);
    if (depth > best_depth) {
      best = int(i);
      best_depth = depth;
      best_at = at;
      best_size = b.size();
    }
  }
  if (best < 0) return fail(dataset + ": no training view has an object mask");
  std::printf("%d %.2f%% %.2f%%\n", best, 100.0 * (best_at.x + 0.5) / best_size.width,
              100.0 * (best_at.y + 0.5) / best_size.height);
  std::fprintf(stderr, "view %d: deepest mask point (%d, %d), %.1f px from the edge\n", best, best_at.x, best_at.y,
               best_depth);
  return 0;
}

int tint(const std::string& before_png, const std::string& after_png, const std::string& mask_png) {
  const nlohmann::json layout = goris::test::read_layout(after_png);
  nlohmann::json main;
  for (const auto& v : layout.at("viewports"))
    if (v.at("name") == "main") main = v;
  if (main.is_null()) return fail("no main viewport in the layout of " + after_png);
  const goris::Image a = goris::read_image(before_png), b = goris::read_image(after_png);
  if (a.width != b.width || a.height != b.height || a.channels != b.channels)
    return fail("the two screenshots differ in size");
  const goris::Image mask = goris::load_mask(mask_png);
  // Dilated by ~6 % of the mask's size: the reconstruction of a few dozen iterations is blurry.
  cv::Mat m = binary_mask(mask);
  const int r = std::max(1, int(std::lround(0.06 * std::max(m.cols, m.rows))));
  cv::Mat dilated;
  cv::dilate(m, dilated, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * r + 1, 2 * r + 1)));

  const int x0 = int(std::ceil(main.at("x").get<double>())), y0 = int(std::ceil(main.at("y").get<double>()));
  const int w = int(main.at("w").get<double>()), h = int(main.at("h").get<double>());
  long tinted = 0, inside = 0, mask_px = 0, mask_tinted = 0;
  for (int y = y0; y < std::min(y0 + h, a.height); ++y)
    for (int x = x0; x < std::min(x0 + w, a.width); ++x) {
      const int mx = std::clamp(int((x - x0 + 0.5) * m.cols / w), 0, m.cols - 1);
      const int my = std::clamp(int((y - y0 + 0.5) * m.rows / h), 0, m.rows - 1);
      double d = 0;
      for (int c = 0; c < std::min(3, a.channels); ++c) {
        const size_t i = (size_t(y) * a.width + x) * a.channels + c;
        d += std::abs(double(a.pixels[i]) - double(b.pixels[i]));
      }
      const bool t = d > 0.08;
      const bool in_mask = m.at<uint8_t>(my, mx) > 0;
      tinted += t;
      inside += t && dilated.at<uint8_t>(my, mx) > 0;
      mask_px += in_mask;
      mask_tinted += t && in_mask;
    }
  const double inside_fraction = tinted ? double(inside) / double(tinted) : 0.0;
  const double coverage = mask_px ? double(mask_tinted) / double(mask_px) : 0.0;
  std::printf("tinted %ld pixels, %.1f%% inside the dilated mask; %.1f%% of the mask's %ld pixels tinted\n", tinted,
              100.0 * inside_fraction, 100.0 * coverage, mask_px);
  if (tinted < 30) return fail("almost nothing is tinted: the selection is not shown");
  if (inside_fraction < 0.8) return fail("the tint lies mostly outside the target's mask");
  if (coverage < 0.02) return fail("the tint covers next to nothing of the target");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  try {
    if (mode == "target" && argc == 3) return target(argv[2]);
    if (mode == "tint" && argc == 5) return tint(argv[2], argv[3], argv[4]);
  } catch (const std::exception& e) {
    return fail(e.what());
  }
  return fail("usage: gui_selection_check target DATASET | tint BEFORE.png AFTER.png MASK.png");
}
