// The benchmark chart pieces (tools/report): Pareto front, axis ticks, the SVG text and the drawn image.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include <opencv2/core.hpp>

#include "core/util/error.h"
#include "tools/report/axis_ticks.h"
#include "tools/report/chart.h"
#include "tools/report/pareto.h"
#include "tools/report/svg_writer.h"

namespace goris {
namespace {

using Idx = std::vector<std::size_t>;

TEST(Pareto, KeepsOnlyPointsNothingBeatsOnBothAxes) {
  // (time, psnr): 1 is dominated by 0 (slower, worse); 3 by 2 (slower, same psnr).
  const std::vector<TimeQuality> p = {{10, 25}, {20, 24}, {30, 28}, {40, 28}, {5, 20}, {100, 31}};
  EXPECT_EQ(pareto_front(p), (Idx{4, 0, 2, 5}));
}

TEST(Pareto, SinglePointAndEmpty) {
  EXPECT_EQ(pareto_front({{3, 20}}), (Idx{0}));
  EXPECT_TRUE(pareto_front({}).empty());
}

TEST(Pareto, TiesKeepTheFirstAndTheBestAtEqualTime) {
  EXPECT_EQ(pareto_front({{5, 20}, {5, 20}}), (Idx{0}));       // identical: one marker
  EXPECT_EQ(pareto_front({{5, 20}, {5, 22}, {5, 21}}), (Idx{1}));  // same time: the best only
  EXPECT_EQ(pareto_front({{1, 30}, {2, 30}, {3, 29}}), (Idx{0}));  // fastest of the best dominates the rest
}

TEST(Pareto, IgnoresNonFinitePoints) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(pareto_front({{1, nan}, {2, 20}, {inf, 40}, {3, 25}}), (Idx{1, 3}));
}

TEST(AxisTicks, LogRangeWidensToDecades) {
  const AxisRange r = log_axis_range(3.2, 450);
  EXPECT_DOUBLE_EQ(r.lo, 1);
  EXPECT_DOUBLE_EQ(r.hi, 1000);
  const AxisRange one = log_axis_range(10, 10);  // a single value still gets a decade
  EXPECT_DOUBLE_EQ(one.lo, 10);
  EXPECT_DOUBLE_EQ(one.hi, 100);
}

TEST(AxisTicks, LogTicksAreNiceAndInsideTheRange) {
  // Three decades or more: powers of ten only.
  const std::vector<double> coarse = log_ticks({0.1, 1000});
  ASSERT_EQ(coarse.size(), 5u);
  EXPECT_DOUBLE_EQ(coarse.front(), 0.1);
  EXPECT_DOUBLE_EQ(coarse.back(), 1000);
  // Fewer decades: 1, 2, 5 steps.
  const std::vector<double> fine = log_ticks({10, 100});
  ASSERT_EQ(fine.size(), 4u);
  EXPECT_DOUBLE_EQ(fine[0], 10);
  EXPECT_DOUBLE_EQ(fine[1], 20);
  EXPECT_DOUBLE_EQ(fine[2], 50);
  EXPECT_DOUBLE_EQ(fine[3], 100);
  for (std::size_t i = 1; i < fine.size(); ++i) EXPECT_GT(fine[i], fine[i - 1]);
}

TEST(AxisTicks, LinearTicksCoverTheData) {
  const AxisRange r = linear_axis_range(23.4, 31.7);
  EXPECT_LE(r.lo, 23.4);
  EXPECT_GE(r.hi, 31.7);
  const std::vector<double> t = linear_ticks(r);
  ASSERT_GE(t.size(), 3u);
  ASSERT_LE(t.size(), 12u);
  const double step = t[1] - t[0];
  for (std::size_t i = 1; i < t.size(); ++i) EXPECT_NEAR(t[i] - t[i - 1], step, 1e-9);
  EXPECT_NEAR(t.front(), r.lo, 1e-9);
  EXPECT_NEAR(t.back(), r.hi, 1e-9);
}

TEST(AxisTicks, BadRangesAreErrors) {
  EXPECT_THROW(log_axis_range(0, 10), Error);
  EXPECT_THROW(log_axis_range(5, 1), Error);
  EXPECT_THROW(linear_axis_range(std::nan(""), 1), Error);
  EXPECT_EQ(tick_label(0.5), "0.5");
  EXPECT_EQ(tick_label(20), "20");
  EXPECT_EQ(tick_label(1000), "1000");
}

Chart sample_chart() {
  Chart c;
  c.title = "PSNR <vs> time & more";
  c.x_label = "time (s)";
  c.y_label = "PSNR (dB)";
  c.markers = {{2, 24, palette_color(0), MarkerShape::Circle, "a"},
               {20, 27, palette_color(1), MarkerShape::Square, "b"},
               {200, 29, palette_color(2), MarkerShape::Triangle, "c"},
               {50, 26, palette_color(3), MarkerShape::Diamond, "d"}};
  c.step_line = {{2, 24}, {20, 27}, {200, 29}};
  c.legend = {{"baseline", palette_color(0)}, {"Pareto front", c.step_color, MarkerShape::Circle, true}};
  return c;
}

std::size_t count(const std::string& s, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}

TEST(ChartSvg, IsWellFormedWithTheExpectedElements) {
  const std::string svg = chart_svg(sample_chart());
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_NE(svg.find("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"860\" height=\"520\""), std::string::npos);
  EXPECT_EQ(svg.substr(svg.size() - 7), "</svg>\n");
  EXPECT_EQ(count(svg, "<svg"), 1u);
  // One circle for the circle marker plus one legend circle; the other shapes are polygons.
  EXPECT_EQ(count(svg, "<circle"), 2u);
  EXPECT_EQ(count(svg, "<polygon"), 3u);
  EXPECT_EQ(count(svg, "<circle"), count(svg, "</circle>"));
  EXPECT_EQ(count(svg, "<text"), count(svg, "</text>"));
  EXPECT_GE(count(svg, "<polyline"), 2u);  // frame + step line
  // The title is escaped; the y label is rotated; the log axis has the 1, 10, 100, 1000 ticks.
  EXPECT_NE(svg.find("PSNR &lt;vs&gt; time &amp; more"), std::string::npos);
  EXPECT_EQ(svg.find("<vs>"), std::string::npos);
  EXPECT_NE(svg.find("rotate(-90"), std::string::npos);
  for (const char* t : {">1</text>", ">10</text>", ">100</text>", ">1000</text>"})
    EXPECT_NE(svg.find(t), std::string::npos) << t;
  EXPECT_NE(svg.find("<title>b</title>"), std::string::npos);
}

TEST(ChartSvg, StepLineIsAStaircase) {
  Chart c = sample_chart();
  c.legend.clear();
  const std::string svg = chart_svg(c);
  // The front's polyline: 3 points, 2 corners between them, 1 extension to the right edge.
  const std::size_t at = svg.rfind("<polyline points=\"");
  ASSERT_NE(at, std::string::npos);
  const std::string pts = svg.substr(at + 18, svg.find('"', at + 18) - at - 18);
  EXPECT_EQ(count(pts, ",") , 6u);
}

TEST(ChartImage, DrawsANonBlankImageOfTheRequestedSize) {
  const cv::Mat img = chart_image(sample_chart());
  ASSERT_EQ(img.type(), CV_8UC3);
  EXPECT_EQ(img.cols, 860);
  EXPECT_EQ(img.rows, 520);
  cv::Mat gray;
  cv::extractChannel(img, gray, 1);
  const int ink = cv::countNonZero(gray < 200);
  EXPECT_GT(ink, 2000);                   // axes, ticks, text, markers
  EXPECT_LT(ink, img.rows * img.cols / 2);  // still mostly background
  // The marker colours appear (palette colour 1, orange: B=0, G=159, R=230).
  cv::Mat orange;
  cv::inRange(img, cv::Scalar(0, 150, 220), cv::Scalar(20, 170, 240), orange);
  EXPECT_GT(cv::countNonZero(orange), 20);
}

TEST(Chart, RejectsChartsItCannotDraw) {
  Chart empty;
  EXPECT_THROW(chart_svg(empty), Error);
  Chart bad = sample_chart();
  bad.markers[0].x = 0;  // log axis
  EXPECT_THROW(chart_image(bad), Error);
  bad.log_x = false;
  EXPECT_NO_THROW(chart_image(bad));
}

}  // namespace
}  // namespace goris
