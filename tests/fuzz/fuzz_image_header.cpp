// libFuzzer target for the image header guard (core/io/image_probe.cpp): any bytes, stored as a file, must
// either pass check_image_header_size, or be refused by it with goris::Error; a PNG or JPEG header that
// passes must give its size to probe_image_size without a decode, within the limits. Anything else (a
// crash, a sanitizer report, a hang, another exception) is a bug.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>

#include "core/io/image.h"
#include "core/util/error.h"

namespace {
const std::filesystem::path& scratch() {
  static const std::filesystem::path p = std::filesystem::temp_directory_path() / ("fuzz_image_header_" + std::to_string(getpid()));
  return p;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::filesystem::path& path = scratch();
  if (FILE* f = std::fopen(path.c_str(), "wb")) {
    if (size) std::fwrite(data, 1, size, f);
    std::fclose(f);
  } else {
    std::abort();
  }
  static const uint8_t kPng[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
  const bool png = size >= 8 && std::memcmp(data, kPng, 8) == 0;
  const bool jpeg = size >= 3 && data[0] == 0xFF && data[1] == 0xD8 && data[2] == 0xFF;
  try {
    goris::check_image_header_size(path);
  } catch (const goris::Error&) {
    return 0;
  }
  if (!png && !jpeg) return 0;  // other formats would be decoded by OpenCV: not this target's code
  try {
    const goris::ImageSize s = goris::probe_image_size(path);
    if (s.width <= 0 || s.height <= 0 || std::uint64_t(s.width) * std::uint64_t(s.height) > goris::kMaxImagePixels)
      std::abort();
  } catch (const goris::Error&) {
  }
  return 0;
}
