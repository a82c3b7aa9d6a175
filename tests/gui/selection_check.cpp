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
//   gui_selection_check removed WITH.png CLEANED.png RESTORED.png MASK.png
//       three screenshots of the same view: the scene with the target, the cleaned scene the editor shows
//       when the removal has finished, and the before / after toggle back to the scene with the target.
//       Passes when the cleaned scene differs from the scene with the target over the (dilated) object mask
//       in the main viewport, by more than elsewhere, and the toggle brings the scene with the target back.
//   gui_selection_check bbox MASK.png
//       prints the object mask's bounding box as "X0% Y0% X1% Y1%" (percent of the image).
//   gui_selection_check region BEFORE.png AFTER.png X0% Y0% X1% Y1%
//       the selection tools' check: the pixels of the main viewport that changed between the two
//       screenshots (the tint) lie inside this rectangle of the image (percent, widened by 8 % of the image
//       for the splats' extent around their centres), and cover some of it.
//   gui_selection_check same A.png B.png
//       the main viewports of the two screenshots are alike (undo brought the view back).
//   gui_selection_check iou DIR DATASET MIN_MEAN
//       the object masks a selection wrote (DIR/mask_XXX.png, any size) against the data set's own training
//       masks at that size: prints every view's IoU, their mean and minimum; fails when the mean is below
//       MIN_MEAN.
//   gui_selection_check slider WITH.png CLEANED.png SLIDER.png
//       the compare slider at 0.5 against the scene with the target: left of it the main viewport shows the
//       cleaned scene, right of it the scene with the target.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>

#include "core/inpaint/mask.h"
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

struct MainViewport {
  int x0 = 0, y0 = 0, w = 0, h = 0;
};

MainViewport main_viewport(const std::string& png) {
  const nlohmann::json layout = goris::test::read_layout(png);
  for (const auto& v : layout.at("viewports"))
    if (v.at("name") == "main")
      return {int(std::ceil(v.at("x").get<double>())), int(std::ceil(v.at("y").get<double>())), int(v.at("w").get<double>()),
              int(v.at("h").get<double>())};
  throw std::runtime_error("no main viewport in the layout of " + png);
}

// The object mask dilated by ~6 % of its size (a reconstruction of a few dozen iterations is blurry).
cv::Mat dilated_mask(const std::string& mask_png) {
  const cv::Mat m = binary_mask(goris::load_mask(mask_png));
  const int r = std::max(1, int(std::lround(0.06 * std::max(m.cols, m.rows))));
  cv::Mat dilated;
  cv::dilate(m, dilated, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * r + 1, 2 * r + 1)));
  return dilated;
}

// Mean |a - b| (RGB, 0..1) over the main viewport's pixels that the mask, scaled onto it, covers (every
// pixel for an empty mask) between the fractions x_from and x_to of its width.
double masked_difference(const goris::Image& a, const goris::Image& b, const MainViewport& v, const cv::Mat& m,
                         double x_from = 0, double x_to = 1) {
  if (a.width != b.width || a.height != b.height || a.channels != b.channels)
    throw std::runtime_error("the screenshots differ in size");
  double sum = 0;
  long n = 0;
  for (int y = v.y0; y < std::min(v.y0 + v.h, a.height); ++y)
    for (int x = v.x0; x < std::min(v.x0 + v.w, a.width); ++x) {
      const double fx = (x - v.x0 + 0.5) / v.w;
      if (fx < x_from || fx > x_to) continue;
      if (!m.empty()) {
        const int mx = std::clamp(int(fx * m.cols), 0, m.cols - 1);
        const int my = std::clamp(int((y - v.y0 + 0.5) * m.rows / v.h), 0, m.rows - 1);
        if (!m.at<uint8_t>(my, mx)) continue;
      }
      for (int c = 0; c < std::min(3, a.channels); ++c) {
        const size_t i = (size_t(y) * a.width + x) * a.channels + c;
        sum += std::abs(double(a.pixels[i]) - double(b.pixels[i])) / 3.0;
      }
      ++n;
    }
  if (n == 0) throw std::runtime_error("the mask covers nothing of the main viewport");
  return sum / double(n);
}

int removed(const std::string& with_png, const std::string& cleaned_png, const std::string& restored_png,
            const std::string& mask_png) {
  const MainViewport v = main_viewport(cleaned_png);
  const cv::Mat m = dilated_mask(mask_png);
  const goris::Image with = goris::read_image(with_png), cleaned = goris::read_image(cleaned_png),
                     restored = goris::read_image(restored_png);
  cv::Mat outside;
  cv::bitwise_not(m, outside);
  const double d_cleaned = masked_difference(with, cleaned, v, m), d_restored = masked_difference(with, restored, v, m);
  const double d_elsewhere = masked_difference(with, cleaned, v, outside);
  std::printf("mean |RGB| difference: cleaned %.4f over the target's mask, %.4f elsewhere; the toggle back %.4f\n",
              d_cleaned, d_elsewhere, d_restored);
  // A model of a few dozen iterations is a blur: removing the target changes its region by little, but
  // there more than anywhere else.
  if (d_cleaned < 0.003 || d_cleaned < 2 * d_elsewhere)
    return fail("the main viewport does not show the cleaned scene: the target's region is not what changed");
  if (d_restored > 0.3 * d_cleaned) return fail("before / after did not bring back the scene with the target");
  return 0;
}

// The slider at 0.5: left of it the cleaned scene, right of it the scene with the target.
int slider(const std::string& with_png, const std::string& cleaned_png, const std::string& slider_png) {
  const MainViewport v = main_viewport(slider_png);
  const goris::Image with = goris::read_image(with_png), cleaned = goris::read_image(cleaned_png),
                     shown = goris::read_image(slider_png);
  const double gap = 3.0 / v.w;  // the slider's line
  const double left = masked_difference(shown, cleaned, v, {}, 0, 0.5 - gap);
  const double right = masked_difference(shown, with, v, {}, 0.5 + gap, 1);
  std::printf("slider: left of it %.4f from the cleaned scene, right of it %.4f from the scene with the target\n",
              left, right);
  if (left > 0.004 || right > 0.004) return fail("the slider does not set the cleaned scene against the scene with the target");
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

int bbox(const std::string& mask_png) {
  const cv::Mat m = binary_mask(goris::load_mask(mask_png));
  const cv::Rect r = cv::boundingRect(m);
  if (r.area() == 0) return fail(mask_png + " is empty");
  std::printf("%.2f%% %.2f%% %.2f%% %.2f%%\n", 100.0 * r.x / m.cols, 100.0 * r.y / m.rows,
              100.0 * (r.x + r.width) / m.cols, 100.0 * (r.y + r.height) / m.rows);
  return 0;
}

double percent(const std::string& s) {
  std::size_t used = 0;
  const double v = std::stod(s, &used);
  if (used != s.size() && !(used + 1 == s.size() && s.back() == '%')) throw std::runtime_error("not a percentage: " + s);
  return v / 100.0;
}

// Per pixel of the main viewport: whether it changed between the screenshots by more than `threshold`
// (summed RGB).
cv::Mat changed_pixels(const goris::Image& a, const goris::Image& b, const MainViewport& v, double threshold) {
  if (a.width != b.width || a.height != b.height || a.channels != b.channels)
    throw std::runtime_error("the screenshots differ in size");
  cv::Mat out(v.h, v.w, CV_8UC1, cv::Scalar(0));
  for (int y = 0; y < v.h && v.y0 + y < a.height; ++y)
    for (int x = 0; x < v.w && v.x0 + x < a.width; ++x) {
      double d = 0;
      for (int c = 0; c < std::min(3, a.channels); ++c) {
        const size_t i = (size_t(v.y0 + y) * a.width + (v.x0 + x)) * a.channels + c;
        d += std::abs(double(a.pixels[i]) - double(b.pixels[i]));
      }
      out.at<uint8_t>(y, x) = d > threshold ? 255 : 0;
    }
  return out;
}

int region(const std::string& before_png, const std::string& after_png, double x0, double y0, double x1, double y1) {
  const MainViewport v = main_viewport(after_png);
  const cv::Mat t = changed_pixels(goris::read_image(before_png), goris::read_image(after_png), v, 0.08);
  constexpr double kMargin = 0.08;
  long tinted = 0, inside = 0, rect_px = 0, rect_tinted = 0;
  for (int y = 0; y < t.rows; ++y)
    for (int x = 0; x < t.cols; ++x) {
      const double fx = (x + 0.5) / v.w, fy = (y + 0.5) / v.h;
      const bool on = t.at<uint8_t>(y, x) > 0;
      const bool in_rect = fx >= x0 && fx <= x1 && fy >= y0 && fy <= y1;
      const bool near = fx >= x0 - kMargin && fx <= x1 + kMargin && fy >= y0 - kMargin && fy <= y1 + kMargin;
      tinted += on;
      inside += on && near;
      rect_px += in_rect;
      rect_tinted += on && in_rect;
    }
  const double inside_fraction = tinted ? double(inside) / double(tinted) : 0.0;
  const double coverage = rect_px ? double(rect_tinted) / double(rect_px) : 0.0;
  std::printf("tinted %ld pixels, %.1f%% inside the region (widened by %.0f%%); %.1f%% of the region tinted\n", tinted,
              100.0 * inside_fraction, 100.0 * kMargin, 100.0 * coverage);
  if (tinted < 30) return fail("almost nothing is tinted: the selection is not shown");
  if (inside_fraction < 0.8) return fail("the tint lies mostly outside the region");
  if (coverage < 0.02) return fail("the tint covers next to nothing of the region");
  return 0;
}

int same(const std::string& a_png, const std::string& b_png) {
  const MainViewport v = main_viewport(b_png);
  const cv::Mat t = changed_pixels(goris::read_image(a_png), goris::read_image(b_png), v, 0.03);
  const long changed = cv::countNonZero(t);
  std::printf("%ld of %d main-viewport pixels differ\n", changed, v.w * v.h);
  if (changed > long(0.001 * v.w * v.h)) return fail("the main viewports differ");
  return 0;
}

int iou(const std::string& dir, const std::string& dataset, double min_mean) {
  namespace fs = std::filesystem;
  // The written masks' size decides the size the data set's masks are loaded at.
  int width = 0;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().rfind("mask_", 0) == 0 && e.path().extension() == ".png") {
      width = goris::read_mask_png(e.path()).width;
      break;
    }
  if (width == 0) return fail(dir + ": no mask_XXX.png");
  goris::DatasetOptions o;
  o.target_width = width;
  const goris::Dataset ds = goris::load_dataset(dataset, o);
  double sum = 0, worst = 1;
  int n = 0;
  for (const goris::View& v : ds.train) {
    if (!v.object_mask) continue;
    const std::string name = v.name.rfind("r_", 0) == 0 ? "mask_" + v.name.substr(2) + ".png" : v.name + ".png";
    const fs::path file = fs::path(dir) / name;
    if (!fs::exists(file)) return fail(file.string() + " is missing");
    const goris::Mask written = goris::read_mask_png(file);
    const goris::Image exact = goris::load_view_object_mask(v);
    if (written.width != exact.width || written.height != exact.height)
      return fail(file.string() + ": " + std::to_string(written.width) + "x" + std::to_string(written.height) +
                  ", the data set's mask is " + std::to_string(exact.width) + "x" + std::to_string(exact.height));
    long inter = 0, uni = 0;
    for (int y = 0; y < exact.height; ++y)
      for (int x = 0; x < exact.width; ++x) {
        const bool a = written(x, y), b = exact.pixels[size_t(y) * exact.width + x] > 0.5f;
        inter += a && b;
        uni += a || b;
      }
    const double j = uni == 0 ? 1.0 : double(inter) / double(uni);
    std::printf("%s %.3f\n", v.name.c_str(), j);
    sum += j;
    worst = std::min(worst, j);
    ++n;
  }
  if (n == 0) return fail(dataset + ": no training view has an object mask");
  const double mean = sum / n;
  std::printf("masks IoU against the data set's masks: mean %.4f, min %.4f over %d views\n", mean, worst, n);
  if (mean < min_mean) return fail("the mean IoU " + std::to_string(mean) + " is below " + std::to_string(min_mean));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  try {
    if (mode == "target" && argc == 3) return target(argv[2]);
    if (mode == "tint" && argc == 5) return tint(argv[2], argv[3], argv[4]);
    if (mode == "bbox" && argc == 3) return bbox(argv[2]);
    if (mode == "region" && argc == 8)
      return region(argv[2], argv[3], percent(argv[4]), percent(argv[5]), percent(argv[6]), percent(argv[7]));
    if (mode == "same" && argc == 4) return same(argv[2], argv[3]);
    if (mode == "iou" && argc == 5) return iou(argv[2], argv[3], std::stod(argv[4]));
    if (mode == "slider" && argc == 5) return slider(argv[2], argv[3], argv[4]);
    if (mode == "removed" && argc == 6) return removed(argv[2], argv[3], argv[4], argv[5]);
  } catch (const std::exception& e) {
    return fail(e.what());
  }
  return fail("usage: gui_selection_check target DATASET | tint BEFORE.png AFTER.png MASK.png | removed WITH.png "
              "CLEANED.png RESTORED.png MASK.png | slider WITH.png CLEANED.png SLIDER.png | bbox MASK.png | region "
              "BEFORE.png AFTER.png X0% Y0% X1% Y1% | same A.png B.png | iou DIR DATASET MIN_MEAN");
}
