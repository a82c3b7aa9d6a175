// libFuzzer target for `--set KEY=VALUE` (train/config/train_config.cpp) and the checked number parsing under
// it (core/util/number_text.h): each input line is one override; any text must apply (leaving a
// configuration that validates or is refused by validate with goris::Error) or be refused with
// goris::Error; the number parsers must return a value within their limits whenever they accept.
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/util/error.h"
#include "core/util/number_text.h"
#include "train/config/train_config.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> sets;
  for (std::size_t a = 0, b; a <= text.size(); a = b + 1) {
    b = text.find('\n', a);
    if (b == std::string::npos) b = text.size();
    sets.push_back(text.substr(a, b - a));
  }
  for (const std::string& s : sets) {
    long double whole = 0;
    if (goris::parse_whole_number(s, -2147483648.0L, 2147483647.0L, whole).empty() &&
        !(whole >= -2147483648.0L && whole <= 2147483647.0L))
      std::abort();
    double real = 0;
    if (goris::parse_real_number(s, -1e30, 1e30, real).empty() && !(real >= -1e30 && real <= 1e30)) std::abort();
  }
  goris::TrainConfig config;
  try {
    goris::apply_config_overrides(sets, config);
    config.validate("fuzz");
  } catch (const goris::Error&) {
  }
  return 0;
}
