#pragma once
// A minimal SVG document builder: escaped text, numbers with two decimals, elements appended in order.
#include <string>
#include <vector>

#include "tools/report/chart.h"

namespace goris {

class SvgWriter {
 public:
  SvgWriter(int width, int height);
  void rect(double x, double y, double w, double h, Rgb fill, Rgb stroke, double stroke_width);
  void line(double x0, double y0, double x1, double y1, Rgb color, double width);
  void polyline(const std::vector<cv::Point2d>& pts, Rgb color, double width);
  void circle(double cx, double cy, double r, Rgb fill, const std::string& title);
  void polygon(const std::vector<cv::Point2d>& pts, Rgb fill, const std::string& title);
  // anchor: "start" | "middle" | "end"; vertical: rotated 90 degrees counter-clockwise about (x, y).
  void text(double x, double y, const std::string& s, double size, const char* anchor, Rgb color, bool vertical = false);
  std::string finish() const;  // the whole document

 private:
  std::string body_;
  int width_, height_;
};

std::string svg_escape(const std::string& s);

}  // namespace goris
