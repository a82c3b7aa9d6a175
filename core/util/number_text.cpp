#include "core/util/number_text.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace goris {

namespace {
std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}
std::string range_text(long double min, long double max) { return "from " + limit_text(min) + " to " + limit_text(max); }
}  // namespace

std::string limit_text(long double v) {
  char b[64];
  if (std::fabs(v) < 2e19L && v == std::floor(v))
    std::snprintf(b, sizeof b, "%.0Lf", v);
  else
    std::snprintf(b, sizeof b, "%.6Lg", v);
  return b;
}

bool names_non_finite_number(const std::string& text) {
  std::string t = lower(text);
  if (!t.empty() && (t[0] == '-' || t[0] == '+')) t.erase(0, 1);
  return t == "nan" || t == "inf" || t == "infinity";
}

std::string parse_whole_number(const std::string& text, long double min, long double max, long double& value) {
  const std::string want = "must be a whole number " + range_text(min, max) + ", got '" + text + "'";
  std::size_t i = 0;
  const bool negative = !text.empty() && text[0] == '-';
  if (negative || (!text.empty() && text[0] == '+')) i = 1;
  if (i >= text.size()) return want;
  long double v = 0;
  for (; i < text.size(); ++i) {
    if (!std::isdigit(static_cast<unsigned char>(text[i]))) return want;
    v = v * 10 + (text[i] - '0');  // exact up to 2^64 in a long double's 64-bit mantissa
  }
  if (negative) v = -v;
  if (v < min || v > max) return want;
  value = v;
  return "";
}

std::string parse_real_number(const std::string& text, double min, double max, double& value) {
  if (names_non_finite_number(text)) return "NaN and infinity are not allowed: a finite number " + range_text(min, max) + " is needed";
  const std::string want = "must be a number " + range_text(min, max) + ", got '" + text + "'";
  if (text.empty() || std::isspace(static_cast<unsigned char>(text[0]))) return want;
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(v)) return want;
  if (v < min || v > max) return want;
  value = v;
  return "";
}

}  // namespace goris
