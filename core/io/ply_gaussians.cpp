// GaussianPly's own checks and the conversion of its SH coefficients to and from the engine's layout.
#include "core/io/ply_header.h"
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

}  // namespace goris
