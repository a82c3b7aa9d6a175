// LDR-FLIP after "FLIP: A Difference Evaluator for Alternating Images" (HPG 2020); see flip.h.
#include "core/metrics/flip.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace goris {
namespace {

using Kernel = std::vector<float>;  // 2r + 1 taps, tap i weighs the sample at offset i - r
using Mat3 = std::array<std::array<double, 3>, 3>;

constexpr double kPi = std::numbers::pi;

// --- colour spaces ---------------------------------------------------------------------------------

// Linear sRGB (D65) to CIE XYZ; the white point is its image of RGB (1, 1, 1).
constexpr Mat3 kRgbToXyz = {{{0.4124564, 0.3575761, 0.1804375},
                             {0.2126729, 0.7151522, 0.0721750},
                             {0.0193339, 0.1191920, 0.9503041}}};

Mat3 inverse(const Mat3& m) {
  const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                     m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  Mat3 r{};
  r[0][0] = (m[1][1] * m[2][2] - m[1][2] * m[2][1]) / det;
  r[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) / det;
  r[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / det;
  r[1][0] = (m[1][2] * m[2][0] - m[1][0] * m[2][2]) / det;
  r[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det;
  r[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / det;
  r[2][0] = (m[1][0] * m[2][1] - m[1][1] * m[2][0]) / det;
  r[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / det;
  r[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / det;
  return r;
}

const Mat3& xyz_to_rgb() {
  static const Mat3 m = inverse(kRgbToXyz);
  return m;
}

std::array<double, 3> mul(const Mat3& m, double a, double b, double c) {
  return {m[0][0] * a + m[0][1] * b + m[0][2] * c, m[1][0] * a + m[1][1] * b + m[1][2] * c,
          m[2][0] * a + m[2][1] * b + m[2][2] * c};
}

// D65 reference white (the XYZ of linear RGB white).
const std::array<double, 3>& white() {
  static const std::array<double, 3> w = mul(kRgbToXyz, 1, 1, 1);
  return w;
}

double srgb_to_linear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

// YCxCz: the linear opponent space of the paper (a CIELab without its cube root), relative to D65.
std::array<double, 3> xyz_to_ycxcz(const std::array<double, 3>& xyz) {
  const auto& n = white();
  const double x = xyz[0] / n[0], y = xyz[1] / n[1], z = xyz[2] / n[2];
  return {116 * y - 16, 500 * (x - y), 200 * (y - z)};
}

std::array<double, 3> ycxcz_to_xyz(double yy, double cx, double cz) {
  const auto& n = white();
  const double y = (yy + 16) / 116;
  return {n[0] * (y + cx / 500), n[1] * y, n[2] * (y - cz / 200)};
}

double lab_f(double t) {
  constexpr double d = 6.0 / 29.0;
  return t > d * d * d ? std::cbrt(t) : t / (3 * d * d) + 4.0 / 29.0;
}

// Linear RGB to Hunt-adjusted CIELab: a and b scaled by L / 100 (darker colours look less chromatic).
std::array<double, 3> linear_rgb_to_hunt_lab(double r, double g, double b) {
  const auto xyz = mul(kRgbToXyz, r, g, b);
  const auto& n = white();
  const double fx = lab_f(xyz[0] / n[0]), fy = lab_f(xyz[1] / n[1]), fz = lab_f(xyz[2] / n[2]);
  const double l = 116 * fy - 16;
  return {l, 0.01 * l * 500 * (fx - fy), 0.01 * l * 200 * (fy - fz)};
}

// HyAB: city-block distance in lightness plus Euclidean distance in chroma.
double hyab(const std::array<double, 3>& p, const std::array<double, 3>& q) {
  const double da = p[1] - q[1], db = p[2] - q[2];
  return std::abs(p[0] - q[0]) + std::sqrt(da * da + db * db);
}

// --- colour pipeline constants (the paper's) ----------------------------------------------------------

constexpr double kQc = 0.7;   // exponent on the HyAB distance
constexpr double kPc = 0.4;   // fraction of cmax where the remapping's two linear pieces meet
constexpr double kPt = 0.95;  // remapped error at that point
constexpr double kQf = 0.5;   // exponent on the feature difference
constexpr double kFeatureWidthDeg = 0.082;  // w: the feature detectors' width in degrees

// Contrast sensitivity as a sum of two Gaussians per opponent channel:
// S(x) = a1 sqrt(pi / b1) exp(-pi^2 x^2 / b1) + a2 sqrt(pi / b2) exp(-pi^2 x^2 / b2), x in degrees.
struct Csf {
  double a1, b1, a2, b2;
};
constexpr std::array<Csf, 3> kCsf = {{{1.0, 0.0047, 0.0, 1e-5},      // achromatic (Y)
                                      {1.0, 0.0053, 0.0, 1e-5},      // red-green (Cx)
                                      {34.1, 0.04, 13.5, 0.025}}};  // blue-yellow (Cz)

// The largest possible colour error: between Hunt-adjusted green and blue, raised to qc.
double cmax() {
  static const double c = std::pow(hyab(linear_rgb_to_hunt_lab(0, 1, 0), linear_rgb_to_hunt_lab(0, 0, 1)), kQc);
  return c;
}

// --- filters -----------------------------------------------------------------------------------------

// One separable term of a channel's CSF: coefficient * (k x k), with k summing to 1.
struct CsfTerm {
  double coefficient;
  Kernel k;
};

struct Filters {
  std::array<std::vector<CsfTerm>, 3> csf;  // per YCxCz channel; the 2D kernel sums to 1
  Kernel gauss;                             // feature detectors' Gaussian, sums to 1
  Kernel edge;                              // its first derivative: positive taps sum to 1, negative to -1
  Kernel point;                             // its second derivative, normalised the same way
};

void normalise_signed(Kernel& k) {
  double pos = 0, neg = 0;
  for (float v : k) (v > 0 ? pos : neg) += v;
  for (float& v : k) v = float(v > 0 ? v / pos : (v < 0 ? v / -neg : 0.0));
}

Filters make_filters(double ppd) {
  Filters f;
  // CSF: one radius for every channel, three standard deviations of the widest Gaussian
  // (exp(-pi^2 x^2 / b) has variance b / (2 pi^2)).
  double bmax = 0;
  for (const Csf& c : kCsf) bmax = std::max({bmax, c.b1, c.b2});
  const int r = std::max(1, int(std::ceil(3 * std::sqrt(bmax / (2 * kPi * kPi)) * ppd)));
  for (int ch = 0; ch < 3; ++ch) {
    const Csf& c = kCsf[ch];
    double total = 0;
    for (auto [a, b] : {std::pair{c.a1, c.b1}, std::pair{c.a2, c.b2}}) {
      if (a == 0) continue;
      Kernel k(2 * r + 1);
      double sum = 0;
      for (int i = -r; i <= r; ++i) {
        const double x = i / ppd;
        sum += k[i + r] = float(std::exp(-kPi * kPi * x * x / b));
      }
      for (float& v : k) v = float(v / sum);
      // The 2D term a sqrt(pi / b) g(x) g(y) sums to a sqrt(pi / b) sum^2 over the window.
      const double weight = a * std::sqrt(kPi / b) * sum * sum;
      f.csf[ch].push_back({weight, std::move(k)});
      total += weight;
    }
    for (CsfTerm& t : f.csf[ch]) t.coefficient /= total;
  }
  // Feature detectors: sigma = w / 2 in pixels, radius 3 sigma. The 2D filters are products of a 1D
  // derivative and a 1D Gaussian, and normalising the 2D positive / negative sums equals normalising each
  // 1D factor, so they stay separable.
  const double sd = 0.5 * kFeatureWidthDeg * ppd;
  const int fr = std::max(1, int(std::ceil(3 * sd)));
  f.gauss.resize(2 * fr + 1);
  f.edge.resize(2 * fr + 1);
  f.point.resize(2 * fr + 1);
  double gsum = 0;
  for (int i = -fr; i <= fr; ++i) {
    const double g = std::exp(-double(i) * i / (2 * sd * sd));
    gsum += f.gauss[i + fr] = float(g);
    f.edge[i + fr] = float(-i * g);
    f.point[i + fr] = float((double(i) * i / (sd * sd) - 1) * g);
  }
  for (float& v : f.gauss) v = float(v / gsum);
  normalise_signed(f.edge);
  normalise_signed(f.point);
  return f;
}

// dst(x, y) = sum_i k[i] src(clamp(x + i - r), y): along rows, clamp-to-edge.
void filter_rows(const float* src, float* dst, int w, int h, const Kernel& k) {
  const int r = int(k.size() / 2);
  std::vector<float> row(size_t(w) + 2 * r);
  for (int y = 0; y < h; ++y) {
    const float* s = src + size_t(y) * w;
    for (int x = -r; x < w + r; ++x) row[x + r] = s[std::clamp(x, 0, w - 1)];
    float* d = dst + size_t(y) * w;
    for (int x = 0; x < w; ++x) {
      float acc = 0;
      for (size_t i = 0; i < k.size(); ++i) acc += k[i] * row[x + i];
      d[x] = acc;
    }
  }
}

// The same along columns.
void filter_cols(const float* src, float* dst, int w, int h, const Kernel& k) {
  const int r = int(k.size() / 2);
  for (int y = 0; y < h; ++y) {
    float* d = dst + size_t(y) * w;
    std::fill(d, d + w, 0.0f);
    for (int i = 0; i < int(k.size()); ++i) {
      const float* s = src + size_t(std::clamp(y + i - r, 0, h - 1)) * w;
      const float ki = k[i];
      for (int x = 0; x < w; ++x) d[x] += ki * s[x];
    }
  }
}

// --- per-image work ----------------------------------------------------------------------------------

struct Prepared {
  std::vector<float> lab;    // [3][H][W] Hunt-adjusted CIELab of the CSF-filtered image
  std::vector<float> edge;   // [H][W] edge-detector magnitude on the achromatic channel
  std::vector<float> point;  // [H][W] point-detector magnitude
};

Prepared prepare(const float* srgb, int w, int h, const Filters& f) {
  const size_t n = size_t(w) * h;
  std::vector<float> opp(3 * n);  // YCxCz
  for (size_t p = 0; p < n; ++p) {
    const auto o = xyz_to_ycxcz(
        mul(kRgbToXyz, srgb_to_linear(srgb[p]), srgb_to_linear(srgb[n + p]), srgb_to_linear(srgb[2 * n + p])));
    for (int c = 0; c < 3; ++c) opp[c * n + p] = float(o[c]);
  }

  // Colour: CSF filtering per opponent channel.
  std::vector<float> filtered(3 * n, 0.0f), tmp(n), term(n);
  for (int c = 0; c < 3; ++c) {
    float* out = filtered.data() + c * n;
    for (const CsfTerm& t : f.csf[c]) {
      filter_rows(opp.data() + c * n, tmp.data(), w, h, t.k);
      filter_cols(tmp.data(), term.data(), w, h, t.k);
      const float co = float(t.coefficient);
      for (size_t p = 0; p < n; ++p) out[p] += co * term[p];
    }
  }
  Prepared out;
  out.lab.resize(3 * n);
  const Mat3& inv = xyz_to_rgb();
  for (size_t p = 0; p < n; ++p) {
    const auto xyz = ycxcz_to_xyz(filtered[p], filtered[n + p], filtered[2 * n + p]);
    const auto rgb = mul(inv, xyz[0], xyz[1], xyz[2]);
    // Filtering can leave the gamut: clamp to [0, 1] linear RGB as the paper does.
    const auto lab = linear_rgb_to_hunt_lab(std::clamp(rgb[0], 0.0, 1.0), std::clamp(rgb[1], 0.0, 1.0),
                                            std::clamp(rgb[2], 0.0, 1.0));
    for (int c = 0; c < 3; ++c) out.lab[c * n + p] = float(lab[c]);
  }

  // Features on the achromatic channel, normalised to [0, 1]: (Y + 16) / 116 (the paper's erratum).
  std::vector<float> y(n);
  for (size_t p = 0; p < n; ++p) y[p] = (opp[p] + 16.0f) / 116.0f;
  std::vector<float> gx(n), ex(n), px(n), a(n), b(n);
  filter_rows(y.data(), gx.data(), w, h, f.gauss);  // smoothed along x, for the y derivatives
  filter_rows(y.data(), ex.data(), w, h, f.edge);
  filter_rows(y.data(), px.data(), w, h, f.point);
  out.edge.resize(n);
  out.point.resize(n);
  filter_cols(ex.data(), a.data(), w, h, f.gauss);
  filter_cols(gx.data(), b.data(), w, h, f.edge);
  for (size_t p = 0; p < n; ++p) out.edge[p] = std::sqrt(a[p] * a[p] + b[p] * b[p]);
  filter_cols(px.data(), a.data(), w, h, f.gauss);
  filter_cols(gx.data(), b.data(), w, h, f.point);
  for (size_t p = 0; p < n; ++p) out.point[p] = std::sqrt(a[p] * a[p] + b[p] * b[p]);
  return out;
}

}  // namespace

double flip_pixels_per_degree(double distance_m, double monitor_width_m, double resolution_x) {
  return distance_m * (resolution_x / monitor_width_m) * (kPi / 180.0);
}

std::vector<float> flip_error_map(const float* test, const float* reference, int width, int height, double ppd,
                                  double* mean) {
  if (!test || !reference) throw std::invalid_argument("flip_error_map: null image");
  if (width <= 0 || height <= 0) throw std::invalid_argument("flip_error_map: empty image");
  if (!(ppd > 0)) throw std::invalid_argument("flip_error_map: pixels per degree must be positive");
  const Filters filters = make_filters(ppd);  // once per call, shared by both images
  const Prepared t = prepare(test, width, height, filters);
  const Prepared r = prepare(reference, width, height, filters);

  const size_t n = size_t(width) * height;
  const double c_max = cmax(), pc_cmax = kPc * c_max;
  std::vector<float> map(n);
  double sum = 0;
  for (size_t p = 0; p < n; ++p) {
    // Colour error: HyAB^qc remapped so that pc * cmax -> pt and cmax -> 1.
    const double de = std::pow(hyab({t.lab[p], t.lab[n + p], t.lab[2 * n + p]},
                                    {r.lab[p], r.lab[n + p], r.lab[2 * n + p]}),
                               kQc);
    double ec = de < pc_cmax ? kPt / pc_cmax * de : kPt + (de - pc_cmax) / (c_max - pc_cmax) * (1 - kPt);
    ec = std::clamp(ec, 0.0, 1.0);
    // Feature error: the larger of the edge and point differences, each at most sqrt(2).
    const double df = std::max(std::abs(double(t.edge[p]) - r.edge[p]), std::abs(double(t.point[p]) - r.point[p]));
    const double ef = std::clamp(std::pow(df / std::numbers::sqrt2, kQf), 0.0, 1.0);
    const double e = std::pow(ec, 1 - ef);
    map[p] = float(e);
    sum += map[p];  // the mean of the map as returned
  }
  if (mean) *mean = sum / double(n);
  return map;
}

double flip_pooled_mean(const std::vector<float>& error_map, const float* weight) {
  if (error_map.empty()) return std::numeric_limits<double>::quiet_NaN();
  double sum = 0, wsum = 0;
  for (size_t p = 0; p < error_map.size(); ++p) {
    const double wt = weight ? double(weight[p]) : 1.0;
    if (!(wt > 0)) continue;
    sum += wt * error_map[p];
    wsum += wt;
  }
  return wsum > 0 ? sum / wsum : std::numeric_limits<double>::quiet_NaN();
}

double flip_mean(const float* test, const float* reference, int width, int height, double ppd,
                 const float* weight) {
  return flip_pooled_mean(flip_error_map(test, reference, width, height, ppd), weight);
}

}  // namespace goris
