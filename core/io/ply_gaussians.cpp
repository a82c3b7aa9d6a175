// GaussianPly's own checks and the conversion of its SH coefficients to and from the engine's layout.
#include "core/io/ply_header.h"
#include "core/scene/gaussian_view.h"
#include "core/util/error.h"

namespace goris {

const std::vector<float>* GaussianPly::extra(const std::string& name) const {
  for (const auto& [n, v] : extras)
    if (n == name) return &v;
  return nullptr;
}

size_t GaussianPly::rest_per_gaussian(int sh_degree) {
  return 3 * size_t((sh_degree + 1) * (sh_degree + 1) - 1);
}

void GaussianPly::check_consistent(const std::string& what) const {
  if (sh_degree < 0 || sh_degree > 3)
    throw Error(what, "SH degree " + std::to_string(sh_degree) + " is outside 0..3");
  auto check = [&](const std::vector<float>& v, size_t per, const char* field) {
    if (v.size() != count * per)
      throw Error(what, std::string("Gaussian array '") + field + "' holds " + std::to_string(v.size()) +
                            " values, expected " + std::to_string(count) + " x " + std::to_string(per));
  };
  check(positions, 3, "positions");
  if (!normals.empty()) check(normals, 3, "normals");
  check(f_dc, 3, "f_dc");
  check(f_rest, rest_per_gaussian(sh_degree), "f_rest");
  check(opacity, 1, "opacity");
  check(scales, 3, "scales");
  check(rotations, 4, "rotations");
  for (size_t i = 0; i < extras.size(); ++i) {
    const std::string& n = extras[i].first;
    bool printable = !n.empty();
    for (char c : n) printable &= c > 32 && c < 127;
    if (!printable) throw Error(what, "extra property name '" + n + "' is empty or has spaces or control characters");
    if (ply_detail::is_standard_name(n)) throw Error(what, "extra property '" + n + "' has a standard property's name");
    for (size_t j = 0; j < i; ++j)
      if (extras[j].first == n) throw Error(what, "extra property '" + n + "' appears twice");
    check(extras[i].second, 1, n.c_str());
  }
}

std::vector<float> sh_to_engine_layout(const GaussianPly& ply) {
  ply.check_consistent("sh_to_engine_layout");
  const size_t rest = GaussianPly::rest_per_gaussian(ply.sh_degree) / 3;  // coefficients k >= 1 per channel
  std::vector<float> sh(ply.count * kMaxShCoeffs * 3, 0.0f);
  for (size_t i = 0; i < ply.count; ++i) {
    float* dst = &sh[i * kMaxShCoeffs * 3];
    const float* src = &ply.f_rest[i * rest * 3];
    for (int c = 0; c < 3; ++c) {
      dst[c] = ply.f_dc[i * 3 + c];
      for (size_t k = 1; k <= rest; ++k) dst[k * 3 + c] = src[size_t(c) * rest + (k - 1)];
    }
  }
  return sh;
}

void sh_from_engine_layout(std::span<const float> sh, GaussianPly& ply) {
  if (ply.sh_degree < 0 || ply.sh_degree > 3)
    throw Error("sh_from_engine_layout", "SH degree " + std::to_string(ply.sh_degree) + " is outside 0..3");
  if (sh.size() != ply.count * kMaxShCoeffs * 3)
    throw Error("sh_from_engine_layout", "expected " + std::to_string(ply.count) + " x 16 x 3 SH values, got " +
                                             std::to_string(sh.size()));
  const size_t rest = GaussianPly::rest_per_gaussian(ply.sh_degree) / 3;
  ply.f_dc.resize(ply.count * 3);
  ply.f_rest.resize(ply.count * rest * 3);
  for (size_t i = 0; i < ply.count; ++i) {
    const float* src = &sh[i * kMaxShCoeffs * 3];
    float* dst = &ply.f_rest[i * rest * 3];
    for (int c = 0; c < 3; ++c) {
      ply.f_dc[i * 3 + c] = src[c];
      for (size_t k = 1; k <= rest; ++k) dst[size_t(c) * rest + (k - 1)] = src[k * 3 + c];
    }
  }
}

}  // namespace goris
