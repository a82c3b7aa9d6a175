#pragma once
// CLI11 checks for number flags that never wrap and say their limits (core/util/number_text.h):
// whole(min, max) for integer flags - "--seed: must be a whole number from 0 to 18446744073709551615, got
// '-1'" - and real(min, max) for real-valued ones, which refuses NaN and infinity by name. They replace
// CLI11's PositiveNumber / Range, whose conversion lets -1 into an unsigned flag, reads 010 as octal and
// reports the bound of a double in 309 digits.
#include <CLI/CLI.hpp>

#include <cstdint>
#include <limits>
#include <string>

#include "core/util/number_text.h"

namespace goris::cli {

inline CLI::Validator whole(long double min, long double max) {
  return CLI::Validator(
      [min, max](std::string& s) {
        long double v = 0;
        return parse_whole_number(s, min, max, v);
      },
      "INT " + limit_text(min) + ".." + limit_text(max));
}

inline CLI::Validator real(double min, double max) {
  return CLI::Validator(
      [min, max](std::string& s) {
        double v = 0;
        return parse_real_number(s, min, max, v);
      },
      "NUMBER " + limit_text(min) + ".." + limit_text(max));
}

inline constexpr long double kIntMax = std::numeric_limits<int>::max();
inline constexpr long double kSeedMax = std::numeric_limits<std::uint64_t>::max();
inline constexpr double kRealMax = 1e30;  // a bound beyond any sensible factor, but well inside float

}  // namespace goris::cli
