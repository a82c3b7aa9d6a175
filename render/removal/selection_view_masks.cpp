#include "render/removal/selection_view_masks.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "core/scene/gaussians.h"
#include "core/util/error.h"
#include "render/raster/rasterizer.h"
#include "render/removal/select_view.h"

namespace goris {

RasterOutput render_selection_channel(const GaussianModel& model, const SelectionMask& mask, const Camera& camera,
                                      const RasterSettings& raster) {
  const std::size_t n = model.count();
  if (mask.size() != n)
    throw Error("selection", "mask has " + std::to_string(mask.size()) + " entries for " + std::to_string(n) +
                                 " Gaussians");
  std::vector<float> sel(n);
  for (std::size_t i = 0; i < n; ++i) sel[i] = mask[i] ? 1.0f : 0.0f;
  const Buffer<float> sel_buf(sel, model.device());
  GaussianView view = plain_gaussian_view(model);
  view.extras = sel_buf.data();
  view.n_extras = 1;
  return rasterize(view, camera, raster, model.device());
}

Mask selection_view_mask(const GaussianModel& model, const SelectionMask& mask, const Camera& camera,
                         const RasterSettings& raster, const ViewMaskSettings& s, const Image* photo) {
  if (!(s.threshold > 0.0f && s.threshold < 1.0f)) throw Error("masks", "the coverage threshold must lie in (0, 1)");
  const std::vector<float> cov = render_selection_channel(model, mask, camera, raster).gbuffer.extras.to_host();
  Mask m(camera.width, camera.height);
  for (std::size_t p = 0; p < m.data.size(); ++p) m.data[p] = cov[p] > s.threshold ? 255 : 0;
  m = open_mask(close_mask(m, s.close_radius), s.open_radius);
  return photo ? refine_mask_with_photo(m, cov, *photo, s) : m;
}

Mask refine_mask_with_photo(const Mask& coarse, const std::vector<float>& coverage, const Image& photo,
                            const ViewMaskSettings& s) {
  const int w = coarse.width, h = coarse.height;
  if (photo.width != w || photo.height != h || photo.channels != 3 || photo.pixels.device() != Device::CPU)
    throw Error("masks", "the photo to refine a " + std::to_string(w) + "x" + std::to_string(h) + " mask with is " +
                             std::to_string(photo.width) + "x" + std::to_string(photo.height) + "x" +
                             std::to_string(photo.channels) + " (an RGB CPU image of the mask's size is needed)");
  if (coverage.size() != coarse.pixel_count()) throw Error("masks", "coverage and mask sizes differ");
  if (s.grabcut_iterations < 1 || !(s.band_fraction > 0.0f) || s.core_radius < 0) throw Error("masks", "bad photo refinement settings");
  if (count_set(coarse) == 0) return coarse;
  const int band = std::max(2, int(std::lround(s.band_fraction * float(std::max(w, h)))));
  const Mask outer = dilate_mask(coarse, band);
  // Erosion as the complement's dilation (pixels outside the image count as set, as in open_mask).
  Mask complement(w, h);
  for (std::size_t p = 0; p < complement.data.size(); ++p) complement.data[p] = coarse.data[p] ? 0 : 255;
  const Mask outside_core = dilate_mask(complement, s.core_radius);
  cv::Mat labels(h, w, CV_8UC1);
  std::size_t unknown_fg = 0, unknown_bg = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t p = std::size_t(y) * std::size_t(w) + std::size_t(x);
      std::uint8_t l = cv::GC_BGD;
      if (!outside_core.data[p] && coverage[p] > s.core_coverage) l = cv::GC_FGD;
      else if (coarse.data[p]) l = cv::GC_PR_FGD, ++unknown_fg;
      else if (outer.data[p]) l = cv::GC_PR_BGD, ++unknown_bg;
      labels.at<std::uint8_t>(y, x) = l;
    }
  // GrabCut needs samples of both classes for its colour models.
  if (unknown_bg == 0 || unknown_fg == 0) return coarse;
  cv::Mat bgr(h, w, CV_8UC3);
  const float* px = photo.pixels.data();
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float* c = px + 3 * (std::size_t(y) * std::size_t(w) + std::size_t(x));
      auto to8 = [](float v) { return std::uint8_t(std::clamp(std::lround(v * 255.0f), 0L, 255L)); };
      bgr.at<cv::Vec3b>(y, x) = cv::Vec3b(to8(c[2]), to8(c[1]), to8(c[0]));
    }
  cv::Mat bg_model, fg_model;
  cv::grabCut(bgr, labels, cv::Rect(), bg_model, fg_model, s.grabcut_iterations, cv::GC_INIT_WITH_MASK);
  Mask out(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::uint8_t l = labels.at<std::uint8_t>(y, x);
      out.set(x, y, l == cv::GC_FGD || l == cv::GC_PR_FGD);
    }
  return open_mask(close_mask(out, s.close_radius), s.open_radius);
}

std::string object_mask_file_name(const std::string& name) {
  return name.rfind("r_", 0) == 0 ? "mask_" + name.substr(2) + ".png" : name + ".png";
}

double mask_iou(const Mask& a, const Mask& b) {
  if (a.width != b.width || a.height != b.height)
    throw Error("masks", "IoU of masks of different sizes (" + std::to_string(a.width) + "x" + std::to_string(a.height) +
                             " and " + std::to_string(b.width) + "x" + std::to_string(b.height) + ")");
  std::size_t inter = 0, uni = 0;
  for (std::size_t p = 0; p < a.data.size(); ++p) {
    const bool x = a.data[p] != 0, y = b.data[p] != 0;
    inter += x && y;
    uni += x || y;
  }
  return uni ? double(inter) / double(uni) : 1.0;
}

}  // namespace goris
