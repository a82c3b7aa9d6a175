#include "tools/report/chart.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "core/util/error.h"
#include "tools/report/axis_ticks.h"
#include "tools/report/svg_writer.h"

namespace goris {
namespace {

enum class Anchor { Start, Middle, End };

// The drawing operations the layout needs; one implementation writes SVG, the other draws into a cv::Mat.
class Canvas {
 public:
  virtual ~Canvas() = default;
  virtual void rect(double x, double y, double w, double h, Rgb fill, Rgb stroke) = 0;
  virtual void line(cv::Point2d a, cv::Point2d b, Rgb c, double width) = 0;
  virtual void polyline(const std::vector<cv::Point2d>& pts, Rgb c, double width) = 0;
  virtual void marker(cv::Point2d p, MarkerShape s, double r, Rgb fill, const std::string& title) = 0;
  virtual void text(cv::Point2d p, const std::string& s, double size, Anchor a, Rgb c, bool vertical = false) = 0;
};

std::vector<cv::Point2d> shape_points(cv::Point2d p, MarkerShape s, double r) {
  switch (s) {
    case MarkerShape::Square: return {{p.x - r, p.y - r}, {p.x + r, p.y - r}, {p.x + r, p.y + r}, {p.x - r, p.y + r}};
    case MarkerShape::Triangle: return {{p.x, p.y - 1.2 * r}, {p.x + 1.1 * r, p.y + 0.8 * r}, {p.x - 1.1 * r, p.y + 0.8 * r}};
    case MarkerShape::Diamond: return {{p.x, p.y - 1.3 * r}, {p.x + 1.3 * r, p.y}, {p.x, p.y + 1.3 * r}, {p.x - 1.3 * r, p.y}};
    case MarkerShape::Circle: break;
  }
  return {};
}

class SvgCanvas : public Canvas {
 public:
  SvgCanvas(int w, int h) : svg(w, h) {}
  void rect(double x, double y, double w, double h, Rgb fill, Rgb stroke) override { svg.rect(x, y, w, h, fill, stroke, 1); }
  void line(cv::Point2d a, cv::Point2d b, Rgb c, double width) override { svg.line(a.x, a.y, b.x, b.y, c, width); }
  void polyline(const std::vector<cv::Point2d>& pts, Rgb c, double width) override { svg.polyline(pts, c, width); }
  void marker(cv::Point2d p, MarkerShape s, double r, Rgb fill, const std::string& title) override {
    if (s == MarkerShape::Circle) svg.circle(p.x, p.y, r, fill, title);
    else svg.polygon(shape_points(p, s, r), fill, title);
  }
  void text(cv::Point2d p, const std::string& s, double size, Anchor a, Rgb c, bool vertical) override {
    svg.text(p.x, p.y, s, size, a == Anchor::Start ? "start" : a == Anchor::Middle ? "middle" : "end", c, vertical);
  }
  SvgWriter svg;
};

class MatCanvas : public Canvas {
 public:
  MatCanvas(int w, int h) : img(h, w, CV_8UC3, cv::Scalar(255, 255, 255)) {}
  static cv::Scalar bgr(Rgb c) { return {double(c.b), double(c.g), double(c.r)}; }
  static cv::Point px(cv::Point2d p) { return {int(std::lround(p.x)), int(std::lround(p.y))}; }
  void rect(double x, double y, double w, double h, Rgb fill, Rgb stroke) override {
    const cv::Rect r(int(std::lround(x)), int(std::lround(y)), int(std::lround(w)), int(std::lround(h)));
    cv::rectangle(img, r, bgr(fill), cv::FILLED);
    cv::rectangle(img, r, bgr(stroke), 1);
  }
  void line(cv::Point2d a, cv::Point2d b, Rgb c, double width) override {
    cv::line(img, px(a), px(b), bgr(c), std::max(1, int(std::lround(width))), cv::LINE_AA);
  }
  void polyline(const std::vector<cv::Point2d>& pts, Rgb c, double width) override {
    for (size_t i = 1; i < pts.size(); ++i) line(pts[i - 1], pts[i], c, width);
  }
  void marker(cv::Point2d p, MarkerShape s, double r, Rgb fill, const std::string&) override {
    if (s == MarkerShape::Circle) {
      cv::circle(img, px(p), int(std::lround(r)), bgr(fill), cv::FILLED, cv::LINE_AA);
      cv::circle(img, px(p), int(std::lround(r)), cv::Scalar(32, 32, 32), 1, cv::LINE_AA);
      return;
    }
    std::vector<cv::Point> poly;
    for (const auto& q : shape_points(p, s, r)) poly.push_back(px(q));
    cv::fillConvexPoly(img, poly, bgr(fill), cv::LINE_AA);
    cv::polylines(img, poly, true, cv::Scalar(32, 32, 32), 1, cv::LINE_AA);
  }
  void text(cv::Point2d p, const std::string& s, double size, Anchor a, Rgb c, bool vertical) override {
    const double scale = size / 30.0;  // Hershey simplex: ~30 px per unit of scale incl. ascent
    int base = 0;
    const cv::Size ts = cv::getTextSize(s, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &base);
    const int shift = a == Anchor::Start ? 0 : a == Anchor::Middle ? ts.width / 2 : ts.width;
    if (!vertical) {
      cv::putText(img, s, {px(p).x - shift, px(p).y}, cv::FONT_HERSHEY_SIMPLEX, scale, bgr(c), 1, cv::LINE_AA);
      return;
    }
    // Draw horizontally on a white strip, rotate it and copy the inked pixels.
    cv::Mat strip(ts.height + base + 2, ts.width + 2, CV_8UC3, cv::Scalar(255, 255, 255));
    cv::putText(strip, s, {1, ts.height + 1}, cv::FONT_HERSHEY_SIMPLEX, scale, bgr(c), 1, cv::LINE_AA);
    cv::rotate(strip, strip, cv::ROTATE_90_COUNTERCLOCKWISE);
    // (x, y) is the baseline start before rotation: the rotated strip's bottom edge sits at y + shift.
    cv::Rect dst(px(p).x - ts.height - 1, px(p).y + shift - strip.rows, strip.cols, strip.rows);
    dst &= cv::Rect(0, 0, img.cols, img.rows);
    if (dst.empty()) return;
    cv::Mat src = strip(cv::Rect(dst.x - (px(p).x - ts.height - 1), dst.y - (px(p).y + shift - strip.rows), dst.width, dst.height));
    cv::Mat gray, mask;
    cv::cvtColor(src, gray, cv::COLOR_BGR2GRAY);
    cv::threshold(gray, mask, 250, 255, cv::THRESH_BINARY_INV);
    src.copyTo(img(dst), mask);
  }
  cv::Mat img;
};

void check_chart(const Chart& c) {
  if (c.markers.empty()) throw Error("chart '" + c.title + "'", "no points to draw");
  if (c.width < 200 || c.height < 150) throw Error("chart '" + c.title + "'", "size below 200 x 150 pixels");
  for (const auto& m : c.markers) {
    if (!std::isfinite(m.x) || !std::isfinite(m.y)) throw Error("chart '" + c.title + "'", "a point is not finite");
    if (c.log_x && m.x <= 0) throw Error("chart '" + c.title + "'", "log x axis needs positive x, got " + tick_label(m.x));
  }
}

void draw(const Chart& c, Canvas& canvas) {
  check_chart(c);
  const Rgb black{20, 20, 20}, grid{225, 225, 225}, frame{120, 120, 120};
  double xmin = c.markers[0].x, xmax = xmin, ymin = c.markers[0].y, ymax = ymin;
  for (const auto& m : c.markers) {
    xmin = std::min(xmin, m.x), xmax = std::max(xmax, m.x);
    ymin = std::min(ymin, m.y), ymax = std::max(ymax, m.y);
  }
  AxisRange xr;
  std::vector<double> xt;
  if (c.log_x) {
    xr = log_axis_range(xmin, xmax);
    xt = log_ticks(xr);
  } else {
    xr = linear_axis_range(xmin, xmax);
    xt = linear_ticks(xr);
  }
  const AxisRange yr = linear_axis_range(ymin, ymax);
  const std::vector<double> yt = linear_ticks(yr);

  const double legend_w = c.legend.empty() ? 20 : 190;
  const double left = 70, top = c.title.empty() ? 20 : 44, right = c.width - legend_w, bottom = c.height - 56;
  auto fx = [&](double x) {
    const double t = c.log_x ? (std::log10(x) - std::log10(xr.lo)) / (std::log10(xr.hi) - std::log10(xr.lo))
                             : (x - xr.lo) / (xr.hi - xr.lo);
    return left + t * (right - left);
  };
  auto fy = [&](double y) { return bottom - (y - yr.lo) / (yr.hi - yr.lo) * (bottom - top); };

  canvas.rect(0, 0, c.width, c.height, {255, 255, 255}, {255, 255, 255});
  if (!c.title.empty()) canvas.text({c.width / 2.0, 26}, c.title, 16, Anchor::Middle, black);
  for (double v : xt) {
    canvas.line({fx(v), top}, {fx(v), bottom}, grid, 1);
    canvas.line({fx(v), bottom}, {fx(v), bottom + 5}, frame, 1);
    canvas.text({fx(v), bottom + 20}, tick_label(v), 12, Anchor::Middle, black);
  }
  for (double v : yt) {
    canvas.line({left, fy(v)}, {right, fy(v)}, grid, 1);
    canvas.line({left - 5, fy(v)}, {left, fy(v)}, frame, 1);
    canvas.text({left - 8, fy(v) + 4}, tick_label(v), 12, Anchor::End, black);
  }
  canvas.polyline({{left, top}, {right, top}, {right, bottom}, {left, bottom}, {left, top}}, frame, 1);
  canvas.text({(left + right) / 2, bottom + 44}, c.x_label, 14, Anchor::Middle, black);
  canvas.text({20, (top + bottom) / 2}, c.y_label, 14, Anchor::Middle, black, true);

  if (!c.step_line.empty()) {
    std::vector<cv::Point2d> pts;
    for (size_t i = 0; i < c.step_line.size(); ++i) {
      const cv::Point2d p{fx(c.step_line[i].x), fy(c.step_line[i].y)};
      if (i > 0) pts.push_back({p.x, pts.back().y});  // flat to the next point's time, then up
      pts.push_back(p);
    }
    pts.push_back({right, pts.back().y});
    canvas.polyline(pts, c.step_color, 2);
  }
  for (const auto& m : c.markers) canvas.marker({fx(m.x), fy(m.y)}, m.shape, 6, m.color, m.tooltip);

  double ly = top + 10;
  for (const auto& e : c.legend) {
    const double lx = right + 18;
    if (e.line) canvas.line({lx - 8, ly}, {lx + 8, ly}, e.color, 2);
    else canvas.marker({lx, ly}, e.shape, 5, e.color, "");
    canvas.text({lx + 14, ly + 4}, e.text, 12, Anchor::Start, black);
    ly += 20;
  }
}

}  // namespace

std::string chart_svg(const Chart& chart) {
  SvgCanvas canvas(chart.width, chart.height);
  draw(chart, canvas);
  return canvas.svg.finish();
}

cv::Mat chart_image(const Chart& chart) {
  MatCanvas canvas(chart.width, chart.height);
  draw(chart, canvas);
  return canvas.img;
}

Rgb palette_color(std::size_t index) {
  static const Rgb colors[] = {{0, 114, 178}, {230, 159, 0}, {0, 158, 115}, {204, 121, 167},
                               {213, 94, 0},  {86, 180, 233}, {240, 228, 66}, {0, 0, 0},
                               {148, 103, 189}, {140, 86, 75}, {23, 190, 207}, {188, 189, 34}};
  return colors[index % (sizeof colors / sizeof colors[0])];
}

MarkerShape marker_shape(std::size_t index) {
  static const MarkerShape shapes[] = {MarkerShape::Circle, MarkerShape::Square, MarkerShape::Triangle, MarkerShape::Diamond};
  return shapes[index % 4];
}

}  // namespace goris
