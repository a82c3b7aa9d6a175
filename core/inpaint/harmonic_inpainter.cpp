#include "core/inpaint/harmonic_inpainter.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace goris {

namespace {

constexpr int kCoarsest = 16;  // below this size a level is started from the onion peel, not a coarser level

// The unknown pixels with their in-image 4-neighbours, split into the two colours of a checkerboard so
// that a sweep over one colour only reads the other (Gauss-Seidel that is order-independent).
struct HoleGraph {
  std::vector<std::uint32_t> pixels[2];
  std::vector<std::uint32_t> nbr_begin[2];  // CSR into nbrs
  std::vector<std::uint32_t> nbrs[2];
  int extent = 1;                           // the larger side of the unknown pixels' bounding box
};

HoleGraph build_graph(const std::vector<std::uint8_t>& unknown, int W, int H) {
  HoleGraph g;
  int x0 = W, x1 = -1, y0 = H, y1 = -1;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      if (!unknown[std::size_t(y) * W + x]) continue;
      x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
      const int colour = (x + y) & 1;
      g.pixels[colour].push_back(std::uint32_t(y) * W + x);
      g.nbr_begin[colour].push_back(std::uint32_t(g.nbrs[colour].size()));
      const int nx[4] = {x - 1, x + 1, x, x}, ny[4] = {y, y, y - 1, y + 1};
      for (int k = 0; k < 4; ++k)
        if (nx[k] >= 0 && nx[k] < W && ny[k] >= 0 && ny[k] < H) g.nbrs[colour].push_back(std::uint32_t(ny[k]) * W + nx[k]);
    }
  for (int c = 0; c < 2; ++c) g.nbr_begin[c].push_back(std::uint32_t(g.nbrs[c].size()));
  if (x1 >= 0) g.extent = std::max(x1 - x0 + 1, y1 - y0 + 1);
  return g;
}

// Onion peel: repeatedly give every unknown pixel next to assigned ones the mean of those, rim inwards.
void onion_init(std::vector<double>& v, const std::vector<std::uint8_t>& unknown, int W, int H) {
  std::vector<std::uint8_t> assigned(unknown.size());
  std::vector<std::uint32_t> front, next;
  for (std::size_t p = 0; p < unknown.size(); ++p) {
    assigned[p] = unknown[p] ? 0 : 1;
    if (unknown[p]) front.push_back(std::uint32_t(p));
  }
  std::vector<std::pair<std::uint32_t, double>> updates;
  while (!front.empty()) {
    next.clear();
    updates.clear();
    for (std::uint32_t p : front) {
      const int x = int(p % W), y = int(p / W);
      const int nx[4] = {x - 1, x + 1, x, x}, ny[4] = {y, y, y - 1, y + 1};
      double sum = 0;
      int n = 0;
      for (int k = 0; k < 4; ++k)
        if (nx[k] >= 0 && nx[k] < W && ny[k] >= 0 && ny[k] < H && assigned[std::size_t(ny[k]) * W + nx[k]]) {
          sum += v[std::size_t(ny[k]) * W + nx[k]];
          ++n;
        }
      if (n > 0) updates.emplace_back(p, sum / n);
      else next.push_back(p);
    }
    if (updates.empty()) break;  // a component with no known pixel: left as it is
    for (const auto& [p, value] : updates) {
      v[p] = value;
      assigned[p] = 1;
    }
    front.swap(next);
  }
}

// Successive over-relaxation of Laplace's equation on the unknown pixels.
void relax(std::vector<double>& v, const HoleGraph& g, double tolerance, int max_sweeps) {
  const double omega = 2.0 / (1.0 + std::sin(3.14159265358979 / double(g.extent + 1)));
  for (int sweep = 0; sweep < max_sweeps; ++sweep) {
    double max_change = 0;
    for (int colour = 0; colour < 2; ++colour) {
      const auto& px = g.pixels[colour];
      const auto& begin = g.nbr_begin[colour];
      const auto& nb = g.nbrs[colour];
      for (std::size_t i = 0; i < px.size(); ++i) {
        if (begin[i + 1] == begin[i]) continue;  // a 1x1 image
        double sum = 0;
        for (std::uint32_t k = begin[i]; k < begin[i + 1]; ++k) sum += v[nb[k]];
        const double change = omega * (sum / double(begin[i + 1] - begin[i]) - v[px[i]]);
        v[px[i]] += change;
        max_change = std::max(max_change, std::fabs(change));
      }
    }
    if (max_change < tolerance) break;
  }
}

// Cascade: solve a half-size problem (a coarse pixel is known when any of its 2x2 fine pixels is, with
// their mean), start the unknown fine pixels from it, relax. Low frequencies converge on the coarse
// levels, where sweeps are cheap, so large holes do not need thousands of fine sweeps.
void solve(std::vector<double>& v, const std::vector<std::uint8_t>& unknown, int W, int H, double tolerance,
           int max_sweeps) {
  if (std::find(unknown.begin(), unknown.end(), std::uint8_t(1)) == unknown.end()) return;
  if (W >= kCoarsest && H >= kCoarsest) {
    const int W2 = (W + 1) / 2, H2 = (H + 1) / 2;
    std::vector<double> cv(std::size_t(W2) * H2, 0.0);
    std::vector<std::uint8_t> cu(std::size_t(W2) * H2, 1);
    std::vector<int> n(std::size_t(W2) * H2, 0);
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x) {
        const std::size_t p = std::size_t(y) * W + x, c = std::size_t(y / 2) * W2 + x / 2;
        if (unknown[p]) continue;
        cv[c] += v[p];
        ++n[c];
        cu[c] = 0;
      }
    for (std::size_t c = 0; c < cv.size(); ++c)
      if (n[c]) cv[c] /= n[c];
    solve(cv, cu, W2, H2, tolerance, max_sweeps);
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x)
        if (unknown[std::size_t(y) * W + x]) v[std::size_t(y) * W + x] = cv[std::size_t(y / 2) * W2 + x / 2];
  } else {
    onion_init(v, unknown, W, H);
  }
  relax(v, build_graph(unknown, W, H), tolerance, max_sweeps);
}

}  // namespace

Image HarmonicInpainter::fill(const Image& encoded, const Mask& hole, const MapInfo& info) const {
  const int W = encoded.width, H = encoded.height, C = encoded.channels;
  const std::size_t n = encoded.pixel_count();
  const std::vector<float> in = encoded.pixels.to_host();
  Image out(W, H, C, Device::CPU);
  out.pixels.upload(in.data(), in.size());
  std::vector<std::uint8_t> unknown(n);
  for (std::size_t p = 0; p < n; ++p) unknown[p] = hole.data[p] ? 1 : 0;
  std::vector<double> v(n);
  for (int c = 0; c < C; ++c) {
    for (std::size_t p = 0; p < n; ++p) v[p] = unknown[p] ? 0.0 : double(in[p * C + c]);
    solve(v, unknown, W, H, tolerance_, max_sweeps_);
    for (std::size_t p = 0; p < n; ++p)
      if (unknown[p]) out.pixels[p * C + c] = float(v[p]);
  }
  (void)info;
  return out;
}

}  // namespace goris
