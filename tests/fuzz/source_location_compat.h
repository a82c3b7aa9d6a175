#pragma once
// Forced into the fuzz build only (./dev fuzz compiles with -include of this file): clang 14 with libstdc++
// 12 has no __builtin_source_location, so <source_location> declares nothing there and
// core/compute/kernel_profile.h would not compile. This supplies std::source_location from the builtins
// clang 14 does have; with any compiler that has the real one it is empty.
#if defined(__clang__) && defined(__has_builtin)
#if !__has_builtin(__builtin_source_location)
#include <cstdint>

namespace std {
struct source_location {
  static constexpr source_location current(const char* file = __builtin_FILE(), const char* function = __builtin_FUNCTION(),
                                           uint_least32_t line = __builtin_LINE(),
                                           uint_least32_t column = __builtin_COLUMN()) noexcept {
    source_location s;
    s.file_ = file;
    s.function_ = function;
    s.line_ = line;
    s.column_ = column;
    return s;
  }
  constexpr source_location() noexcept = default;
  constexpr uint_least32_t line() const noexcept { return line_; }
  constexpr uint_least32_t column() const noexcept { return column_; }
  constexpr const char* file_name() const noexcept { return file_; }
  constexpr const char* function_name() const noexcept { return function_; }

 private:
  const char* file_ = "";
  const char* function_ = "";
  uint_least32_t line_ = 0, column_ = 0;
};
}  // namespace std
#endif
#endif
