// probe_image_size: image dimensions from the header bytes, so that `goris info` and the loaders' mask
// checks need not decode hundreds of images; check_image_header_size: the same header read before a
// decode, so that a small file declaring a huge image is refused instead of allocated.
#include <array>
#include <cstring>
#include <fstream>
#include <optional>
#include <system_error>

#include "core/io/file_bytes.h"
#include "core/io/image.h"
#include "core/util/error.h"

namespace goris {
namespace fs = std::filesystem;

namespace {

uint32_t be32(const uint8_t* p) { return (uint32_t(p[0]) << 24) | (uint32_t(p[1]) << 16) | (uint32_t(p[2]) << 8) | p[3]; }
uint16_t be16(const uint8_t* p) { return uint16_t((p[0] << 8) | p[1]); }

ImageSize checked(const fs::path& path, uint64_t w, uint64_t h) {
  if (w == 0 || h == 0 || w > (1u << 20) || h > (1u << 20))
    throw Error(path.string(), "invalid image size " + std::to_string(w) + "x" + std::to_string(h) + " in the header");
  return {int(w), int(h)};
}

// PNG: 8-byte signature, then the IHDR chunk (length, "IHDR", width, height big-endian).
ImageSize probe_png(const fs::path& path, std::ifstream& in) {
  std::array<uint8_t, 24> b{};
  in.seekg(0);
  if (!in.read(reinterpret_cast<char*>(b.data()), b.size())) throw Error(path.string(), "truncated PNG header");
  if (std::memcmp(b.data() + 12, "IHDR", 4) != 0) throw Error(path.string(), "malformed PNG: first chunk is not IHDR");
  return checked(path, be32(b.data() + 16), be32(b.data() + 20));
}

// JPEG: walk the marker segments up to the first start-of-frame (SOF0..SOF15 except DHT/JPG/DAC).
ImageSize probe_jpeg(const fs::path& path, std::ifstream& in) {
  in.seekg(2);
  while (true) {
    int c = in.get();
    if (c == EOF) break;
    if (c != 0xFF) throw Error(path.string(), "malformed JPEG: expected a marker at byte " + std::to_string(int64_t(in.tellg()) - 1));
    int marker = in.get();
    while (marker == 0xFF) marker = in.get();  // fill bytes
    if (marker == EOF) break;
    if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD7)) continue;  // no length
    if (marker == 0xD9 || marker == 0xDA) break;  // end of image / start of scan before any frame
    uint8_t len_bytes[2];
    if (!in.read(reinterpret_cast<char*>(len_bytes), 2)) break;
    const uint16_t len = be16(len_bytes);
    if (len < 2) throw Error(path.string(), "malformed JPEG: segment length < 2");
    const bool sof = marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
    if (sof) {
      uint8_t f[5];
      if (!in.read(reinterpret_cast<char*>(f), 5)) break;
      return checked(path, be16(f + 3), be16(f + 1));
    }
    in.seekg(len - 2, std::ios::cur);
  }
  throw Error(path.string(), "malformed or truncated JPEG: no frame header found");
}

// The size a PNG or JPEG header declares; nothing for other formats.
std::optional<ImageSize> header_size(const fs::path& path) {
  require_regular_file(path, "image file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path.string(), "cannot open for reading");
  uint8_t sig[8] = {};
  in.read(reinterpret_cast<char*>(sig), 8);
  const size_t got = size_t(in.gcount());
  in.clear();
  static const uint8_t kPng[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
  if (got == 8 && std::memcmp(sig, kPng, 8) == 0) return probe_png(path, in);
  if (got >= 3 && sig[0] == 0xFF && sig[1] == 0xD8 && sig[2] == 0xFF) return probe_jpeg(path, in);
  return std::nullopt;
}

}  // namespace

ImageSize probe_image_size(const fs::path& path) {
  if (const auto s = header_size(path)) return *s;
  const Image im = read_image(path);  // other formats: decode once
  return {im.width, im.height};
}

void check_image_header_size(const fs::path& path) {
  const auto s = header_size(path);
  if (!s) return;
  const std::uint64_t pixels = std::uint64_t(s->width) * std::uint64_t(s->height);
  if (pixels > kMaxImagePixels)
    throw Error(path.string(), "the header declares " + std::to_string(s->width) + "x" + std::to_string(s->height) +
                                   " pixels (" + std::to_string(pixels / 1000000) + " megapixels), more than the limit of " +
                                   std::to_string(kMaxImagePixels / 1000000) +
                                   " megapixels; not decoding it (downscale the file first)");
}

}  // namespace goris
