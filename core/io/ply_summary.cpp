// `goris info` for a PLY file: what it holds, in a few lines.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/io/ply.h"
#include "core/io/ply_header.h"

namespace goris {
namespace {

std::string fmt(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.4g", v);
  return b;
}

}  // namespace

std::string ply_summary(const std::filesystem::path& path) {
  const ply_detail::FileView file(path);
  ply_detail::PlyHeader h;
  const GaussianPly g = ply_detail::parse_gaussians(file.data(), file.size(), path.string(), h);

  std::string s = path.string() + ": 3D Gaussian PLY (" +
                  (h.format == ply_detail::PlyFormat::ascii ? "ascii" : "binary_little_endian") + ", " +
                  std::to_string(file.size()) + " bytes)\n";
  s += "  " + std::to_string(g.count) + " Gaussians, SH degree " + std::to_string(g.sh_degree) + " (" +
       std::to_string(GaussianPly::rest_per_gaussian(g.sh_degree)) + " f_rest values each)\n";

  bool normals = false;
  for (const auto& e : h.elements)
    if (e.name == "vertex")
      for (const auto& p : e.properties) normals |= p.name == "nx";
  bool all_zero = true;
  for (float v : g.normals) all_zero &= v == 0.0f;
  s += std::string("  normals: ") + (!normals ? "absent" : all_zero ? "present, all zero" : "present") + "\n";

  s += "  extra properties (" + std::to_string(g.extras.size()) + "):";
  if (g.extras.empty()) s += " none";
  for (const auto& e : g.extras) s += " " + e.first;
  s += "\n";
  for (const auto& e : h.elements)
    if (e.name != "vertex")
      s += "  other element (ignored): " + e.name + ", " + std::to_string(e.count) + (e.count == 1 ? " item\n" : " items\n");

  return s + gaussian_stats(g);
}

std::string gaussian_stats(const GaussianPly& g) {
  std::string s;
  if (g.count == 0) return s;
  s += "  position bounds:";
  for (int a = 0; a < 3; ++a) {
    float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
    for (size_t i = 0; i < g.count; ++i) {
      lo = std::min(lo, g.positions[i * 3 + a]);
      hi = std::max(hi, g.positions[i * 3 + a]);
    }
    s += std::string(a ? "  " : " ") + "xyz"[a] + " [" + fmt(lo) + ", " + fmt(hi) + "]";
  }
  double omin = 1, omax = 0, osum = 0;
  for (float o : g.opacity) {
    const double a = 1.0 / (1.0 + std::exp(-double(o)));
    omin = std::min(omin, a);
    omax = std::max(omax, a);
    osum += a;
  }
  s += "\n  opacity after sigmoid: min " + fmt(omin) + ", mean " + fmt(osum / double(g.count)) + ", max " +
       fmt(omax) + "\n";
  return s;
}

}  // namespace goris
