#include "tools/report/svg_writer.h"

#include <cstdio>

namespace goris {
namespace {

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.2f", v);
  return b;
}

std::string color(Rgb c) {
  char b[8];
  std::snprintf(b, sizeof b, "#%02x%02x%02x", c.r, c.g, c.b);
  return b;
}

std::string points(const std::vector<cv::Point2d>& pts) {
  std::string s;
  for (const auto& p : pts) s += (s.empty() ? "" : " ") + num(p.x) + "," + num(p.y);
  return s;
}

std::string title_element(const std::string& title) {
  return title.empty() ? "" : "<title>" + svg_escape(title) + "</title>";
}

}  // namespace

std::string svg_escape(const std::string& s) {
  std::string out;
  for (char c : s) switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  return out;
}

SvgWriter::SvgWriter(int width, int height) : width_(width), height_(height) {}

void SvgWriter::rect(double x, double y, double w, double h, Rgb fill, Rgb stroke, double stroke_width) {
  body_ += "<rect x=\"" + num(x) + "\" y=\"" + num(y) + "\" width=\"" + num(w) + "\" height=\"" + num(h) +
           "\" fill=\"" + color(fill) + "\" stroke=\"" + color(stroke) + "\" stroke-width=\"" + num(stroke_width) +
           "\"/>\n";
}

void SvgWriter::line(double x0, double y0, double x1, double y1, Rgb c, double width) {
  body_ += "<line x1=\"" + num(x0) + "\" y1=\"" + num(y0) + "\" x2=\"" + num(x1) + "\" y2=\"" + num(y1) +
           "\" stroke=\"" + color(c) + "\" stroke-width=\"" + num(width) + "\"/>\n";
}

void SvgWriter::polyline(const std::vector<cv::Point2d>& pts, Rgb c, double width) {
  body_ += "<polyline points=\"" + points(pts) + "\" fill=\"none\" stroke=\"" + color(c) + "\" stroke-width=\"" +
           num(width) + "\"/>\n";
}

void SvgWriter::circle(double cx, double cy, double r, Rgb fill, const std::string& title) {
  body_ += "<circle cx=\"" + num(cx) + "\" cy=\"" + num(cy) + "\" r=\"" + num(r) + "\" fill=\"" + color(fill) +
           "\" stroke=\"#202020\" stroke-width=\"0.8\">" + title_element(title) + "</circle>\n";
}

void SvgWriter::polygon(const std::vector<cv::Point2d>& pts, Rgb fill, const std::string& title) {
  body_ += "<polygon points=\"" + points(pts) + "\" fill=\"" + color(fill) +
           "\" stroke=\"#202020\" stroke-width=\"0.8\">" + title_element(title) + "</polygon>\n";
}

void SvgWriter::text(double x, double y, const std::string& s, double size, const char* anchor, Rgb c, bool vertical) {
  body_ += "<text x=\"" + num(x) + "\" y=\"" + num(y) + "\" font-size=\"" + num(size) + "\" text-anchor=\"" + anchor +
           "\" fill=\"" + color(c) + "\"" +
           (vertical ? " transform=\"rotate(-90 " + num(x) + " " + num(y) + ")\"" : std::string()) + ">" +
           svg_escape(s) + "</text>\n";
}

std::string SvgWriter::finish() const {
  const std::string w = std::to_string(width_), h = std::to_string(height_);
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + w +
         "\" height=\"" + h + "\" viewBox=\"0 0 " + w + " " + h + "\" font-family=\"DejaVu Sans, Arial, sans-serif\">\n" +
         body_ + "</svg>\n";
}

}  // namespace goris
