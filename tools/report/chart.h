#pragma once
// A small scatter chart with an optional step line (a Pareto front), described once and drawn both as SVG
// text and as a BGR image (OpenCV), so the project writes its own benchmark charts without a plotting
// runtime. The x axis may be logarithmic; both axes get nice ticks, labels and a light grid; a legend sits
// to the right of the plot.
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace goris {

struct Rgb {
  unsigned char r = 0, g = 0, b = 0;
};

enum class MarkerShape { Circle, Square, Triangle, Diamond };

struct ChartMarker {
  double x = 0, y = 0;
  Rgb color;
  MarkerShape shape = MarkerShape::Circle;
  std::string tooltip;  // SVG <title>: shown on hover
};

struct ChartLegendEntry {
  std::string text;
  Rgb color;
  MarkerShape shape = MarkerShape::Circle;
  bool line = false;  // a line sample instead of a marker
};

struct Chart {
  std::string title, x_label, y_label;
  bool log_x = true;
  int width = 860, height = 520;
  std::vector<ChartMarker> markers;
  // Points of the step line in increasing x; drawn as a staircase (flat to the next x, then up) that
  // continues flat to the right edge.
  std::vector<cv::Point2d> step_line;
  Rgb step_color{90, 90, 90};
  std::vector<ChartLegendEntry> legend;
};

// Throws goris::Error when the chart has no markers, a marker is not finite, or (log_x) an x is <= 0.
std::string chart_svg(const Chart& chart);
cv::Mat chart_image(const Chart& chart);  // CV_8UC3, chart.height x chart.width

// A qualitative palette (colour-blind friendly order), cycled by index.
Rgb palette_color(std::size_t index);
MarkerShape marker_shape(std::size_t index);

}  // namespace goris
